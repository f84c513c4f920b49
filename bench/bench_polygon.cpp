// Polygon benchmarks: kBenchPrimitives polygons (5..40 vertices, every
// other one concave) in random planes in [-1, 1]^3.
//   polygon/crossing:     the crossing kernel (packets only);
//   polygon/triangulated: the same polygons ear-clipped into triangles, run
//     through the watertight triangle streams. Its items are the same
//     ray x POLYGON tests as polygon/crossing (not ray x triangle tests), so
//     items_per_second compares per polygon.
// Hit mix: rays toward points of the polygons. Miss mix: rays through the
// cluster that miss every polygon (they reach the planes and often the
// bounding rectangles, unlike rays that miss by t alone).
#include "bench/bench_support.h"
#include "geometry/kind_streams.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver::bench {
namespace {

std::vector<PolygonDesc> bench_polygons(testing::RaySampler& s) {
  std::vector<PolygonDesc> descs;
  for (std::size_t k = 0; k < kBenchPrimitives; ++k) {
    const Vec3<float> normal = s.unit_direction();
    const Vec3<float> e1 =
        normalize(cross(normal, std::abs(normal.x) < 0.9f ? Vec3<float>{1, 0, 0} : Vec3<float>{0, 1, 0}));
    const Vec3<float> e2 = cross(normal, e1);
    const Vec3<float> center = s.in_box({-1, -1, -1}, {1, 1, 1});
    const float radius = s.uniform(0.1f, 0.3f);
    const int count = s.uniform_int(5, 40);
    PolygonDesc d;
    for (int i = 0; i < count; ++i) {
      const float a = 6.2831853f * float(i) / float(count);
      const float r = radius * (k % 2 ? s.uniform(0.4f, 1.f) : 1.f);
      d.vertices.push_back(center + e1 * (r * std::cos(a)) + e2 * (r * std::sin(a)));
    }
    descs.push_back(d);
  }
  return descs;
}

const bool registered = [] {
  testing::RaySampler s(13);
  const std::vector<PolygonDesc> descs = bench_polygons(s);
  BuildReport report;
  auto polygons = std::make_shared<const PolygonSoA>(build_polygons(descs, report));
  std::vector<TriangleDesc> tri_descs;
  for (const PolygonDesc& d : descs) {
    for (const auto& t : triangulate_polygon(d)) tri_descs.push_back({t, std::nullopt, std::nullopt});
  }
  BuildReport tri_report;
  auto triangles = std::make_shared<const TriangleSoA>(build_triangles(tri_descs, tri_report));

  auto rays = std::make_shared<RayMixes>();
  std::vector<Ray<float>> hit_rays, miss_rays;
  for (std::size_t i = 0; i < kBenchRays; ++i) {
    const PolygonDesc& d = descs[std::size_t(s.uniform_int(0, int(descs.size()) - 1))];
    const int k = s.uniform_int(1, int(d.vertices.size()) - 2);
    const float a = s.uniform(0, 0.5f), b = s.uniform(0, 0.5f);
    const Vec3<float> target = d.vertices[0] + (d.vertices[k] - d.vertices[0]) * a + (d.vertices[k + 1] - d.vertices[0]) * b;
    hit_rays.push_back(s.toward(s.in_box({-2, -2, -2}, {2, 2, 2}), target));
  }
  // Rays through the cluster, kept when they miss every polygon (scalar check).
  const auto scalar = study_polygon_streams<KernelUnit::scalar>(PolygonMethod::crossing);
  while (miss_rays.size() < kBenchRays) {
    std::vector<Ray<float>> batch;
    for (int i = 0; i < 1024; ++i) batch.push_back(s.toward(s.in_box({-3, -3, -3}, {3, 3, 3}), s.in_box({-1, -1, -1}, {1, 1, 1})));
    const RaySoA soa = testing::to_soa(batch);
    OcclusionSoA blocked(soa);
    scalar.occluded_packets(soa, *polygons, blocked);
    for (std::size_t i = 0; i < batch.size() && miss_rays.size() < kBenchRays; ++i) {
      if (!blocked.occluded[i]) miss_rays.push_back(batch[i]);
    }
  }
  rays->camera = camera_rays({0, 0, 0}, 1.f);
  rays->hits = testing::to_soa(hit_rays);
  rays->misses = testing::to_soa(miss_rays);

  auto polygon_streams_of = [](auto u, PolygonMethod m) { return study_polygon_streams<decltype(u)::value>(m); };
  register_kernel_benchmarks<PolygonSoA>(
      "polygon/crossing", streams_by_unit<PolygonSoA>(PolygonMethod::crossing, polygon_streams_of), polygons, rays);
  auto triangle_streams_of = [](auto u, TriangleMethod m) { return study_triangle_streams<decltype(u)::value>(m); };
  register_kernel_benchmarks<TriangleSoA>("polygon/triangulated",
                                    streams_by_unit<TriangleSoA>(TriangleMethod::watertight, triangle_streams_of),
                                    triangles, rays, polygons->size());
  return true;
}();

}  // namespace
}  // namespace quiver::bench
