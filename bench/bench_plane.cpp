#include "bench/bench_support.h"
#include "geometry/kind_streams.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver::bench {
namespace {

const bool registered = [] {
  testing::RaySampler s(11);
  std::vector<PlaneDesc> descs;
  for (std::size_t i = 0; i < kBenchPrimitives; ++i) {
    descs.push_back({s.in_box({-1, -1, -1}, {1, 1, 1}), s.unit_direction()});
  }
  BuildReport report;
  auto planes = std::make_shared<const PlaneSoA>(build_planes(descs, report));
  auto rays = std::make_shared<RayMixes>();
  std::vector<Ray<float>> hit_rays, miss_rays;
  for (std::size_t i = 0; i < kBenchRays; ++i) {
    hit_rays.push_back(s.toward(s.in_box({-2, -2, -2}, {2, 2, 2}), s.in_box({-1, -1, -1}, {1, 1, 1})));
    // Short rays (tmax = 1e-3) well away from every plane: all miss.
    Ray<float> r = s.toward(s.in_box({50, 50, 50}, {60, 60, 60}), s.in_box({50, 50, 50}, {60, 60, 60}));
    r.tmax = 1e-3f;
    miss_rays.push_back(r);
  }
  rays->camera = camera_rays({0, 0, 0}, 1.f);
  rays->hits = testing::to_soa(hit_rays);
  rays->misses = testing::to_soa(miss_rays);
  auto streams_of = [](auto u, PlaneMethod m) { return study_plane_streams<decltype(u)::value>(m); };
  register_kernel_benchmarks<PlaneSoA>("plane/seed", streams_by_unit<PlaneSoA>(PlaneMethod::seed, streams_of),
                                       planes, rays);
  register_kernel_benchmarks<PlaneSoA>("plane/anchored",
                                       streams_by_unit<PlaneSoA>(PlaneMethod::anchored, streams_of), planes, rays);
  return true;
}();

}  // namespace
}  // namespace quiver::bench
