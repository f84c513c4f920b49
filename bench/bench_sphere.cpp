#include "bench/bench_support.h"
#include "geometry/kind_streams.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver::bench {
namespace {

const bool registered = [] {
  testing::RaySampler s(13);
  std::vector<SphereDesc> descs;
  for (std::size_t i = 0; i < kBenchPrimitives; ++i) {
    descs.push_back({s.in_box({-1, -1, -1}, {1, 1, 1}), s.uniform(0.05f, 0.3f)});
  }
  BuildReport report;
  auto spheres = std::make_shared<const SphereSoA>(build_spheres(descs, report));
  auto rays = std::make_shared<RayMixes>();
  std::vector<Ray<float>> hit_rays, miss_rays;
  for (std::size_t i = 0; i < kBenchRays; ++i) {
    // Aimed at a sphere's center from outside the cluster: every ray hits.
    const SphereDesc& target = descs[i % descs.size()];
    hit_rays.push_back(s.toward(s.in_box({-3, -3, -3}, {3, 3, 3}) * 2.f, target.center));
    // Rays far from every sphere, pointing away: all miss.
    const Vec3<float> o = s.in_box({50, 50, 50}, {60, 60, 60});
    miss_rays.push_back(s.toward(o, o * 2.f));
  }
  rays->camera = camera_rays({0, 0, 0}, 1.f);
  rays->hits = testing::to_soa(hit_rays);
  rays->misses = testing::to_soa(miss_rays);
  auto streams_of = [](auto u, SphereMethod m) { return study_sphere_streams<decltype(u)::value>(m); };
  for (auto [name, method] : {std::pair{"sphere/algebraic", SphereMethod::algebraic},
                              std::pair{"sphere/geometric", SphereMethod::geometric},
                              std::pair{"sphere/robust", SphereMethod::robust}}) {
    register_kernel_benchmarks<SphereSoA>(name, streams_by_unit<SphereSoA>(method, streams_of), spheres, rays);
  }
  return true;
}();

}  // namespace
}  // namespace quiver::bench
