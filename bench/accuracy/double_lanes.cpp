// The kernel templates of geometry/*.h evaluated with double lanes
// (bench/accuracy/lane64.h), one ray at a time over every primitive of the
// store, closest hit as the streams keep it (strict <, first of equal t).
// Only Lane64 code is instantiated here, so quiver_accuracy may build this
// file with -mfma (std::fma then is one instruction, not a libm call).
#include <stdexcept>

#include "bench/accuracy/lane64.h"
#include "bench/accuracy/methods.h"

namespace quiver::accuracy {
namespace {

void check_kind(const Method& m, const Primitives& prims) {
  if (m.kind != prims.kind) throw std::invalid_argument("method run on another kind");
}

// Closest hit of one ray by kernel method K evaluated in double lanes.
template <class K, class S>
DoubleHit closest_in_double(const Ray<float>& ray, const S& store) {
  const Ray<Lane64> lanes{Vec3<Lane64>(ray.origin), Vec3<Lane64>(ray.direction), Lane64(ray.tmin), Lane64(ray.tmax)};
  const auto prepared = K::prepare(lanes);
  DoubleHit best;
  Lane64 tmax = lanes.tmax;
  for (std::size_t p = 0; p < store.size(); ++p) {
    Candidate<Lane64> c;
    if (K::intersect(prepared, store.template broadcast<Lane64>(p), tmax, true, c)) {
      tmax = c.t;
      best = {true, c.t.value, store.id_base + static_cast<std::int32_t>(p)};
    }
  }
  return best;
}

template <class K, class S>
std::vector<DoubleHit> all_in_double(const RaySoA& rays, const S& store) {
  std::vector<DoubleHit> hits(rays.count);
  for (std::size_t r = 0; r < rays.count; ++r) hits[r] = closest_in_double<K>(rays.get(r), store);
  return hits;
}

}  // namespace

std::vector<DoubleHit> run_double(const Method& method, const RaySoA& rays, const Primitives& prims) {
  check_kind(method, prims);
  switch (method.kind) {
    case Kind::sphere:
      switch (SphereMethod(method.method)) {
        case SphereMethod::algebraic: return all_in_double<SphereAlgebraic>(rays, prims.spheres);
        case SphereMethod::geometric: return all_in_double<SphereGeometric>(rays, prims.spheres);
        case SphereMethod::robust: return all_in_double<SphereRobust>(rays, prims.spheres);
      }
      break;
    case Kind::plane:
      if (PlaneMethod(method.method) == PlaneMethod::seed) return all_in_double<PlaneSeed>(rays, prims.planes);
      return all_in_double<PlaneAnchored>(rays, prims.planes);
    case Kind::triangle:
      if (TriangleMethod(method.method) == TriangleMethod::moller_trumbore) {
        return all_in_double<TriangleMollerTrumbore>(rays, prims.triangles);
      }
      return all_in_double<TriangleWatertight>(rays, prims.triangles);
    case Kind::polygon: return all_in_double<PolygonCrossing>(rays, prims.polygons);
    case Kind::cone: return all_in_double<ConeQuadric>(rays, prims.cones);
  }
  throw std::invalid_argument("unknown method");
}

}  // namespace quiver::accuracy
