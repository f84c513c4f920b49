// Runs a method on a case: kernel units through their streams, and the oracle
// (the double-lane evaluation is in double_lanes.cpp).
#include "bench/accuracy/methods.h"
#include "tests/support/study_streams.h"

#include <stdexcept>
#include <string>


namespace quiver::accuracy {
namespace {

template <class Fn>
decltype(auto) with_store(const Primitives& prims, Fn&& fn) {
  switch (prims.kind) {
    case Kind::sphere: return fn(prims.spheres);
    case Kind::plane: return fn(prims.planes);
    case Kind::triangle: return fn(prims.triangles);
    case Kind::polygon: return fn(prims.polygons);
    case Kind::cone: break;
  }
  return fn(prims.cones);
}

// The stream set of a method in kernel unit U, for store type S.
template <KernelUnit U, class S>
KernelStreams<S> streams_of(const Method& m) {
  if constexpr (std::is_same_v<S, SphereSoA>) return study_sphere_streams<U>(SphereMethod(m.method));
  if constexpr (std::is_same_v<S, PlaneSoA>) return study_plane_streams<U>(PlaneMethod(m.method));
  if constexpr (std::is_same_v<S, TriangleSoA>) return study_triangle_streams<U>(TriangleMethod(m.method));
  if constexpr (std::is_same_v<S, PolygonSoA>) return study_polygon_streams<U>(PolygonMethod(m.method));
  if constexpr (std::is_same_v<S, ConeSoA>) return study_cone_streams<U>(ConeMethod(m.method));
}

template <class S>
KernelStreams<S> streams_for(const Method& m, KernelUnit unit) {
  return with_kernel_unit(unit, [&](auto u) { return streams_of<decltype(u)::value, S>(m); });
}

void check_kind(const Method& m, const Primitives& prims) {
  if (m.kind != prims.kind) throw std::invalid_argument("method " + std::string(m.name) + " run on another kind");
}

}  // namespace

const Method& find_method(std::string_view kind_name, std::string_view name) {
  for (const Method& m : kMethods) {
    if (m.kind_name == kind_name && m.name == name) return m;
  }
  throw std::invalid_argument("no method " + std::string(kind_name) + "/" + std::string(name));
}

std::size_t Primitives::size() const {
  return with_store(*this, [](const auto& store) { return store.size(); });
}

// Runs the stream `pick` chooses from the method's stream set into a Result for the rays.
template <class Result, class Pick>
Result run_stream(const Method& method, KernelUnit unit, const RaySoA& rays, const Primitives& prims, Pick pick) {
  check_kind(method, prims);
  Result result(rays);
  with_store(prims, [&](const auto& store) {
    using S = std::decay_t<decltype(store)>;
    pick(streams_for<S>(method, unit))(rays, store, result);
  });
  return result;
}

HitSoA run_unit(const Method& method, KernelUnit unit, const RaySoA& rays, const Primitives& prims) {
  return run_stream<HitSoA>(method, unit, rays, prims, [](const auto& streams) { return streams.closest_packets; });
}

OcclusionSoA run_unit_occluded(const Method& method, KernelUnit unit, const RaySoA& rays, const Primitives& prims) {
  return run_stream<OcclusionSoA>(method, unit, rays, prims, [](const auto& streams) { return streams.occluded_packets; });
}

std::vector<Reference> run_oracle(const RaySoA& rays, const Primitives& prims) {
  std::vector<Reference> refs(rays.count);
  with_store(prims, [&](const auto& store) {
    for (std::size_t r = 0; r < rays.count; ++r) refs[r] = closest_reference(rays.get(r), store);
  });
  return refs;
}

std::vector<KernelUnit> units_by_width() {
  std::vector<KernelUnit> units;
  for (Isa isa : kIsas) {
    if (isa_supported(isa)) units.push_back(kernel_unit_for(isa));
  }
  return units;
}

}  // namespace quiver::accuracy
