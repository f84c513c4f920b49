// Each kind's product streams for one kernel unit: packets (W rays against
// one primitive) and, for bounded kinds, the BVH walks of node width
// kProductNodeWidth (geometry/bvh/bvh_streams.h), with the method chosen
// for the kind. geometry/kind_streams.cpp defines them; each kernel unit
// compiles it with its own flags and instantiates them for itself. The
// study's methods and node widths: tests/support/study_streams.h.
#pragma once

#include "geometry/bvh/bvh_streams.h"
#include "geometry/kinds.h"
#include "geometry/streams.h"

namespace quiver {

template <class K>
struct KindStreams {
  KernelStreams<typename K::Store> scan;
  BvhStreams<typename K::Store> tree;  // empty for unbounded kinds
};
using ProductStreams = PerKind<KindStreams>;

// A method per kind: the product's unless changed.
template <class K>
struct KindMethod {
  typename K::Method method = K::product_method;
};
using KindMethods = PerKind<KindMethod>;

// The streams of unit U for every kind, with its method in `methods`; a
// method only the study builds throws std::invalid_argument.
template <KernelUnit U>
ProductStreams product_kind_streams(const KindMethods& methods);

// One kind's streams of unit U with `method`.
template <KernelUnit U, class K>
KindStreams<K> product_streams_of(typename K::Method method) {
  KindMethods methods;
  methods.of<K>().method = method;
  return product_kind_streams<U>(methods).template of<K>();
}

}  // namespace quiver
