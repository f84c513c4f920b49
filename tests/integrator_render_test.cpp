// Whole-image checks of the Whitted renderer: every kernel unit and thread
// count gives the same bits; depth 0/1/2 differ where, and only where,
// mirrors are; transparent shadows attenuate by kt times colour per surface;
// no acne when the scene is scaled by 1e-4 or 1e6; lane statistics add up;
// an OBJ mesh without normals shades smoothly across its face edges.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "scene/default_scene.h"
#include "integrator/camera.h"
#include "integrator/render.h"
#include "io/nff_reader.h"
#include "io/obj_reader.h"
#include "scene/auto_view.h"
#include "tests/support/checker_floor.h"
#include "tests/support/same_bits.h"

namespace quiver {
namespace {

constexpr KernelUnit kUnits[] = {KernelUnit::scalar_fma, KernelUnit::sse4, KernelUnit::avx2, KernelUnit::avx512};

RenderSettings small_settings(int w, int h, const char* aa = "none") {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.aa = parse_anti_aliasing(aa);
  s.threads = 2;
  s.aov_depth = s.aov_normal = s.aov_id = true;
  return s;
}

using quiver::testing::same_bits;

// A smooth octahedron with per-vertex normals and UVs, textured.
void add_octahedron(SceneDesc& scene, const Vec3<float>& c, float r, std::size_t material) {
  const Vec3<float> p[6] = {{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : faces) {
    TriangleDesc t;
    std::array<Vec3<float>, 3> normals;
    std::array<std::array<float, 2>, 3> uvs;
    for (int k = 0; k < 3; ++k) {
      t.p[k] = c + p[f[k]];
      normals[k] = p[f[k]];
      uvs[k] = {0.5f + 0.5f * p[f[k]].x / r, 0.5f + 0.5f * p[f[k]].y / r};
    }
    t.normals = normals;
    t.uvs = uvs;
    scene.triangles.push_back({t, material});
  }
}

// The default scene (every kind, a rectangle light) plus a textured smooth
// triangle mesh and a sphere light: every primitive and light kind.
SceneDesc every_kind_scene() {
  SceneDesc scene = default_scene();
  add_octahedron(scene, {2.6f, 0.6f, 0.5f}, 0.6f, 3);
  LightDesc bulb;
  bulb.kind = LightDesc::Kind::sphere;
  bulb.position = {-2.f, 3.f, 2.f};
  bulb.radius = 0.4f;
  bulb.color = {0.3f, 0.3f, 0.25f};
  bulb.samples = 2;
  scene.lights.push_back(bulb);
  return scene;
}

SceneDesc nff_scene() {
  return read_nff(std::string(QUIVER_TEST_DATA_DIR) + "/nff/every_entity.nff");
}

void expect_same_image(const Framebuffer& a, const Framebuffer& b, const std::string& what) {
  EXPECT_TRUE(same_bits(a.rgb, b.rgb)) << what << ": colour";
  EXPECT_TRUE(same_bits(a.depth, b.depth)) << what << ": depth";
  EXPECT_TRUE(same_bits(a.normal, b.normal)) << what << ": normal";
  EXPECT_EQ(a.kind, b.kind) << what << ": kind";
  EXPECT_EQ(a.id, b.id) << what << ": id";
}

TEST(Render, PixelGroupsVisitEveryPixelOnceInFourByFourGroups) {
  // A 17 x 5 region at (3, 7): full groups, then a 1-wide column and a 1-high row.
  const int x0 = 3, y0 = 7, x1 = 20, y1 = 12;
  std::vector<std::pair<int, int>> order;
  for_each_pixel_in_groups(x0, y0, x1, y1, [&](int x, int y) { order.emplace_back(x, y); });
  ASSERT_EQ(order.size(), std::size_t((x1 - x0) * (y1 - y0)));
  std::vector<int> visits(order.size(), 0);
  for (const auto& [x, y] : order) {
    ASSERT_TRUE(x >= x0 && x < x1 && y >= y0 && y < y1) << x << ", " << y;
    ++visits[std::size_t((y - y0) * (x1 - x0) + (x - x0))];
  }
  EXPECT_TRUE(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
  // The first 16 samples are a 4 x 4 footprint (an 8-wide packet: its upper
  // 4 x 2), the next 16 the group to its right.
  for (int k = 0; k < 32; ++k) {
    EXPECT_EQ(order[std::size_t(k)], std::make_pair(x0 + 4 * (k / 16) + k % 4, y0 + (k % 16) / 4)) << k;
  }
  // The first group row ends with the 1-wide column (x = 19, rows 7 to 10),
  // and the last group row is 1 high.
  for (int row = 0; row < 4; ++row) EXPECT_EQ(order[std::size_t(64 + row)], std::make_pair(19, 7 + row)) << row;
  EXPECT_EQ(order.back(), std::make_pair(19, 11));
  EXPECT_EQ(order[order.size() - 2], std::make_pair(18, 11));
}

// Each unit against the scalar reference, one test per unit (skipped, with
// the reason, where this CPU cannot run it).
class RenderUnits : public ::testing::TestWithParam<KernelUnit> {};

TEST_P(RenderUnits, GiveTheScalarReferenceBits) {
  const KernelUnit unit = GetParam();
  if (!kernel_unit_supported(unit)) GTEST_SKIP() << "this CPU cannot run " << kernel_unit_name(unit);
  const struct {
    const char* name;
    SceneDesc desc;
    const char* aa;
  } cases[] = {{"default+mesh", every_kind_scene(), "jitter:2"},
               {"every_entity.nff", nff_scene(), "adaptive:0.05:2"},
               {"default corners", default_scene(), "corners"},
               {"default refine", default_scene(), "refine:0.02:4"}};
  SceneBuildOptions every_store_indexed;
  every_store_indexed.bvh_min_primitives = 1;
  for (const auto& c : cases) {
    for (const SceneBuildOptions& options : {SceneBuildOptions{}, every_store_indexed}) {
      const Scene scene = build_scene(c.desc, options);
      RenderSettings settings = small_settings(48, 36, c.aa);
      settings.isa = Isa::scalar;
      settings.threads = 1;
      const RenderResult reference = render(scene, settings);
      ASSERT_GT(reference.stats.rays.primary_hits, 0u) << c.name;
      settings.isa = isa_of(unit);
      settings.threads = 2;
      const RenderResult r = render(scene, settings);
      expect_same_image(reference.image, r.image, std::string(c.name) + " at " + std::string(kernel_unit_name(unit)));
      EXPECT_EQ(r.stats.rays.total(), reference.stats.rays.total()) << c.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryUnit, RenderUnits, ::testing::ValuesIn(kUnits),
                         [](const ::testing::TestParamInfo<KernelUnit>& info) {
                           return std::string(kernel_unit_name(info.param));
                         });

// A coarse UV sphere (12 segments, 6 rings) as OBJ text without `vn`.
std::string coarse_sphere_obj() {
  constexpr int kSegments = 12, kRings = 6;
  const double pi = 3.141592653589793;
  std::string text = "v 0 1 0\n";
  for (int r = 1; r < kRings; ++r) {
    for (int s = 0; s < kSegments; ++s) {
      const double theta = pi * r / kRings, phi = 2.0 * pi * s / kSegments;
      text += "v " + std::to_string(std::sin(theta) * std::cos(phi)) + " " + std::to_string(std::cos(theta)) + " " +
              std::to_string(std::sin(theta) * std::sin(phi)) + "\n";
    }
  }
  text += "v 0 -1 0\n";
  const auto ring = [&](int r, int s) { return std::to_string(2 + (r - 1) * kSegments + s % kSegments); };
  const std::string south = std::to_string(2 + (kRings - 1) * kSegments);
  for (int s = 0; s < kSegments; ++s) {
    text += "f 1 " + ring(1, s + 1) + " " + ring(1, s) + "\n";
    for (int r = 1; r + 1 < kRings; ++r) {
      text += "f " + ring(r, s) + " " + ring(r, s + 1) + " " + ring(r + 1, s + 1) + " " + ring(r + 1, s) + "\n";
    }
    text += "f " + south + " " + ring(kRings - 1, s) + " " + ring(kRings - 1, s + 1) + "\n";
  }
  return text;
}

// The largest change of brightness between neighbouring pixels of the
// middle row, among pixels 3 or more from the silhouette (the sphere
// covers them and their 3 neighbours either side).
float largest_step_across_the_middle_row(const Framebuffer& image) {
  const int y = image.height / 2;
  const auto covered = [&](int x) { return std::isfinite(image.depth[std::size_t(y * image.width + x)]); };
  const auto brightness = [&](int x) {
    const std::size_t i = 3 * std::size_t(y * image.width + x);
    return image.rgb[i] + image.rgb[i + 1] + image.rgb[i + 2];
  };
  float step = 0.f;
  for (int x = 3; x + 4 < image.width; ++x) {
    bool inside = true;
    for (int d = -3; d <= 4; ++d) inside = inside && covered(x + d);
    if (inside) step = std::max(step, std::fabs(brightness(x + 1) - brightness(x)));
  }
  return step;
}

// Before smooth normals an OBJ without `vn` rendered faceted: brightness
// jumps where the row crosses a face edge. Smoothed (the default crease
// angle; the sphere's faces meet at 30 degrees), it changes gradually.
// The AOVs describe the first surface each pixel's centre ray hits: of two
// unit spheres, the id names the one whose surface holds the point at the
// depth along the ray, the kind is the sphere's, and the normal is that
// point's direction from the sphere's centre; a miss is infinitely deep,
// of no kind and id -1, with a zero normal.
TEST(Render, AovsDescribeTheFirstSurface) {
  SceneDesc desc;
  desc.camera = CameraDesc{{0.3f, 0.4f, 6.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 50.f, 0.f, 24, 24};
  desc.materials = {MaterialDesc{}};
  const Vec3<float> centres[2] = {{-1.2f, 0.f, 0.f}, {1.2f, 0.2f, -0.5f}};
  for (const Vec3<float>& c : centres) desc.spheres.push_back({{c, 1.f}, 0});
  const Scene scene = build_scene(desc, {});
  const Camera camera(*desc.camera, 24, 24);
  for (Isa isa : {Isa::scalar, best_supported_isa()}) {
    SCOPED_TRACE(isa_name(isa));
    RenderSettings settings = small_settings(24, 24);
    settings.isa = isa;
    const Framebuffer image = render(scene, settings).image;
    int covered[2] = {0, 0};
    for (int y = 0; y < 24; ++y) {
      for (int x = 0; x < 24; ++x) {
        const std::size_t p = std::size_t(y) * 24 + std::size_t(x);
        if (!std::isfinite(image.depth[p])) {
          EXPECT_EQ(image.kind[p], kNoKind) << x << ", " << y;
          EXPECT_EQ(image.id[p], -1) << x << ", " << y;
          for (int a = 0; a < 3; ++a) EXPECT_EQ(image.normal[3 * p + std::size_t(a)], 0.f) << x << ", " << y;
          continue;
        }
        EXPECT_EQ(image.kind[p], static_cast<std::int32_t>(kind_tag<SphereKind>)) << x << ", " << y;
        ASSERT_TRUE(image.id[p] == 0 || image.id[p] == 1) << image.id[p];
        ++covered[image.id[p]];
        const Ray<float> ray = camera.ray(x + 0.5, y + 0.5);
        const Vec3<float> outward = ray.origin + ray.direction * image.depth[p] - centres[image.id[p]];
        EXPECT_NEAR(length(outward), 1.f, 1e-5f) << x << ", " << y;
        for (int a = 0; a < 3; ++a) {
          EXPECT_NEAR(image.normal[3 * p + std::size_t(a)], outward[a], 1e-5f) << x << ", " << y;
        }
      }
    }
    EXPECT_GT(covered[0], 30);
    EXPECT_GT(covered[1], 30);
  }
}

TEST(Render, AnObjMeshWithoutNormalsShadesSmoothlyAcrossFaceEdges) {
  const std::string obj = coarse_sphere_obj();
  const auto no_library = [](std::string_view) -> std::optional<MtlLibrary> { return std::nullopt; };
  float steps[2] = {0.f, 0.f};
  for (const bool smooth : {false, true}) {
    SceneDesc desc = parse_obj_scene(obj, "sphere.obj", no_library, smooth ? kDefaultCreaseAngleDegrees : 0.0);
    add_default_view(desc, 96, 96);
    const Scene scene = build_scene(desc, {});
    RenderSettings settings = small_settings(96, 96);
    settings.isa = Isa::scalar;
    const RenderResult reference = render(scene, settings);
    steps[smooth] = largest_step_across_the_middle_row(reference.image);
    // The smoothed normals render alike at every width.
    for (const KernelUnit unit : kUnits) {
      if (!kernel_unit_supported(unit)) continue;
      settings.isa = isa_of(unit);
      expect_same_image(reference.image, render(scene, settings).image, std::string(kernel_unit_name(unit)));
    }
  }
  EXPECT_GT(steps[0], 0.05f);             // faceted: a visible jump at an edge
  EXPECT_LT(steps[1], 0.25f * steps[0]);  // smooth: no jump
}

TEST(Render, BvhGivesTheSameImageAsScanning) {
  // Hit ids differ (a BVH reorders its store); everything seen does not.
  SceneDesc crowded = every_kind_scene();
  for (int i = 0; i < 40; ++i) {
    const float x = -3.f + 0.15f * static_cast<float>(i);
    add_octahedron(crowded, {x, 0.3f + 0.02f * static_cast<float>(i % 7), 1.5f - 0.1f * static_cast<float>(i % 5)},
                   0.12f, static_cast<std::size_t>(i % 4));
  }
  const struct {
    const char* name;
    SceneDesc desc;
  } cases[] = {{"crowded", crowded}, {"every_entity.nff", nff_scene()}};
  for (const auto& c : cases) {
    SceneBuildOptions scan;
    scan.acceleration = Acceleration::none;
    RenderSettings settings = small_settings(64, 48, "jitter:2");
    const RenderResult reference = render(build_scene(c.desc, scan), settings);
    // The product walks one node width; the walks of the others match the
    // scan hit for hit (geometry_bvh_test.cpp).
    SceneBuildOptions indexed;
    indexed.bvh_min_primitives = 1;
    const Scene scene = build_scene(c.desc, indexed);
    EXPECT_GT(scene.acceleration_bytes(), 0u);
    const RenderResult r = render(scene, settings);
    const std::string what = std::string(c.name) + ", node width " + std::to_string(kProductNodeWidth);
    EXPECT_TRUE(same_bits(reference.image.rgb, r.image.rgb)) << what << ": colour";
    EXPECT_TRUE(same_bits(reference.image.depth, r.image.depth)) << what << ": depth";
    EXPECT_TRUE(same_bits(reference.image.normal, r.image.normal)) << what << ": normal";
    EXPECT_EQ(reference.image.kind, r.image.kind) << what << ": kind";
    EXPECT_EQ(r.stats.rays.total(), reference.stats.rays.total()) << what;
  }
}

TEST(Render, ThreadCountAndTileSizeDoNotChangeTheImage) {
  // Tiles of 16 and 7 cut the 4 x 2 pixel groups (and so the packets) differently.
  const Scene scene = build_scene(every_kind_scene(), {});
  for (const char* aa : {"none", "jitter:2", "corners", "adaptive:0.05:2", "refine:0.02:8"}) {
    RenderSettings settings = small_settings(40, 30, aa);
    settings.isa = best_supported_isa();
    settings.threads = 1;
    settings.tile_size = 16;
    const RenderResult one = render(scene, settings);
    settings.threads = 2;
    settings.tile_size = 7;
    const RenderResult two = render(scene, settings);
    EXPECT_TRUE(same_bits(one.image.rgb, two.image.rgb)) << aa;
    settings.tile_size = 1;  // the smallest tile: a pixel
    const RenderResult pixels = render(scene, settings);
    EXPECT_TRUE(same_bits(one.image.rgb, pixels.image.rgb)) << aa;
  }
}

// Tiles split between renderers (as quiver-mpi splits them between
// processes), each into its own film, then packed and unpacked into one
// film and finished, give render()'s image and ray counts in every
// anti-aliasing mode: corners shares corners between tiles, adaptive shares
// them within a tile, refine reads a one-pixel apron around it.
TEST(Render, TilesSplitBetweenRenderersGiveTheWholeImage) {
  const Scene scene = build_scene(every_kind_scene(), {});
  for (const char* aa :
       {"none", "grid:2", "jitter:2", "corners", "adaptive:0.05:2", "refine:0.02:8", "refine:0.02:8:grid"}) {
    RenderSettings settings = small_settings(45, 37, aa);  // partial tiles at the right and bottom
    settings.isa = best_supported_isa();
    settings.tile_size = 8;
    const RenderResult whole = render(scene, settings);

    constexpr std::size_t kParts = 3;
    FrameRenderer gather(scene, settings);
    Film film = gather.make_film();
    std::size_t tiles_rendered = 0;
    RayCounts rays;
    for (std::size_t part = 0; part < kParts; ++part) {
      RenderSettings part_settings = settings;
      part_settings.threads = int(part) + 1;
      part_settings.isa = part == 1 ? Isa::scalar : best_supported_isa();
      FrameRenderer renderer(scene, part_settings);
      Film own = renderer.make_film();
      // This part's tiles, last first.
      std::vector<std::size_t> mine;
      for (std::size_t t = part; t < renderer.tiles().size(); t += kParts) mine.push_back(t);
      std::atomic<std::size_t> next{0};
      std::mutex mutex;
      std::vector<std::size_t> done;
      tiles_rendered += renderer.render_tiles(
          own,
          [&]() -> std::optional<std::size_t> {
            const std::size_t k = next++;
            if (k < mine.size()) return mine[mine.size() - 1 - k];
            return std::nullopt;
          },
          [&](std::size_t tile, double ms) {
            EXPECT_GE(ms, 0.0);
            std::lock_guard lock(mutex);
            done.push_back(tile);
          });
      std::sort(done.begin(), done.end());
      EXPECT_EQ(done, mine) << aa;
      for (std::size_t t : mine) {
        std::vector<std::byte> bytes;
        renderer.pack_tile(own, t, bytes);
        ASSERT_EQ(bytes.size(), renderer.tile_bytes(t)) << aa;
        gather.unpack_tile(film, t, bytes);
      }
      const RayCounts r = renderer.stats().rays;
      rays.primary += r.primary;
      rays.shadow += r.shadow;
      rays.reflection += r.reflection;
      rays.refraction += r.refraction;
    }
    EXPECT_EQ(tiles_rendered, gather.tiles().size()) << aa;
    gather.finish(film);
    expect_same_image(whole.image, film.image, aa);
    EXPECT_EQ(rays.primary, whole.stats.rays.primary) << aa;
    EXPECT_EQ(rays.shadow, whole.stats.rays.shadow) << aa;
    EXPECT_EQ(rays.reflection, whole.stats.rays.reflection) << aa;
    EXPECT_EQ(rays.refraction, whole.stats.rays.refraction) << aa;
  }
}

TEST(Render, UnpackingATileOfTheWrongSizeThrows) {
  const Scene scene = build_scene(default_scene(), {});
  const FrameRenderer renderer(scene, small_settings(20, 20));
  Film film = renderer.make_film();
  const std::vector<std::byte> bytes(renderer.tile_bytes(0) - 1);
  EXPECT_THROW(renderer.unpack_tile(film, 0, bytes), std::invalid_argument);
  EXPECT_THROW(renderer.tile_bytes(renderer.tiles().size()), std::out_of_range);
}

// refine with grid strata samples a pixel at the centres of its strata, and a
// refined pixel afresh at the finer ones: with a threshold of 0 every pixel
// whose first four rays differ at all is refined, and refine:0:4:grid is
// grid:4's image (a refined pixel's 16 rays added in another order, its 4
// first ones dropped; the others flat at both sizes).
TEST(Render, RefineWithGridStrataEveryPixelRefinedIsGridsImage) {
  const Scene scene = build_scene(every_kind_scene(), {});
  for (const bool filter : {false, true}) {
    RenderSettings settings = small_settings(24, 18, "grid:4");
    settings.isa = best_supported_isa();
    settings.tile_size = 64;  // one tile: no apron outside the image
    settings.trace.filter_textures = filter;
    const RenderResult grid = render(scene, settings);
    settings.aa = parse_anti_aliasing("refine:0:4:grid");
    const RenderResult refined = render(scene, settings);
    const std::uint64_t pixels = 24u * 18u, refined_rays = refined.stats.rays.primary - 4u * pixels;
    EXPECT_EQ(refined_rays % 16u, 0u) << filter;  // 16 fresh rays per refined pixel
    EXPECT_GT(refined_rays, 16u * pixels / 2) << filter;  // most pixels of this scene vary
    ASSERT_EQ(refined.image.rgb.size(), grid.image.rgb.size());
    float worst = 0.f;
    for (std::size_t k = 0; k < grid.image.rgb.size(); ++k) {
      worst = std::max(worst, std::fabs(refined.image.rgb[k] - grid.image.rgb[k]));
    }
    EXPECT_LT(worst, 1e-5f) << filter;  // float sums of 16 values in another order
    // With jittered strata the same rays count, other positions: another image.
    settings.aa = parse_anti_aliasing("refine:0:4");
    EXPECT_FALSE(same_bits(render(scene, settings).image.rgb, grid.image.rgb)) << filter;
  }
}

// refine: 2 x 2 rays in every pixel; more only where a pixel's own samples
// or its neighbours disagree, in colour or in the surfaces they meet, at
// most N x N.
TEST(Render, RefineSpendsRaysOnlyWhereAPixelIsUncertain) {
  RenderSettings settings = small_settings(40, 30, "refine:1e9:8");  // colour never uncertain
  settings.isa = best_supported_isa();
  settings.tile_size = 64;  // one tile: no apron outside the image
  const std::uint64_t pixels = 40u * 30u;
  // One wall filling the view, seen head on: one surface, no depth jump.
  SceneDesc wall;
  wall.camera = CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f, 0.f, 40, 30};
  wall.lights.push_back({});
  wall.materials.push_back({});
  wall.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 0.f, 1.f}}, 0});
  EXPECT_EQ(render(build_scene(wall, {}), settings).stats.rays.primary, 4 * pixels);
  // A ball of the same material before it: only the pixels at its rim
  // (and their neighbours) meet a depth jump, and take more rays.
  wall.spheres.push_back({{{0.f, 0.f, 2.f}, 0.4f}, 0});
  const std::uint64_t with_ball = render(build_scene(wall, {}), settings).stats.rays.primary;
  EXPECT_GT(with_ball, 4 * pixels);
  EXPECT_LT(with_ball, 4 * pixels + 60 * 200);  // the rim and its neighbours: under 200 pixels
  // Surfaces refine a pixel once; only its colour's uncertainty refines it
  // further, which never comes here: at most 8 x 8 spends what 4 x 4 does.
  settings.aa = parse_anti_aliasing("refine:1e9:4");
  EXPECT_EQ(render(build_scene(wall, {}), settings).stats.rays.primary, with_ball);
  settings.aa = parse_anti_aliasing("refine:1e9:8");
  // Another material at nearly the same depth (0.02% nearer) counts as another surface too.
  wall.spheres.clear();
  wall.materials.push_back({});
  TriangleDesc patch;
  patch.p = {Vec3<float>(-0.3f, -0.3f, 1e-3f), Vec3<float>(0.3f, -0.3f, 1e-3f), Vec3<float>(0.f, 0.3f, 1e-3f)};
  wall.triangles.push_back({patch, 1});
  EXPECT_GT(render(build_scene(wall, {}), settings).stats.rays.primary, 4 * pixels);
  const Scene scene = build_scene(default_scene(), {});
  settings.aa = parse_anti_aliasing("refine:0.02:8");
  const std::uint64_t some = render(scene, settings).stats.rays.primary;
  settings.aa = parse_anti_aliasing("refine:0:8");
  const std::uint64_t most = render(scene, settings).stats.rays.primary;
  EXPECT_GT(some, 4 * pixels);
  EXPECT_LT(some, most);
  EXPECT_LE(most, 64 * pixels);
  // Tiles of 7 add each tile's apron to the first pass, and change no pixel.
  const RenderResult whole = render(scene, settings);
  settings.tile_size = 7;
  const RenderResult tiled = render(scene, settings);
  EXPECT_TRUE(same_bits(whole.image.rgb, tiled.image.rgb));
  EXPECT_GT(tiled.stats.rays.primary, whole.stats.rays.primary);
}

// A pixel whose own first rays meet two materials is refined, even where
// every pixel's last first-pass ray meets the same one as its neighbours':
// a strip of a second material, a hair in front of a wall, covering the left
// half of the first pixel column (where the strata i = 0 sample) only.
TEST(Render, RefineSeesTwoMaterialsWithinOnePixel) {
  constexpr int kWidth = 40, kHeight = 30;
  RenderSettings settings = small_settings(kWidth, kHeight, "refine:1e9:4");  // colour never uncertain
  settings.isa = best_supported_isa();
  settings.tile_size = 64;  // one tile: no apron outside the image
  SceneDesc wall;
  wall.camera = CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f, 0.f, kWidth, kHeight};
  wall.lights.push_back({});
  wall.materials.push_back({});
  wall.materials.push_back({});
  wall.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 0.f, 1.f}}, 0});
  const std::uint64_t pixels = std::uint64_t(kWidth) * kHeight;
  EXPECT_EQ(render(build_scene(wall, {}), settings).stats.rays.primary, 4 * pixels);
  // Where the rays through the first column's centre line meet the strip's plane.
  constexpr float kStripZ = 1e-3f;
  const Camera camera(*wall.camera, kWidth, kHeight);
  const Vec3<double> d = view_direction(camera, 0.5, 0.5 * kHeight);
  const auto edge = float((kStripZ - 5.0) / d.z * d.x);
  const Vec3<float> a{edge - 10.f, -10.f, kStripZ}, b{edge, -10.f, kStripZ}, c{edge, 10.f, kStripZ},
      e{edge - 10.f, 10.f, kStripZ};
  TriangleDesc lower, upper;
  lower.p = {a, b, c};
  upper.p = {a, c, e};
  wall.triangles.push_back({lower, 1});
  wall.triangles.push_back({upper, 1});
  const RenderResult strip = render(build_scene(wall, {}), settings);
  // The first column's pixels (and, by their means, their neighbours) take 16 rays.
  EXPECT_GE(strip.stats.rays.primary, 4 * pixels + 12 * std::uint64_t(kHeight));
}

// The jittered modes (jitter, refine) draw their sample positions from the
// seed: the same seed repeats the image bit for bit, another seed changes
// it. The modes that do not jitter (none, grid, corners, adaptive, whose
// samples sit on fixed lattices) give the same image for any seed. Point
// lights only: area lights draw their samples from the seed too.
TEST(Render, JitteredModesFollowTheSeedAndRepeatIt) {
  SceneDesc desc = default_scene();
  std::erase_if(desc.lights, [](const LightDesc& l) { return l.kind != LightDesc::Kind::point; });
  ASSERT_FALSE(desc.lights.empty());
  const Scene scene = build_scene(desc, {});
  const auto image = [&](const char* aa, std::uint64_t seed) {
    RenderSettings settings = small_settings(40, 30, aa);
    settings.isa = best_supported_isa();
    settings.trace.seed = seed;
    return render(scene, settings).image;
  };
  for (const char* aa : {"jitter:3", "refine:0.02:4"}) {
    const Framebuffer first = image(aa, 5);
    EXPECT_TRUE(same_bits(first.rgb, image(aa, 5).rgb)) << aa << ": the same seed repeats the image";
    EXPECT_FALSE(same_bits(first.rgb, image(aa, 6).rgb)) << aa << ": another seed moves the samples";
  }
  for (const char* aa : {"none", "grid:3", "corners", "adaptive:0.05:2"}) {
    EXPECT_TRUE(same_bits(image(aa, 5).rgb, image(aa, 6).rgb)) << aa << " does not jitter";
  }
}

// A material lit by the ambient light alone (ka 1, kd 0) under texture `texture`.
MaterialDesc ambient_only(std::size_t texture) {
  MaterialDesc flat;
  flat.ka = 1.f;
  flat.kd = 0.f;
  flat.texture = texture;
  return flat;
}

// A plane facing the camera at z = plane_z, seen from `distance` above the
// point (eye.x, eye.y, plane_z), under a solid checker of `cell`-wide cells
// (colours a and b) lit by ambient light alone (ka 1, kd 0): each sample is
// exactly its cell's colour.
SceneDesc ambient_checker_plane(int side, std::array<float, 2> eye, float plane_z, double distance, double cell,
                                Vec3<float> a, Vec3<float> b) {
  SceneDesc desc;
  desc.camera = CameraDesc{{eye[0], eye[1], float(plane_z + distance)}, {eye[0], eye[1], plane_z}, {0.f, 1.f, 0.f},
                           40.f, 0.f, side, side};
  desc.ambient = {1.f, 1.f, 1.f};
  TextureDesc checks;
  checks.kind = TextureDesc::Kind::checker3d;
  checks.color_a = a;
  checks.color_b = b;
  checks.scale = float(1.0 / cell);
  desc.textures.push_back(checks);
  desc.materials.push_back(ambient_only(0));
  desc.planes.push_back({{{0.f, 0.f, plane_z}, {0.f, 0.f, 1.f}}, 0});
  return desc;
}

// jitter draws a sample's x and y offsets independently. One jittered
// sample per pixel of a camera-facing solid checker whose cells are one
// pixel wide with their corners at the pixel centres: a sample's colour is
// the pixel's parity flipped by (x offset >= 1/2) xor (y offset >= 1/2), so
// independent offsets give the parity pattern in half the pixels (1024
// pixels: 16 standard deviations below 3/4), offsets tied together in all.
TEST(Render, JitterDrawsEachSamplesXAndYOffsetIndependently) {
  const int side = 32;
  const double distance = 10.0;
  const double cell = distance * Camera(CameraDesc{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 40.f, 0.f, side, side}, side, side)
                                     .pixel_size();
  // The view axis meets the film between pixels 15 and 16: half a cell off puts the pixel centres on corners.
  const float half = float(cell / 2);
  const SceneDesc desc = ambient_checker_plane(side, {half, half}, half, distance, cell, {1.f, 1.f, 1.f}, {0.f, 0.f, 0.f});
  RenderSettings settings = small_settings(side, side, "jitter:1");
  settings.isa = best_supported_isa();
  settings.trace.filter_textures = false;  // point samples: each exactly one colour
  const Framebuffer image = render(build_scene(desc, {}), settings).image;
  std::size_t follow_parity = 0;
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const float red = image.rgb[(std::size_t(y) * side + std::size_t(x)) * 3];
      ASSERT_TRUE(red == 0.f || red == 1.f) << x << ", " << y;
      follow_parity += (red == image.rgb[0]) == ((x + y) % 2 == 0);
    }
  }
  EXPECT_LT(follow_parity, std::size_t(side * side * 3 / 4));
  EXPECT_GT(follow_parity, std::size_t(side * side / 4));
}

// refine's error estimate is the sample variance with n - 1 (unbiased).
// A camera-facing solid checker of 0.5 and 0 whose cells are half a pixel,
// aligned with the first pass's 2 x 2 strata, gives every pixel two samples
// of each: variance 0.25 / 3 (0.25 / 4 with n), over 4 samples 1 / 48
// against a threshold of 0.125 squared, 1 / 64 (so n would not refine);
// equal pixel means and one surface leave the other rules silent.
TEST(Render, RefineJudgesAPixelByItsUnbiasedSampleVariance) {
  const int side = 16;
  const double distance = 10.0;
  const double cell = distance * Camera(CameraDesc{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 40.f, 0.f, side, side}, side, side)
                                     .pixel_size() / 2;
  const float mid = float(cell / 2);  // the plane in the middle of a cell along z
  const SceneDesc desc = ambient_checker_plane(side, {0.f, 0.f}, mid, distance, cell, {0.5f, 0.5f, 0.5f}, {0.f, 0.f, 0.f});
  const Scene scene = build_scene(desc, {});
  const auto primary_rays = [&](const char* aa) {
    RenderSettings settings = small_settings(side, side, aa);
    settings.isa = best_supported_isa();
    settings.trace.filter_textures = false;
    const RenderResult r = render(scene, settings);
    for (std::size_t p = 0; p < r.image.pixel_count(); ++p) EXPECT_EQ(r.image.rgb[3 * p], 0.25f) << "pixel " << p;
    return r.stats.rays.primary;
  };
  const std::uint64_t first_pass = primary_rays("refine:1:8");  // nothing is uncertain at threshold 1
  EXPECT_GE(primary_rays("refine:0.125:8"), first_pass + std::uint64_t(side * side));
}

// A textured quad maps (u, v) by the inverse of its bilinear patch
// p = a + s (b - a) + t (d - a) + s t (a - b + c - d), taking the root in
// [0, 1]. The trapezoid (-2, -1), (2, -1), (1, 1), (-1, 1) puts (s, t) =
// (0.4, 0.6) at (-0.28, 0.2), where t's quadratic -4 t^2 + 10.4 t - 4.8
// has the roots 0.6 and 2. A 2 x 1 texture black to red, clamped, reads
// red 2 (u - 1/4) there: 0.3 (float inputs: within 1e-5).
TEST(Render, ATexturedQuadTakesTheBilinearRootInsideIt) {
  SceneDesc desc;
  desc.camera = CameraDesc{{-0.28f, 0.2f, 5.f}, {-0.28f, 0.2f, 0.f}, {0.f, 1.f, 0.f}, 10.f, 0.f, 1, 1};
  desc.ambient = {1.f, 1.f, 1.f};
  TextureDesc ramp;
  ramp.kind = TextureDesc::Kind::image;
  ramp.wrap = WrapMode::clamp;
  ramp.width = 2;
  ramp.height = 1;
  ramp.rgb = {0.f, 0.f, 0.f, 1.f, 0.f, 0.f};
  desc.textures.push_back(ramp);
  desc.materials.push_back(ambient_only(0));
  desc.polygons.push_back({{{{-2.f, -1.f, 0.f}, {2.f, -1.f, 0.f}, {1.f, 1.f, 0.f}, {-1.f, 1.f, 0.f}}}, {}, 0});
  RenderSettings settings = small_settings(1, 1);
  settings.isa = best_supported_isa();
  settings.trace.filter_textures = false;
  const Framebuffer image = render(build_scene(desc, {}), settings).image;
  ASSERT_EQ(image.kind[0], static_cast<std::int32_t>(kind_tag<PolygonKind>));
  EXPECT_NEAR(image.rgb[0], 0.3f, 1e-5f);
}

TEST(Render, LaneStatisticsAddUp) {
  const Scene scene = build_scene(default_scene(), {});
  RenderSettings settings = small_settings(32, 24);
  settings.isa = best_supported_isa();
  const RenderResult r = render(scene, settings);
  const std::uint64_t lanes = static_cast<std::uint64_t>(lane_width(kernel_unit_for(settings.isa)));
  ASSERT_GE(r.stats.waves.size(), 3u);
  EXPECT_EQ(r.stats.waves[0].active, 32u * 24u);
  EXPECT_EQ(r.stats.rays.primary, 32u * 24u);
  std::uint64_t secondary = 0;
  for (std::size_t d = 0; d < r.stats.waves.size(); ++d) {
    const WaveLanes& w = r.stats.waves[d];
    EXPECT_LE(w.active, w.issued_compacted) << "wave " << d;
    EXPECT_LE(w.issued_compacted, w.issued_uncompacted) << "wave " << d;
    EXPECT_EQ(w.issued_compacted % lanes, 0u);
    if (d > 0) secondary += w.active;
  }
  EXPECT_EQ(secondary, r.stats.rays.reflection + r.stats.rays.refraction);
  EXPECT_EQ(r.stats.shadow.active, r.stats.rays.shadow);
  // Shadow rays go out a light sample's slot at a time, each slot's padded to whole packets.
  const WaveLanes& shadow = r.stats.shadow;
  EXPECT_EQ(shadow.issued_compacted % lanes, 0u);
  EXPECT_LE(shadow.active, shadow.issued_compacted);
  EXPECT_LE(shadow.issued_compacted, shadow.issued_uncompacted);
  ASSERT_NE(shadow.active % lanes, 0u) << "a ray count that pads differently is needed";
  // The shading packets are the waves' packets; a lane is active where it hit.
  std::uint64_t compacted = 0;
  for (const WaveLanes& w : r.stats.waves) compacted += w.issued_compacted;
  EXPECT_GE(r.stats.shading_active, r.stats.rays.primary_hits);
  EXPECT_LE(r.stats.shading_active, compacted);
  // Every shadow ray is one active lane of a light sample iteration.
  EXPECT_EQ(r.stats.light_sample_active, r.stats.rays.shadow);
  EXPECT_LE(r.stats.light_sample_active, r.stats.light_sample_issued);
  EXPECT_EQ(r.stats.light_sample_issued % lanes, 0u);
}

TEST(Render, PhasesAreTimedOnlyWhenAskedAndNeverChangeTheImage) {
  const Scene scene = build_scene(default_scene(), {});
  RenderSettings settings = small_settings(32, 24);
  settings.isa = best_supported_isa();
  const RenderResult untimed = render(scene, settings);
  const PhaseTimes& none = untimed.stats.phases;
  EXPECT_EQ(none.total(), 0u);
  EXPECT_EQ(none.shadow_walks, 0u);
  settings.trace.time_phases = true;
  const RenderResult timed = render(scene, settings);
  const PhaseTimes& p = timed.stats.phases;
  EXPECT_GT(p.camera_and_film, 0u);
  EXPECT_GT(p.intersection, 0u);
  EXPECT_GT(p.shading, 0u);
  EXPECT_GT(p.shadows, 0u);
  EXPECT_GT(p.shadow_walks, 0u);
  EXPECT_LE(p.shadow_walks, p.shadows);
  EXPECT_EQ(timed.image.rgb, untimed.image.rgb);
}

// ---- depth 0, 1, 2 -----------------------------------------------------------

SceneDesc mirrors_scene(bool second_mirror) {
  SceneDesc s;
  s.camera = CameraDesc{{0.f, 1.5f, 6.f}, {0.f, 0.8f, 0.f}, {0.f, 1.f, 0.f}, 50.f, 0.f, 48, 36};
  s.background = {0.2f, 0.3f, 0.5f};
  s.lights.push_back({});
  s.lights[0].position = {3.f, 6.f, 4.f};
  s.textures.push_back({});  // 2D checker
  MaterialDesc floor;
  floor.texture = 0;
  MaterialDesc mirror;
  mirror.color = {0.9f, 0.9f, 0.9f};
  mirror.kd = 0.1f;
  mirror.kr = 0.8f;
  s.materials = {floor, mirror};
  s.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}}, 0});
  s.spheres.push_back({{{-0.9f, 1.f, 0.f}, 1.f}, 1});
  if (second_mirror) s.spheres.push_back({{{1.2f, 0.9f, 0.4f}, 0.9f}, 1});
  return s;
}

Framebuffer render_at_depth(const SceneDesc& desc, int depth) {
  const Scene scene = build_scene(desc, {});
  RenderSettings settings = small_settings(48, 36);
  settings.isa = best_supported_isa();
  settings.trace.max_depth = depth;
  settings.trace.min_weight = 0.f;
  return render(scene, settings).image;
}

TEST(Render, DepthZeroOneTwoDifferOnlyWhereMirrorsAre) {
  for (bool two : {false, true}) {
    const SceneDesc desc = mirrors_scene(two);
    const Framebuffer d0 = render_at_depth(desc, 0), d1 = render_at_depth(desc, 1), d2 = render_at_depth(desc, 2);
    std::size_t changed_on_mirror = 0, changed_elsewhere = 0;
    for (std::size_t p = 0; p < d0.pixel_count(); ++p) {
      const bool mirror = d0.kind[p] == static_cast<std::int32_t>(kind_tag<SphereKind>);
      const bool changed = std::memcmp(&d0.rgb[3 * p], &d1.rgb[3 * p], 3 * sizeof(float)) != 0;
      (mirror ? changed_on_mirror : changed_elsewhere) += changed;
    }
    EXPECT_GT(changed_on_mirror, 50u) << "depth 1 adds reflections on the mirror";
    EXPECT_EQ(changed_elsewhere, 0u) << "the matte floor and background do not change";
    if (two) {
      EXPECT_FALSE(same_bits(d1.rgb, d2.rgb)) << "two mirrors see each other: depth 2 adds light";
    } else {
      EXPECT_TRUE(same_bits(d1.rgb, d2.rgb)) << "one convex mirror over a matte floor: nothing at depth 2";
    }
  }
}

// A reflection ray whose weight equals the cut-off exactly is cast (the
// cut-off drops weights below it): a kr = 0.5 mirror seen by camera rays
// (weight 1, so the reflection's weight is exactly 0.5) reflects at
// min_weight 0.5 as at 0, and not at the next float above 0.5.
TEST(Render, AReflectionWhoseWeightEqualsTheCutOffIsCast) {
  SceneDesc desc = mirrors_scene(false);
  desc.materials[1].kr = 0.5f;
  const Scene scene = build_scene(desc, {});
  const auto image_at = [&](float min_weight) {
    RenderSettings settings = small_settings(48, 36);
    settings.isa = best_supported_isa();
    settings.trace.max_depth = 1;
    settings.trace.min_weight = min_weight;
    return render(scene, settings).image;
  };
  const Framebuffer every = image_at(0.f);
  EXPECT_TRUE(same_bits(every.rgb, image_at(0.5f).rgb)) << "weight 0.5 at min_weight 0.5 is cast";
  EXPECT_FALSE(same_bits(every.rgb, image_at(std::nextafter(0.5f, 1.f)).rgb)) << "a weight below the cut-off is not";
}

// ---- transparent shadows ---------------------------------------------------

// A white matte floor under a light straight above; between them, at the
// image centre's floor point, transmissive occluders. The camera looks at
// that point from the side, below the occluders.
float centre_red(const SceneDesc& desc) {
  const Scene scene = build_scene(desc, {});
  RenderSettings settings = small_settings(33, 33);
  settings.isa = best_supported_isa();
  settings.trace.max_depth = 0;
  const Framebuffer image = render(scene, settings).image;
  EXPECT_EQ(image.kind[16 * 33 + 16], static_cast<std::int32_t>(kind_tag<PlaneKind>));
  return image.rgb[(16 * 33 + 16) * 3];
}

SceneDesc shadow_scene() {
  SceneDesc s;
  s.camera = CameraDesc{{0.f, 1.f, 8.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f, 0.f, 33, 33};
  s.ambient = {0.f, 0.f, 0.f};
  s.lights.push_back({});
  s.lights[0].position = {0.f, 10.f, 0.f};
  s.lights[0].color = {0.8f, 0.8f, 0.8f};
  MaterialDesc floor;
  floor.ka = 0.f;
  floor.kd = 1.f;
  s.materials.push_back(floor);
  s.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}}, 0});
  return s;
}

void add_slab(SceneDesc& s, float y, float kt, const Vec3<float>& color) {
  MaterialDesc glass;
  glass.color = color;
  glass.ka = glass.kd = 0.f;
  glass.kt = kt;
  glass.ior = 1.f;
  s.materials.push_back(glass);
  s.polygons.push_back({{{{-1.f, y, -1.f}, {1.f, y, -1.f}, {1.f, y, 1.f}, {-1.f, y, 1.f}}}, {}, s.materials.size() - 1});
}

TEST(Render, TransparentShadowsMultiplyKtTimesColourPerSurface) {
  SceneDesc open = shadow_scene();
  const float lit = centre_red(open);
  EXPECT_NEAR(lit, 0.8f, 1e-5f);  // kd (N.L) I with N.L = 1
  SceneDesc one = shadow_scene();
  add_slab(one, 5.f, 0.5f, {0.6f, 1.f, 1.f});
  EXPECT_NEAR(centre_red(one), 0.8f * 0.5f * 0.6f, 1e-5f);
  SceneDesc two = shadow_scene();
  add_slab(two, 5.f, 0.5f, {0.6f, 1.f, 1.f});
  add_slab(two, 3.f, 0.25f, {1.f, 1.f, 1.f});
  EXPECT_NEAR(centre_red(two), 0.8f * 0.5f * 0.6f * 0.25f, 1e-5f);
  SceneDesc opaque = shadow_scene();
  add_slab(opaque, 5.f, 0.5f, {0.6f, 1.f, 1.f});
  opaque.materials.push_back(MaterialDesc{});
  opaque.spheres.push_back({{{0.f, 7.f, 0.f}, 0.5f}, opaque.materials.size() - 1});
  EXPECT_EQ(centre_red(opaque), 0.f);
}

// A smooth triangle whose shading normals lean towards a light that lies
// behind its geometric surface: the shadow ray leaves from the lifted point
// (the lean puts the centre below the tangent planes of two corners), so
// the light lights it unless something blocks that ray; an opaque wall just
// behind the triangle does, leaving the ambient term alone. The same light
// in front lights it; a flat triangle (its normals its face's) is never lit
// from behind.
TEST(Render, ALightBehindASmoothTriangleLightsItOnlyAlongTheLiftedShadowRay) {
  const auto centre_red = [](float light_z, bool leaning, bool wall) {
    SceneDesc desc;
    desc.camera = CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 20.f, 0.f, 9, 9};
    desc.ambient = {0.2f, 0.2f, 0.2f};
    MaterialDesc matte;
    matte.ka = 1.f;
    matte.kd = 1.f;
    desc.materials.push_back(matte);
    SceneTriangle t{};
    t.triangle.p = {Vec3<float>{-4.f, -4.f, 0.f}, Vec3<float>{4.f, -4.f, 0.f}, Vec3<float>{0.f, 4.f, 0.f}};
    const Vec3<float> normal = leaning ? normalize(Vec3<float>{1.f, 0.f, 0.2f}) : Vec3<float>{0.f, 0.f, 1.f};
    t.triangle.normals = std::array<Vec3<float>, 3>{normal, normal, normal};
    desc.triangles.push_back(t);
    if (wall) {
      SceneTriangle back{};
      back.triangle.p = {Vec3<float>{-40.f, -40.f, -0.05f}, Vec3<float>{0.f, 40.f, -0.05f},
                         Vec3<float>{40.f, -40.f, -0.05f}};
      desc.triangles.push_back(back);
    }
    LightDesc light;
    light.position = {10.f, 0.f, light_z};
    desc.lights.push_back(light);
    RenderSettings settings = small_settings(9, 9);
    settings.isa = best_supported_isa();
    const Framebuffer image = render(build_scene(desc, {}), settings).image;
    return image.rgb[(4 * 9 + 4) * 3];
  };
  EXPECT_GT(centre_red(-1.f, true, false), 0.3f);  // the lifted shadow ray passes the triangle's edge
  EXPECT_EQ(centre_red(-1.f, true, true), 0.2f);   // the wall blocks it: ambient alone
  EXPECT_GT(centre_red(1.f, true, true), 0.3f);    // the same light in front of the surface
  EXPECT_EQ(centre_red(-1.f, false, false), 0.2f);
}

// UV spheres of 32 segments and 16 rings, and a coarse one of 12 and 6,
// around the origin (radius 1, triangles with the exact sphere's normals
// at their vertices), lit at 80 degrees from the view, shade as the
// analytic sphere does: faces turned from the light but shaded towards it
// are lit where the shadow ray from the terminator lift reaches the light,
// so the shadow edge has no triangle-shaped steps (without the lift the
// coarse sphere errs 0.032).
double uv_sphere_rmse_at_a_grazing_light(int segments, int rings) {
  constexpr int kSide = 128;
  SceneDesc analytic;
  analytic.camera = CameraDesc{{0.f, 0.f, 4.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 35.f, 0.f, kSide, kSide};
  analytic.ambient = {0.05f, 0.05f, 0.05f};
  MaterialDesc matte;
  matte.kd = 0.9f;
  matte.ks = 0.f;
  analytic.materials.push_back(matte);
  LightDesc light;
  light.kind = LightDesc::Kind::directional;
  const double degrees80 = 80.0 * std::numbers::pi / 180.0;  // from the view axis, towards +x
  light.direction = {-float(std::sin(degrees80)), 0.f, -float(std::cos(degrees80))};
  analytic.lights.push_back(light);
  SceneDesc mesh = analytic;
  analytic.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, 0});
  const auto vertex = [&](int ring, int segment) {
    const double theta = std::numbers::pi * ring / rings, phi = 2.0 * std::numbers::pi * segment / segments;
    return Vec3<float>{float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                       float(std::sin(theta) * std::sin(phi))};
  };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const Vec3<float> a = vertex(r, s), b = vertex(r, s + 1), c = vertex(r + 1, s + 1), d = vertex(r + 1, s);
      for (const std::array<Vec3<float>, 3>& corners : {std::array{a, c, b}, std::array{a, d, c}}) {
        SceneTriangle t{};
        t.triangle.p = corners;
        t.triangle.normals = corners;  // a unit sphere's normal is its point
        if (length(cross(corners[1] - corners[0], corners[2] - corners[0])) > 0.f) mesh.triangles.push_back(t);
      }
    }
  }
  RenderSettings settings = small_settings(kSide, kSide);
  settings.isa = best_supported_isa();
  const Framebuffer sphere = render(build_scene(analytic, {}), settings).image;
  const Framebuffer faces = render(build_scene(mesh, {}), settings).image;
  double squared = 0.0;
  std::size_t both = 0, lit_both = 0;
  for (std::size_t p = 0; p < sphere.depth.size(); ++p) {
    if (!std::isfinite(sphere.depth[p]) || !std::isfinite(faces.depth[p])) continue;
    ++both;
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = double(sphere.rgb[3 * p + c]) - double(faces.rgb[3 * p + c]);
      squared += d * d;
    }
    lit_both += sphere.rgb[3 * p] > 0.06f && faces.rgb[3 * p] > 0.06f;
  }
  EXPECT_GT(both, std::size_t(kSide * kSide / 4));
  EXPECT_GT(lit_both, both / 4) << "the light reaches about half of both";
  return std::sqrt(squared / double(3 * std::max(both, std::size_t(1))));
}

TEST(Render, SmoothUvSphereMeshesShadeAsTheSphereAtAGrazingLight) {
  for (const auto& [segments, rings] : {std::pair{32, 16}, std::pair{12, 6}}) {
    const double rmse = uv_sphere_rmse_at_a_grazing_light(segments, rings);
    RecordProperty("rmse_" + std::to_string(segments) + "x" + std::to_string(rings), std::to_string(rmse));
    EXPECT_LT(rmse, 0.02) << segments << "x" << rings;
  }
}

// A glass plane seen from above, under a rectangle light behind the camera,
// against a black background: what a pixel shows is the light reflected,
// so with Fresnel on it is F kt times the light (0.04 at normal incidence,
// more towards the image's edge), and with it off nothing (kr 0); the
// refracted share sees black either way.
TEST(Render, AFresnelGlassReflectsTheShareItsReflectanceGives) {
  SceneDesc desc;
  desc.camera = CameraDesc{{0.f, 2.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, 60.f, 0.f, 9, 9};
  desc.background = Vec3<float>{0.f, 0.f, 0.f};
  desc.ambient = {0.f, 0.f, 0.f};
  LightDesc light;
  light.kind = LightDesc::Kind::rectangle;
  light.position = {-50.f, 3.f, -50.f};
  light.edge_u = {100.f, 0.f, 0.f};
  light.edge_v = {0.f, 0.f, 100.f};
  light.color = {1.f, 1.f, 1.f};
  desc.lights.push_back(light);
  MaterialDesc glass;
  glass.ka = glass.kd = glass.ks = 0.f;
  glass.kt = 1.f;
  glass.ior = 1.5f;
  desc.materials.push_back(glass);
  desc.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}}, 0});
  RenderSettings settings = small_settings(9, 9);
  settings.isa = best_supported_isa();
  const float centre_fixed = render(build_scene(desc, {}), settings).image.rgb[3 * (4 * 9 + 4)];
  desc.materials[0].fresnel = true;
  const Framebuffer image = render(build_scene(desc, {}), settings).image;
  EXPECT_EQ(centre_fixed, 0.f);
  EXPECT_NEAR(image.rgb[3 * (4 * 9 + 4)], 0.04f, 1e-5f);
  EXPECT_GT(image.rgb[3 * (4 * 9 + 0)], image.rgb[3 * (4 * 9 + 4)]);  // a more oblique view reflects more
}

// A shadow ray toward a point light ends at the light: an opaque sphere on
// the far side of the light (above it, the floor below) casts no shadow,
// while the same sphere between the floor and the light does.
TEST(Render, AnOccluderBeyondAPointLightCastsNoShadow) {
  SceneDesc beyond = shadow_scene();
  beyond.materials.push_back(MaterialDesc{});
  beyond.spheres.push_back({{{0.f, 12.f, 0.f}, 1.f}, beyond.materials.size() - 1});  // the light is at y = 10
  EXPECT_NEAR(centre_red(beyond), 0.8f, 1e-5f);  // kd (N.L) I with N.L = 1, as with no sphere
  SceneDesc between = shadow_scene();
  between.materials.push_back(MaterialDesc{});
  between.spheres.push_back({{{0.f, 8.f, 0.f}, 1.f}, between.materials.size() - 1});
  EXPECT_EQ(centre_red(between), 0.f);
}

// A spot light straight above the floor's centre point lights it fully;
// turned so that the point lies between its cones, by glTF's squared ramp;
// turned past its outer cone, not at all. Every unit gives the same bits.
TEST(Render, ASpotLightFallsOffBetweenItsConesAlike) {
  const auto spot_scene = [](double tilt_degrees) {
    SceneDesc s = shadow_scene();
    LightDesc& spot = s.lights[0];
    spot.kind = LightDesc::Kind::spot;
    const double tilt = tilt_degrees * std::numbers::pi / 180.0;
    spot.direction = {float(std::sin(tilt)), float(-std::cos(tilt)), 0.f};
    spot.cone_inner_cos = float(std::cos(10.0 * std::numbers::pi / 180.0));
    spot.cone_outer_cos = float(std::cos(20.0 * std::numbers::pi / 180.0));
    return s;
  };
  EXPECT_NEAR(centre_red(spot_scene(0.0)), 0.8f, 1e-5f);
  const double off_axis = std::cos(15.0 * std::numbers::pi / 180.0);
  const double ramp = (off_axis - std::cos(20.0 * std::numbers::pi / 180.0)) /
                      (std::cos(10.0 * std::numbers::pi / 180.0) - std::cos(20.0 * std::numbers::pi / 180.0));
  EXPECT_NEAR(centre_red(spot_scene(15.0)), 0.8 * ramp * ramp, 1e-4);
  EXPECT_EQ(centre_red(spot_scene(25.0)), 0.f);
  const Scene scene = build_scene(spot_scene(14.0), {});
  RenderSettings settings = small_settings(33, 33);
  settings.trace.max_depth = 0;
  settings.isa = Isa::scalar;
  const Framebuffer scalar = render(scene, settings).image;
  settings.isa = best_supported_isa();
  EXPECT_EQ(render(scene, settings).image.rgb, scalar.rgb);
}

// ---- texture filtering ------------------------------------------------------

using testing::checker_floor;

double rmse(const Framebuffer& a, const Framebuffer& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) sum += (double(a.rgb[i]) - b.rgb[i]) * (double(a.rgb[i]) - b.rgb[i]);
  return std::sqrt(sum / double(a.rgb.size()));
}

TEST(Render, BoxFilteredCheckersApproachTheSupersampledImageWithOneRayPerPixel) {
  for (bool mirror : {false, true}) {
    SCOPED_TRACE(mirror ? "seen in a mirror" : "seen directly");
    const Scene scene = build_scene(checker_floor(mirror), {});
    RenderSettings settings = small_settings(96, 54, "grid:12");
    settings.trace.filter_textures = false;
    const Framebuffer reference = render(scene, settings).image;
    settings.aa = parse_anti_aliasing("none");
    const double point_sampled = rmse(render(scene, settings).image, reference);
    settings.trace.filter_textures = true;
    const double filtered = rmse(render(scene, settings).image, reference);
    EXPECT_GT(point_sampled, 0.1);  // the scene aliases
    EXPECT_LT(filtered, 0.5 * point_sampled);
  }
}

// ---- tinted glass under total internal reflection ---------------------------

// A long right-angle glass prism (ior 1.5, colour C, kt) lying along x, its
// hypotenuse face (z = 0) looking at the camera straight down the axis. The
// centre pixel's ray enters that face head-on, meets both legs at 45 degrees
// (past the 41.8-degree critical angle), is folded back by two total
// internal reflections and leaves through the hypotenuse head-on, toward the
// white background: two crossings and two folds, nothing lit, no ambient.
SceneDesc porro_prism(const Vec3<float>& color, float kt) {
  SceneDesc s;
  s.camera = CameraDesc{{0.f, 0.f, 10.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f, 0.f, 33, 33};
  s.background = {1.f, 1.f, 1.f};
  s.ambient = {0.f, 0.f, 0.f};
  MaterialDesc glass;
  glass.color = color;
  glass.ka = glass.kd = glass.ks = glass.kr = 0.f;
  glass.kt = kt;
  glass.ior = 1.5f;
  s.materials.push_back(glass);
  // Cross-section in (y, z): B (-1.5, 0), C (0.5, 0), right angle at A (-0.5, -1);
  // every face wound counter-clockwise seen from outside.
  const float x = 3.f;
  const std::vector<std::vector<Vec3<float>>> faces = {
      {{-x, -1.5f, 0.f}, {x, -1.5f, 0.f}, {x, 0.5f, 0.f}, {-x, 0.5f, 0.f}},     // hypotenuse, +z
      {{-x, -0.5f, -1.f}, {-x, 0.5f, 0.f}, {x, 0.5f, 0.f}, {x, -0.5f, -1.f}},   // leg AC
      {{-x, -1.5f, 0.f}, {-x, -0.5f, -1.f}, {x, -0.5f, -1.f}, {x, -1.5f, 0.f}}, // leg AB
      {{x, -1.5f, 0.f}, {x, -0.5f, -1.f}, {x, 0.5f, 0.f}},                      // end, +x
      {{-x, -1.5f, 0.f}, {-x, 0.5f, 0.f}, {-x, -0.5f, -1.f}}};                  // end, -x
  for (const auto& face : faces) s.polygons.push_back({{face}, {}, 0});
  return s;
}

TEST(Render, TintedGlassFiltersEachCrossingButNotTotalInternalReflections) {
  const Vec3<float> color{0.5f, 0.8f, 1.f};
  const float kt = 0.9f;
  const Scene scene = build_scene(porro_prism(color, kt), {});
  // kt at each of the four events; the colour only where the ray crosses
  // the surface (in and out): kt^4 C^2, not kt^4 C^4.
  const float kt4 = kt * kt * kt * kt;
  const float expected[3] = {kt4 * color.x * color.x, kt4 * color.y * color.y, kt4 * color.z * color.z};
  for (const Isa isa : {Isa::scalar, best_supported_isa()}) {
    RenderSettings settings = small_settings(33, 33);
    settings.isa = isa;
    settings.trace.max_depth = 6;
    const Framebuffer image = render(scene, settings).image;
    const std::size_t centre = 16 * 33 + 16;
    ASSERT_EQ(image.kind[centre], static_cast<std::int32_t>(kind_tag<PolygonKind>));
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(image.rgb[3 * centre + std::size_t(c)], expected[c], 1e-5f) << "channel " << c;
    }
  }
}

// ---- the SPD ray tree (--preset spd) ------------------------------------------

// A transmitter with Ks 0 (like SPD gears' glass gears) filling the view,
// a matte wall behind the camera facing it, a light between them. Every eye
// ray hits the glass; its reflection ray (weight 0: kr is 0) hits the wall.
SceneDesc glass_and_wall() {
  SceneDesc s;
  s.camera = CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f, 0.f, 16, 12};
  s.lights.push_back({});
  s.lights[0].position = {0.f, 3.f, 4.f};
  MaterialDesc glass;
  glass.kd = 0.2f;
  glass.kt = 0.8f;
  glass.ior = 1.1f;
  MaterialDesc wall;
  s.materials = {glass, wall};
  s.polygons.push_back({{{{-5.f, -5.f, 0.f}, {5.f, -5.f, 0.f}, {5.f, 5.f, 0.f}, {-5.f, 5.f, 0.f}}}, {}, 0});
  s.polygons.push_back({{{{-20.f, -20.f, 8.f}, {-20.f, 20.f, 8.f}, {20.f, 20.f, 8.f}, {20.f, -20.f, 8.f}}}, {}, 1});
  return s;
}

TEST(Render, SpdTreeSpawnsReflectionsOffTransmittersAndTheirShadowRays) {
  const Scene scene = build_scene(glass_and_wall(), {});
  RenderSettings settings = small_settings(16, 12);
  settings.isa = best_supported_isa();
  settings.trace.max_depth = 1;
  settings.trace.min_weight = 0.f;
  const RenderResult whitted = render(scene, settings);
  settings.trace.spawn_every_ray = true;
  const RenderResult spd = render(scene, settings);
  const std::uint64_t n = 16u * 12u;
  ASSERT_EQ(spd.stats.rays.primary_hits, n);
  // Without the SPD rule a Ks 0 transmitter reflects nothing.
  EXPECT_EQ(whitted.stats.rays.reflection, 0u);
  EXPECT_EQ(whitted.stats.rays.refraction, n);
  EXPECT_EQ(whitted.stats.rays.shadow, n);
  // SPD rule 8: a reflection ray off every transmitter hit; rule 9: a
  // refraction ray (no total internal reflection entering from air); rule
  // 10: a shadow ray from the glass and from every wall point the
  // zero-weight reflection rays reach.
  EXPECT_EQ(spd.stats.rays.reflection, n);
  EXPECT_EQ(spd.stats.rays.refraction, n);
  EXPECT_EQ(spd.stats.rays.shadow, 2 * n);
  // Zero-weight rays add nothing: the same image.
  EXPECT_TRUE(same_bits(whitted.image.rgb, spd.image.rgb));
}

// ---- self-intersection at any scale ------------------------------------------

SceneDesc scaled(SceneDesc s, float k) {
  auto scale = [k](Vec3<float>& p) { p = p * k; };
  scale(s.camera->from);
  scale(s.camera->at);
  for (LightDesc& l : s.lights) {
    scale(l.position);
    scale(l.edge_u);
    scale(l.edge_v);
    l.radius *= k;
  }
  for (SceneSphere& sp : s.spheres) {
    scale(sp.sphere.center);
    sp.sphere.radius *= k;
  }
  for (ScenePlane& p : s.planes) scale(p.plane.point);
  for (ScenePolygon& p : s.polygons) {
    for (Vec3<float>& v : p.polygon.vertices) scale(v);
  }
  for (SceneTriangle& t : s.triangles) {
    for (Vec3<float>& v : t.triangle.p) scale(v);
  }
  for (SceneCone& c : s.cones) {
    scale(c.cone.base);
    scale(c.cone.apex);
    c.cone.base_radius *= k;
    c.cone.apex_radius *= k;
  }
  for (TextureDesc& t : s.textures) t.scale /= k;
  return s;
}

TEST(Render, NoAcneWhenTheSceneIsScaled) {
  // A lit floor with nothing above it: every floor pixel is exactly lit
  // (acne would leave some at the ambient level).
  SceneDesc bare = shadow_scene();
  bare.camera = CameraDesc{{0.f, 3.f, 6.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 60.f, 0.f, 33, 33};
  // The default scene's mirrors, glass, cone and textured quad, compared across scales.
  SceneDesc rich = every_kind_scene();
  rich.lights.pop_back();  // the area light's random samples are scale-free too, but keep it simple
  RenderSettings settings = small_settings(64, 48);
  settings.isa = best_supported_isa();
  const Framebuffer rich_reference = render(build_scene(rich, {}), settings).image;
  for (float k : {1e-4f, 1.f, 1e6f}) {
    RenderSettings bare_settings = small_settings(33, 33);
    bare_settings.isa = best_supported_isa();
    const Framebuffer floor = render(build_scene(scaled(bare, k), {}), bare_settings).image;
    std::size_t floor_pixels = 0, dark = 0;
    for (std::size_t p = 0; p < floor.pixel_count(); ++p) {
      if (floor.kind[p] != static_cast<std::int32_t>(kind_tag<PlaneKind>)) continue;
      ++floor_pixels;
      dark += floor.rgb[3 * p] < 0.01f;
    }
    EXPECT_GT(floor_pixels, 300u) << "scale " << k;
    EXPECT_EQ(dark, 0u) << "scale " << k << ": shadow acne on an unoccluded floor";

    const Framebuffer image = render(build_scene(scaled(rich, k), {}), settings).image;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < image.rgb.size(); ++i) differ += std::fabs(image.rgb[i] - rich_reference.rgb[i]) > 0.05f;
    // Rounding moves a few silhouette and shadow-edge pixels; acne or
    // speckle would change hundreds.
    EXPECT_LT(differ, image.rgb.size() / 200) << "scale " << k;
  }
}

// An area light (a rectangle or a sphere) casts samples x samples shadow
// rays from each shaded point; a point light one. A floor under the light,
// seen straight down, every pixel a lit floor point.
TEST(Render, AreaLightsCastSamplesSquaredShadowRays) {
  for (const LightDesc::Kind kind : {LightDesc::Kind::sphere, LightDesc::Kind::rectangle, LightDesc::Kind::point}) {
    for (const int samples : {1, 3}) {
      SceneDesc desc;
      desc.materials.emplace_back();
      desc.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}}, 0});
      LightDesc light;
      light.kind = kind;
      light.position = {-0.5f, 10.f, -0.5f};
      light.radius = 0.5f;
      light.edge_u = {1.f, 0.f, 0.f};
      light.edge_v = {0.f, 0.f, 1.f};
      light.samples = samples;
      desc.lights.push_back(light);
      desc.camera = CameraDesc{{0.f, 5.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f}, 40.f, 0.f, 12, 8};
      RenderSettings settings = small_settings(12, 8);
      settings.trace.max_depth = 0;
      const RenderResult r = render(build_scene(desc, {}), settings);
      const std::uint64_t per_point = kind == LightDesc::Kind::point ? 1 : std::uint64_t(samples * samples);
      EXPECT_EQ(r.stats.rays.primary, 96u);
      EXPECT_EQ(r.stats.rays.shadow, 96u * per_point) << "light kind " << int(kind) << ", samples " << samples;
    }
  }
}

// A progress callback changes nothing in the result (its cost estimate is
// not counted), is called once per tile, and its share of the work done
// never falls and ends at 1.
TEST(RenderProgress, OncePerTileWorkDoneRisesToOneAndTheImageIsTheSame) {
  SceneDesc desc = default_scene();
  const Scene scene = build_scene(desc, {});
  RenderSettings settings;
  settings.width = 96;
  settings.height = 64;
  settings.tile_size = 16;
  settings.threads = 2;
  const RenderResult plain = render(scene, settings);
  std::vector<RenderProgressState> calls;
  const RenderResult watched = render(scene, settings, [&](const RenderProgressState& p) { calls.push_back(p); });
  EXPECT_EQ(plain.image.rgb, watched.image.rgb);
  EXPECT_EQ(plain.stats.rays.total(), watched.stats.rays.total());
  ASSERT_EQ(calls.size(), watched.tiles_total);
  ASSERT_EQ(watched.tiles_total, 24u);
  double before = 0.0;
  for (std::size_t k = 0; k < calls.size(); ++k) {
    EXPECT_EQ(calls[k].tiles_done, k + 1);
    EXPECT_EQ(calls[k].tiles_total, 24u);
    EXPECT_GT(calls[k].work_done, before);
    before = calls[k].work_done;
  }
  EXPECT_DOUBLE_EQ(calls.back().work_done, 1.0);
}

}  // namespace
}  // namespace quiver
