// The one list of primitive kinds a scene stores. Each kind is described
// once, next to its store (geometry/kinds/<kind>.h): a struct with its name
// and plural, whether it is bounded (BVH-indexed), its
// method enum and the product's method, its description, store and
// builder. Whatever is done per kind (building the stores, numbering hits,
// the intersector's queries, surface mapping, reports) iterates this list
// or dispatches on a tag (its position here) through it; adding a kind adds
// one entry here.
#pragma once

#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include "geometry/kinds/cone.h"
#include "geometry/kinds/plane.h"
#include "geometry/kinds/polygon.h"
#include "geometry/primitive_kind.h"
#include "geometry/kinds/sphere.h"
#include "geometry/kinds/triangle.h"

namespace quiver {

template <class... Kinds>
struct KindList {
  static constexpr std::size_t size = sizeof...(Kinds);
};

// In tag order: a store's hit ids, AOV kinds and tables follow it.
using PrimitiveKinds = KindList<SphereKind, PlaneKind, TriangleKind, PolygonKind, ConeKind>;
inline constexpr std::size_t kKindCount = PrimitiveKinds::size;

template <class K, class... Kinds>
constexpr std::size_t position_in(KindList<Kinds...>) {
  std::size_t i = 0, at = sizeof...(Kinds);
  ((std::is_same_v<K, Kinds> ? (at = i, ++i) : ++i), ...);
  return at;
}

// A kind's tag: its position in the list.
template <class K>
inline constexpr PrimitiveKind kind_tag = static_cast<PrimitiveKind>(position_in<K>(PrimitiveKinds{}));

// Index of a kind's entries in per-kind arrays.
constexpr std::size_t kind_index(PrimitiveKind tag) { return static_cast<std::size_t>(tag); }

// fn(K{}) for each kind, in list order.
template <class Fn>
constexpr void for_each_kind(Fn&& fn) {
  [&]<class... Kinds>(KindList<Kinds...>) { (fn(Kinds{}), ...); }(PrimitiveKinds{});
}

template <class Fn, class K, class... Rest>
decltype(auto) visit_kind_in(PrimitiveKind tag, Fn& fn, KindList<K, Rest...>) {
  if constexpr (sizeof...(Rest) == 0) {
    return fn(K{});  // the last kind: the tag is its
  } else {
    if (tag == kind_tag<K>) return fn(K{});
    return visit_kind_in(tag, fn, KindList<Rest...>{});
  }
}

// fn(K{}) for the kind tagged `tag` (one of the list's); fn returns the
// same type for every kind.
template <class Fn>
decltype(auto) visit_kind(PrimitiveKind tag, Fn&& fn) {
  return visit_kind_in(tag, fn, PrimitiveKinds{});
}

// One T<K> per kind of the list.
template <template <class> class T>
class PerKind {
 public:
  template <class K>
  T<K>& of() {
    return std::get<T<K>>(items_);
  }
  template <class K>
  const T<K>& of() const {
    return std::get<T<K>>(items_);
  }
  // fn(K{}, of<K>()) for each kind, in list order.
  template <class Fn>
  void for_each(Fn&& fn) {
    std::apply([&](auto&... item) { (fn(kind_of(item), item), ...); }, items_);
  }
  template <class Fn>
  void for_each(Fn&& fn) const {
    std::apply([&](const auto&... item) { (fn(kind_of(item), item), ...); }, items_);
  }

 private:
  template <class K>
  static K kind_of(const T<K>&) {
    return {};
  }
  template <class>
  struct Items;
  template <class... Kinds>
  struct Items<KindList<Kinds...>> {
    using type = std::tuple<T<Kinds>...>;
  };
  typename Items<PrimitiveKinds>::type items_;
};

}  // namespace quiver
