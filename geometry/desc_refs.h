// The descriptions a store's builder reads, by reference: a scene hands its
// own entries to the builders (a layer's share of them, in its order), not
// copies, so a large mesh is not held twice while its store is built. Any
// contiguous list of descriptions converts to its references, in order.
#pragma once

#include <cstddef>
#include <iterator>
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
  bool empty() const { return refs_.empty(); }
  const Desc& operator[](std::size_t i) const { return *refs_[i]; }

  // Iterates the descriptions (not the pointers).
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Desc;
    using difference_type = std::ptrdiff_t;
    using pointer = const Desc*;
    using reference = const Desc&;
    Iterator() = default;
    explicit Iterator(const Desc* const* at) : at_(at) {}
    const Desc& operator*() const { return **at_; }
    Iterator& operator++() {
      ++at_;
      return *this;
    }
    Iterator operator++(int) {
      Iterator before = *this;
      ++at_;
      return before;
    }
    bool operator==(const Iterator&) const = default;

   private:
    const Desc* const* at_ = nullptr;
  };
  Iterator begin() const { return Iterator(refs_.data()); }
  Iterator end() const { return Iterator(refs_.data() + refs_.size()); }

 private:
  std::vector<const Desc*> refs_;
};

}  // namespace quiver
