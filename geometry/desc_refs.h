// The descriptions a store's builder reads, by reference: a scene hands its
// own entries to the builders (a layer's share of them, in its order), not
// copies, so a large mesh is not held twice while its store is built. Any
// contiguous list of descriptions converts to its references, in order.
#pragma once

#include <cstddef>
#include <ranges>
#include <vector>

namespace quiver {

template <class Desc>
class DescRefs {
 public:
  DescRefs() = default;
  template <std::ranges::contiguous_range List>
    requires std::same_as<std::ranges::range_value_t<List>, Desc>
  DescRefs(const List& list) {  // NOLINT: implicit, as a span converts
    refs_.reserve(std::ranges::size(list));
    for (const Desc& d : list) refs_.push_back(&d);
  }

  void reserve(std::size_t n) { refs_.reserve(n); }
  void push_back(const Desc& d) { refs_.push_back(&d); }
  std::size_t size() const { return refs_.size(); }
  const Desc& operator[](std::size_t i) const { return *refs_[i]; }

 private:
  std::vector<const Desc*> refs_;
};

}  // namespace quiver
