#include "bench/bench_support.h"
#include "geometry/kind_streams.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver::bench {
namespace {

const bool registered = [] {
  testing::RaySampler s(13);
  // Thin cylinders, truncated cones and full cones in [-1, 1]^3, a third each.
  std::vector<ConeDesc> descs;
  for (std::size_t i = 0; i < kBenchPrimitives; ++i) {
    const Vec3<float> base = s.in_box({-1, -1, -1}, {1, 1, 1});
    const Vec3<float> apex = base + s.unit_direction() * s.uniform(0.3f, 1.f);
    const float r0 = s.uniform(0.05f, 0.2f);
    const float r1 = i % 3 == 0 ? r0 : (i % 3 == 1 ? s.uniform(0.02f, 0.3f) : 0.f);
    descs.push_back({base, r0, apex, r1});
  }
  BuildReport report;
  auto cones = std::make_shared<const ConeSoA>(build_cones(descs, report));
  auto rays = std::make_shared<RayMixes>();
  std::vector<Ray<float>> hit_rays, miss_rays;
  for (std::size_t i = 0; i < kBenchRays; ++i) {
    // Aimed at the middle of a random cone's axis: hits it (and often others).
    const ConeDesc& c = descs[static_cast<std::size_t>(s.uniform_int(0, int(kBenchPrimitives) - 1))];
    const Vec3<float> mid = c.base + (c.apex - c.base) * s.uniform(0.2f, 0.8f);
    hit_rays.push_back(s.toward(s.in_box({-3, -3, -3}, {3, 3, 3}), mid));
    // Rays among points of a far box whose lines pass nowhere near the cones.
    miss_rays.push_back(s.toward(s.in_box({50, 50, 50}, {60, 60, 60}), s.in_box({50, 50, 50}, {60, 60, 60})));
  }
  rays->camera = camera_rays({0, 0, 0}, 1.f);
  rays->hits = testing::to_soa(hit_rays);
  rays->misses = testing::to_soa(miss_rays);
  auto streams_of = [](auto u, ConeMethod m) { return study_cone_streams<decltype(u)::value>(m); };
  register_kernel_benchmarks<ConeSoA>("cone/quadric", streams_by_unit<ConeSoA>(ConeMethod::quadric, streams_of),
                                      cones, rays);
  return true;
}();

}  // namespace
}  // namespace quiver::bench
