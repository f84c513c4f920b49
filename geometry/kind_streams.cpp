// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/kind_streams.h"

namespace quiver {

namespace {

template <KernelUnit U, class K>
KindStreams<K> streams_of(typename K::Method method) {
  return with_product_method(method, [](auto kernel) {
    using Kernel = decltype(kernel);
    KindStreams<K> s;
    s.scan = make_packet_streams<U, Kernel, typename K::Store>();
    if constexpr (K::bounded) s.tree = make_bvh_streams<U, Kernel, typename K::Store>();
    return s;
  });
}

}  // namespace

template <KernelUnit U>
ProductStreams product_kind_streams(const KindMethods& methods) {
  ProductStreams streams;
  streams.for_each([&]<class K>(K, KindStreams<K>& s) { s = streams_of<U, K>(methods.of<K>().method); });
  return streams;
}

// This unit's instances.
template ProductStreams product_kind_streams<kThisUnit>(const KindMethods&);

}  // namespace quiver
