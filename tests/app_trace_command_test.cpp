// `quiver trace` below the command line (app/trace_command.h): the primary
// rays cover every pixel centre once, in 4x2 groups; hits and t_sum equal a
// brute-force count computed here in double (analytic sphere roots, a
// Moller-Trumbore triangle, a convex quad's plane and edge tests) for a small
// scene with both layers; every SIMD width and thread count gives the same
// hits and the same t_sum bit for bit; the option checks.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "integrator/camera.h"
#include "scene/scene.h"
#include "app/trace_command.h"
#include "simd/isa.h"

namespace quiver {
namespace {

using Vec3d = std::array<double, 3>;

Vec3d to_double(const Vec3<float>& v) { return {v.x, v.y, v.z}; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Three spheres (one glass, so the transmissive layer is used), a triangle
// and a convex quad floor, seen by a 45-degree camera.
SceneDesc small_scene(int width, int height) {
  SceneDesc desc;
  desc.camera = CameraDesc{{0.3f, 1.2f, 6.f}, {0.f, 0.4f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.01f, width, height};
  MaterialDesc matte;
  MaterialDesc glass;
  glass.kt = 0.8f;
  glass.ior = 1.5f;
  desc.materials = {matte, glass};
  desc.spheres = {{{{-1.2f, 0.8f, 0.f}, 0.8f}, 0}, {{{0.9f, 0.6f, 0.7f}, 0.6f}, 1}, {{{0.2f, 1.9f, -1.5f}, 0.5f}, 0}};
  SceneTriangle triangle;
  triangle.triangle.p = {Vec3<float>{-2.4f, 0.1f, 1.2f}, Vec3<float>{-1.3f, 0.2f, 1.6f},
                         Vec3<float>{-1.9f, 1.4f, 1.4f}};
  triangle.material = 0;
  desc.triangles = {triangle};
  ScenePolygon floor;
  floor.polygon.vertices = {{-3.f, 0.f, -3.f}, {-3.f, 0.f, 2.5f}, {3.f, 0.f, 2.5f}, {3.f, 0.f, -3.f}};
  floor.material = 0;
  desc.polygons = {floor};
  return desc;
}

// A closest hit in double; `ambiguous` is set when the ray passes within a
// relative 1e-5 of some primitive's silhouette or edge, where float kernels
// may legitimately decide either way.
struct ReferenceHit {
  double t = std::numeric_limits<double>::infinity();
  bool ambiguous = false;
};

constexpr double kAmbiguityMargin = 1e-5;

void sphere_hit(const Vec3d& o, const Vec3d& d, const Vec3d& c, double r, ReferenceHit& best) {
  // |o + t d - c|^2 = r^2 with unit d: t = b -+ sqrt(b^2 - |oc|^2 + r^2), b = -oc.d.
  const Vec3d oc = sub(o, c);
  const double b = -dot(oc, d);
  const double disc = b * b - (dot(oc, oc) - r * r);
  if (std::fabs(disc) < kAmbiguityMargin * r * r) best.ambiguous = true;
  if (disc < 0.0) return;
  const double root = std::sqrt(disc);
  for (double t : {b - root, b + root}) {
    if (t > 0.0) {
      best.t = std::min(best.t, t);
      return;
    }
  }
}

void triangle_hit(const Vec3d& o, const Vec3d& d, const Vec3d& a, const Vec3d& b, const Vec3d& c, ReferenceHit& best) {
  // Moller-Trumbore: o + t d = a + u (b - a) + v (c - a).
  const Vec3d e1 = sub(b, a), e2 = sub(c, a);
  const Vec3d p = cross(d, e2);
  const double det = dot(e1, p);
  if (std::fabs(det) < 1e-300) return;
  const Vec3d s = sub(o, a);
  const double u = dot(s, p) / det;
  const Vec3d q = cross(s, e1);
  const double v = dot(d, q) / det;
  const double t = dot(e2, q) / det;
  if (!(t > 0.0)) return;
  const double w = 1.0 - u - v;
  // Inside the triangle grown by the margin, and near one of its edges.
  const double lowest = std::min({u, v, w});
  if (lowest > -kAmbiguityMargin && lowest < kAmbiguityMargin) best.ambiguous = true;
  if (u >= 0.0 && v >= 0.0 && w >= 0.0) best.t = std::min(best.t, t);
}

ReferenceHit reference_hit(const SceneDesc& desc, const Ray<float>& ray) {
  const Vec3d o = to_double(ray.origin), d = to_double(ray.direction);
  ReferenceHit best;
  for (const SceneSphere& s : desc.spheres) sphere_hit(o, d, to_double(s.sphere.center), s.sphere.radius, best);
  for (const SceneTriangle& tr : desc.triangles) {
    triangle_hit(o, d, to_double(tr.triangle.p[0]), to_double(tr.triangle.p[1]), to_double(tr.triangle.p[2]), best);
  }
  // The convex quads as two triangles sharing a diagonal: a hit on the
  // diagonal is inside the quad, so the diagonal is no edge to be near.
  for (const ScenePolygon& poly : desc.polygons) {
    const auto& v = poly.polygon.vertices;
    ReferenceHit halves;
    triangle_hit(o, d, to_double(v[0]), to_double(v[1]), to_double(v[2]), halves);
    ReferenceHit other;
    triangle_hit(o, d, to_double(v[0]), to_double(v[2]), to_double(v[3]), other);
    best.t = std::min({best.t, halves.t, other.t});
    // Near an outer edge: the ray's plane point is near the quad's border.
    const double t_plane = [&] {
      const Vec3d n = cross(sub(to_double(v[1]), to_double(v[0])), sub(to_double(v[2]), to_double(v[0])));
      return dot(sub(to_double(v[0]), o), n) / dot(d, n);
    }();
    if (t_plane > 0.0) {
      const Vec3d p = {o[0] + t_plane * d[0], o[1] + t_plane * d[1], o[2] + t_plane * d[2]};
      for (std::size_t k = 0; k < v.size(); ++k) {
        const Vec3d a = to_double(v[k]), b = to_double(v[(k + 1) % v.size()]);
        const Vec3d edge = sub(b, a);
        const double distance = std::sqrt(dot(cross(edge, sub(p, a)), cross(edge, sub(p, a))) / dot(edge, edge));
        if (distance < kAmbiguityMargin * std::sqrt(dot(edge, edge))) best.ambiguous = true;
      }
    }
  }
  return best;
}

std::vector<Isa> supported_isas() {
  std::vector<Isa> isas;
  for (Isa isa : kIsas) {
    if (isa_supported(isa)) isas.push_back(isa);
  }
  return isas;
}

TEST(TraceCommand, TilesCoverTheImageOnce) {
  const std::vector<PixelTile> tiles = pixel_tiles(37, 20, 16);
  ASSERT_EQ(tiles.size(), 6u);  // 3 columns x 2 rows
  std::vector<int> covered(37 * 20, 0);
  for (const PixelTile& t : tiles) {
    for (int y = t.y0; y < t.y0 + t.height; ++y) {
      for (int x = t.x0; x < t.x0 + t.width; ++x) ++covered[y * 37 + x];
    }
  }
  EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; }));
  EXPECT_EQ(tiles.back().width, 5);
  EXPECT_EQ(tiles.back().height, 4);
}

TEST(TraceCommand, TileRaysGoThroughEveryPixelCentreInFourByTwoGroups) {
  const SceneDesc desc = small_scene(37, 20);
  const Camera camera(*desc.camera, 37, 20);
  auto same = [](const Ray<float>& a, const Ray<float>& b) {
    return a.origin.x == b.origin.x && a.origin.y == b.origin.y && a.origin.z == b.origin.z &&
           a.direction.x == b.direction.x && a.direction.y == b.direction.y && a.direction.z == b.direction.z;
  };
  RaySoA rays;
  std::size_t total = 0;
  for (const PixelTile& tile : pixel_tiles(37, 20, kTraceTileSide)) {
    tile_primary_rays(camera, tile, rays);
    ASSERT_EQ(rays.count, std::size_t(tile.width * tile.height));
    total += rays.count;
    // Every pixel centre of the tile appears exactly once.
    std::set<std::pair<int, int>> found;
    for (std::size_t i = 0; i < rays.count; ++i) {
      for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
        for (int x = tile.x0; x < tile.x0 + tile.width; ++x) {
          if (same(rays.get(i), camera.ray(x + 0.5, y + 0.5))) found.insert({x, y});
        }
      }
    }
    EXPECT_EQ(found.size(), rays.count);
    // A whole tile's first packet: pixels (0..3, 0) then (0..3, 1).
    if (tile.width >= 4 && tile.height >= 2) {
      for (int k = 0; k < 8; ++k) {
        EXPECT_TRUE(same(rays.get(std::size_t(k)), camera.ray(tile.x0 + k % 4 + 0.5, tile.y0 + k / 4 + 0.5))) << k;
      }
    }
  }
  EXPECT_EQ(total, 37u * 20u);
}

TEST(TraceCommand, HitsAndDistancesEqualABruteForceCountInDouble) {
  const int width = 64, height = 48;
  const SceneDesc desc = small_scene(width, height);
  const Scene scene = build_scene(desc, {});
  ASSERT_EQ(scene.primitive_count(), 5u);
  ASSERT_GT(scene.transmissive.primitive_count(), 0u);

  const Camera camera(*desc.camera, width, height);
  std::uint64_t hits = 0, ambiguous = 0;
  double t_sum = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const ReferenceHit h = reference_hit(desc, camera.ray(x + 0.5, y + 0.5));
      if (h.ambiguous) ++ambiguous;
      if (std::isfinite(h.t)) {
        ++hits;
        t_sum += h.t;
      }
    }
  }
  // The scene is placed so that no pixel centre grazes a silhouette or edge.
  ASSERT_EQ(ambiguous, 0u);
  ASSERT_GT(hits, std::uint64_t(width * height / 4));  // not trivial: many hits
  ASSERT_LT(hits, std::uint64_t(width * height));      // and some misses

  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    const PrimaryTraceResult r = trace_primary(scene, width, height, isa, 1, 2);
    EXPECT_EQ(r.rays, std::uint64_t(width * height));
    EXPECT_EQ(r.hits, hits);
    // Float kernels against double: a few float ulps of each distance.
    EXPECT_NEAR(r.t_sum, t_sum, 1e-5 * t_sum);
    EXPECT_EQ(r.ms.size(), 2u);
    EXPECT_EQ(r.threads, 1);
  }
}

TEST(TraceCommand, EveryWidthAndThreadCountGivesTheSameHitsBitForBit) {
  const int width = 53, height = 35;  // partial tiles and partial packets
  const Scene scene = build_scene(small_scene(width, height), {});
  const PrimaryTraceResult reference = trace_primary(scene, width, height, Isa::scalar, 1, 1);
  ASSERT_GT(reference.hits, 0u);
  for (Isa isa : supported_isas()) {
    for (int threads : {1, 2}) {
      SCOPED_TRACE(std::string(isa_name(isa)) + " threads " + std::to_string(threads));
      const PrimaryTraceResult r = trace_primary(scene, width, height, isa, threads, 1);
      EXPECT_EQ(r.hits, reference.hits);
      EXPECT_EQ(r.t_sum, reference.t_sum);  // bit for bit, not near
      EXPECT_EQ(r.threads, threads);
    }
  }
}

// Primary rays have no tmax: a ray is occluded exactly when it hits. The
// shuffled order traces the same rays: the same hits, t_sum added in
// another order, and the same for every width and thread count.
TEST(TraceCommand, OccludedAndShuffledQueriesFindTheSameHits) {
  const int width = 53, height = 35;
  const Scene scene = build_scene(small_scene(width, height), {});
  const PrimaryTraceResult tiles = trace_primary(scene, width, height, Isa::scalar, 1, 1);
  const PrimaryTraceResult shuffled_reference = trace_primary(scene, width, height, Isa::scalar, 1, 1, {false, true});
  ASSERT_GT(tiles.hits, 0u);
  ASSERT_LT(tiles.hits, tiles.rays);
  EXPECT_NEAR(shuffled_reference.t_sum, tiles.t_sum, 1e-12 * tiles.t_sum);
  for (Isa isa : supported_isas()) {
    for (int threads : {1, 2}) {
      SCOPED_TRACE(std::string(isa_name(isa)) + " threads " + std::to_string(threads));
      for (const bool shuffled : {false, true}) {
        const PrimaryTraceResult occluded = trace_primary(scene, width, height, isa, threads, 1, {true, shuffled});
        EXPECT_EQ(occluded.rays, tiles.rays);
        EXPECT_EQ(occluded.hits, tiles.hits);
        EXPECT_EQ(occluded.t_sum, 0.0);
      }
      const PrimaryTraceResult shuffled = trace_primary(scene, width, height, isa, threads, 1, {false, true});
      EXPECT_EQ(shuffled.hits, tiles.hits);
      EXPECT_EQ(shuffled.t_sum, shuffled_reference.t_sum);  // one permutation for every width and thread count
    }
  }
  // The shuffled batches hold the tiles' rays, each once, in another order.
  ThreadArena arena(1);
  const Camera camera(scene.camera, width, height);
  const auto flat = [](const std::vector<RaySoA>& batches) {
    std::vector<std::array<float, 6>> rays;
    for (const RaySoA& batch : batches) {
      EXPECT_LE(batch.count, 256u);
      for (std::size_t i = 0; i < batch.count; ++i) {
        const Ray<float> r = batch.get(i);
        rays.push_back({r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z});
      }
    }
    return rays;
  };
  std::vector<std::array<float, 6>> in_tiles = flat(primary_batches(camera, width, height, arena, false));
  std::vector<std::array<float, 6>> in_shuffle = flat(primary_batches(camera, width, height, arena, true));
  ASSERT_EQ(in_tiles.size(), std::size_t(width * height));
  EXPECT_NE(in_tiles, in_shuffle);
  std::sort(in_tiles.begin(), in_tiles.end());
  std::sort(in_shuffle.begin(), in_shuffle.end());
  EXPECT_EQ(in_tiles, in_shuffle);
  const std::string line = trace_json_line(tiles, scene, width, height, 1.0, {true, true});
  EXPECT_NE(line.find("\"query\":\"occluded\",\"order\":\"shuffled\""), std::string::npos) << line;
  EXPECT_NE(trace_json_line(tiles, scene, width, height, 1.0).find("\"query\":\"closest\",\"order\":\"tiles\""),
            std::string::npos);
}

TEST(TraceCommand, TheJsonLineHasTheKeysAndTheMedians) {
  const Scene scene = build_scene(small_scene(8, 6), {});
  PrimaryTraceResult r;
  r.rays = 48;
  r.hits = 20;
  r.t_sum = 101.5;
  r.ms = {4.0, 1.0, 2.0};
  r.threads = 2;
  r.isa = Isa::sse4;
  const std::string line = trace_json_line(r, scene, 8, 6, 3.25);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  for (const char* key : {"\"mrays_per_s\":0.024", "\"hits\":20", "\"t_sum\":101.5", "\"rays\":48", "\"ms_median\":2.0",
                          "\"threads\":2", "\"simd\":\"sse4\"", "\"lanes\":4", "\"build_ms\":3.25", "\"width\":8",
                          "\"height\":6", "\"repeat\":3", "\"primitives\":5", "\"acceleration_bytes\":"}) {
    EXPECT_NE(line.find(key), std::string::npos) << key << " in " << line;
  }
}

TEST(TraceCommand, TheMedianOfAnEvenCountIsTheMeanOfTheMiddleTwo) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({7.0}), 7.0);
  EXPECT_EQ(median({9.0, 1.0, 4.0}), 4.0);
  EXPECT_EQ(median({10.0, 1.0, 3.0, 2.0}), 2.5);  // sorted 1 2 3 10
  EXPECT_EQ(median({6.0, 2.0}), 4.0);
}

TEST(TraceCommand, OptionChecks) {
  TraceOptions ok;
  EXPECT_NO_THROW(check_trace_options(ok));
  TraceOptions bad = ok;
  bad.repeat = 0;
  EXPECT_THROW(check_trace_options(bad), UsageError);
  bad = ok;
  bad.repeat = kMaxTraceRepeat + 1;
  EXPECT_THROW(check_trace_options(bad), UsageError);
  bad.repeat = kMaxTraceRepeat;  // the bound itself
  EXPECT_NO_THROW(check_trace_options(bad));
  bad.repeat = 1;
  EXPECT_NO_THROW(check_trace_options(bad));
  bad = ok;
  bad.threads = -1;
  EXPECT_THROW(check_trace_options(bad), UsageError);
  bad = ok;
  bad.width = 0;
  EXPECT_THROW(check_trace_options(bad), UsageError);
  bad = ok;
  bad.crease_angle = 181.0;
  EXPECT_THROW(check_trace_options(bad), UsageError);
  bad.crease_angle = 180.0;
  EXPECT_NO_THROW(check_trace_options(bad));

  TraceOptions size = ok;
  size.width = 4096;
  size.height = 4096;  // 2^24: the largest allowed
  EXPECT_EQ(trace_image_size(size, std::nullopt), std::make_pair(4096, 4096));
  size.height = 4097;
  EXPECT_THROW(trace_image_size(size, std::nullopt), UsageError);
  // Without flags: the camera's resolution, else 512 square.
  const SceneDesc desc = small_scene(40, 30);
  EXPECT_EQ(trace_image_size(ok, desc.camera), std::make_pair(40, 30));
  EXPECT_EQ(trace_image_size(ok, std::nullopt), std::make_pair(kDefaultImageSide, kDefaultImageSide));
}

}  // namespace
}  // namespace quiver
