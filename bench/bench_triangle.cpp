#include "bench/bench_support.h"
#include "geometry/kind_streams.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver::bench {
namespace {

// Vertices within this distance of a triangle's center: a mesh-like size at
// which 52% of the hit mix's rays hit some triangle (measured).
constexpr float kTriangleRadius = 0.4f;

const bool registered = [] {
  testing::RaySampler s(17);
  std::vector<TriangleDesc> descs;
  for (std::size_t i = 0; i < kBenchPrimitives; ++i) {
    const Vec3<float> c = s.in_box({-1, -1, -1}, {1, 1, 1});
    TriangleDesc t;
    for (Vec3<float>& p : t.p) p = c + s.unit_direction() * kTriangleRadius;
    descs.push_back(t);
  }
  BuildReport report;
  auto triangles = std::make_shared<const TriangleSoA>(build_triangles(descs, report));
  auto rays = std::make_shared<RayMixes>();
  std::vector<Ray<float>> hit_rays, miss_rays;
  for (std::size_t i = 0; i < kBenchRays; ++i) {
    // From around the cluster through it.
    hit_rays.push_back(s.toward(s.in_box({-2, -2, -2}, {2, 2, 2}), s.in_box({-1, -1, -1}, {1, 1, 1})));
    // Rays far from every triangle, pointing away: all miss.
    const Vec3<float> o = s.in_box({50, 50, 50}, {60, 60, 60});
    miss_rays.push_back(s.toward(o, o * 2.f));
  }
  rays->camera = camera_rays({0, 0, 0}, 1.f);
  rays->hits = testing::to_soa(hit_rays);
  rays->misses = testing::to_soa(miss_rays);
  auto streams_of = [](auto u, TriangleMethod m) { return study_triangle_streams<decltype(u)::value>(m); };
  for (auto [name, method] : {std::pair{"triangle/moller_trumbore", TriangleMethod::moller_trumbore},
                              std::pair{"triangle/watertight", TriangleMethod::watertight}}) {
    register_kernel_benchmarks<TriangleSoA>(name, streams_by_unit<TriangleSoA>(method, streams_of), triangles,
                                            rays);
  }
  return true;
}();

}  // namespace
}  // namespace quiver::bench
