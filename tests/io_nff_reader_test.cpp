#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "integrator/render.h"
#include "io/nff_reader.h"
#include "io/parse_error.h"
#include "tests/support/temporary_directory.h"

// Largest single request to the global operator new while tracking is on.
// The test binary's non-aligned operator new/delete family is replaced here
// (malloc/free plus this measurement) so the bounds tests can show that a
// huge count in the input never turns into a huge allocation.
namespace {

std::atomic<bool> g_track_allocations{false};
std::atomic<std::size_t> g_largest_allocation{0};

void* allocate_or_null(std::size_t bytes) noexcept {
  if (g_track_allocations.load(std::memory_order_relaxed)) {
    std::size_t seen = g_largest_allocation.load(std::memory_order_relaxed);
    while (bytes > seen && !g_largest_allocation.compare_exchange_weak(seen, bytes)) {
    }
  }
  return std::malloc(bytes == 0 ? 1 : bytes);
}

void* allocate(std::size_t bytes) {
  if (void* p = allocate_or_null(bytes)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t bytes) { return allocate(bytes); }
void* operator new[](std::size_t bytes) { return allocate(bytes); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept { return allocate_or_null(bytes); }
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept { return allocate_or_null(bytes); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = fs::path(QUIVER_TEST_DATA_DIR) / "nff";

// Material line, so error tests can start with a primitive on line 2.
constexpr std::string_view kMaterial = "f 1 1 1 1 0 1 0 1\n";
constexpr std::string_view kCamera =
    "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\n";

void expect_vec3(const Vec3<float>& v, float x, float y, float z) {
  EXPECT_EQ(v.x, x);
  EXPECT_EQ(v.y, y);
  EXPECT_EQ(v.z, z);
}

// parse_nff(text) throws a ParseError at exactly line:column whose what() is
// "test.nff:line:column: expected ..." and contains fragment.
::testing::AssertionResult parse_error_at(std::string_view text, std::size_t line, std::size_t column,
                                          std::string_view fragment) {
  try {
    parse_nff(text, "test.nff");
  } catch (const ParseError& error) {
    const std::string what = error.what();
    const std::string prefix = "test.nff:" + std::to_string(line) + ":" + std::to_string(column) + ": expected ";
    if (error.line() != line || error.column() != column || what.rfind(prefix, 0) != 0) {
      return ::testing::AssertionFailure() << "wrong position: " << what;
    }
    if (what.find(fragment) == std::string::npos) {
      return ::testing::AssertionFailure() << "'" << fragment << "' not in: " << what;
    }
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no ParseError";
}

std::string with_material(std::string_view rest) { return std::string(kMaterial) + std::string(rest); }

// ---- well-formed input: every value read exactly ----

TEST(NffReader, ReadsEveryEntityWithExactValues) {
  const SceneDesc scene = read_nff(kTestData / "every_entity.nff");

  ASSERT_TRUE(scene.background.has_value());
  expect_vec3(*scene.background, 0.1f, 0.2f, 0.3f);

  ASSERT_TRUE(scene.camera.has_value());
  const CameraDesc& camera = *scene.camera;
  expect_vec3(camera.from, 1.f, 2.f, 3.f);
  expect_vec3(camera.at, 0.f, 0.f, 0.f);
  expect_vec3(camera.up, 0.f, 0.f, 1.f);
  EXPECT_EQ(camera.angle_degrees, 45.f);
  EXPECT_EQ(camera.hither, 0.5f);
  EXPECT_EQ(camera.width, 640);
  EXPECT_EQ(camera.height, 480);

  // Two lights: the uncoloured one gets SPD's sqrt(N) / (2N), as does the ambient term.
  const float spd = static_cast<float>(std::sqrt(2.0) / 4.0);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].kind, LightDesc::Kind::point);
  expect_vec3(scene.lights[0].position, 4.f, 5.f, 6.f);
  expect_vec3(scene.lights[0].color, spd, spd, spd);
  expect_vec3(scene.lights[1].position, -1.f, -2.f, -3.f);
  expect_vec3(scene.lights[1].color, 0.5f, 0.25f, 1.f);
  expect_vec3(scene.ambient, spd, spd, spd);

  // NFF materials mapped as io/README.md documents.
  ASSERT_EQ(scene.materials.size(), 2u);
  const MaterialDesc& first = scene.materials[0];
  expect_vec3(first.color, 1.f, 0.5f, 0.f);
  EXPECT_EQ(first.ka, 0.7f);
  EXPECT_EQ(first.kd, 0.7f);
  EXPECT_EQ(first.ks, 0.3f);
  EXPECT_EQ(first.kr, 0.3f);
  EXPECT_EQ(first.shininess, 20.f);
  EXPECT_EQ(first.kt, 0.f);
  EXPECT_EQ(first.ior, 1.f);
  EXPECT_FALSE(first.two_sided);
  const MaterialDesc& second = scene.materials[1];
  expect_vec3(second.color, 0.2f, 0.4f, 0.6f);
  EXPECT_EQ(second.kd, 0.8f);
  EXPECT_EQ(second.ks, 0.f);
  EXPECT_EQ(second.kr, 0.f);
  EXPECT_EQ(second.shininess, 100000.f);
  EXPECT_EQ(second.kt, 0.8f);
  EXPECT_EQ(second.ior, 1.5f);
  EXPECT_TRUE(second.two_sided);

  ASSERT_EQ(scene.spheres.size(), 2u);
  expect_vec3(scene.spheres[0].sphere.center, 0.f, 0.f, 0.f);
  EXPECT_EQ(scene.spheres[0].sphere.radius, 0.5f);
  EXPECT_EQ(scene.spheres[0].material, 0u);
  expect_vec3(scene.spheres[1].sphere.center, 1.5f, -2.25f, 300.f);
  EXPECT_EQ(scene.spheres[1].sphere.radius, 1e-3f);
  EXPECT_EQ(scene.spheres[1].material, 0u);

  ASSERT_EQ(scene.polygons.size(), 3u);
  const ScenePolygon& quad = scene.polygons[0];
  ASSERT_EQ(quad.polygon.vertices.size(), 4u);
  expect_vec3(quad.polygon.vertices[0], 0.f, 0.f, 0.f);
  expect_vec3(quad.polygon.vertices[1], 1.f, 0.f, 0.f);
  expect_vec3(quad.polygon.vertices[2], 1.f, 1.f, 0.f);
  expect_vec3(quad.polygon.vertices[3], 0.f, 1.f, 0.f);
  EXPECT_TRUE(quad.normals.empty());
  EXPECT_EQ(quad.material, 1u);

  const ScenePolygon& concave = scene.polygons[1];
  const std::vector<Vec3<float>> l_shape{{0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {1, 1, 1}, {1, 2, 1}, {0, 2, 1}};
  ASSERT_EQ(concave.polygon.vertices.size(), l_shape.size());
  for (std::size_t i = 0; i < l_shape.size(); ++i) {
    SCOPED_TRACE(i);
    expect_vec3(concave.polygon.vertices[i], l_shape[i].x, l_shape[i].y, l_shape[i].z);
  }
  EXPECT_TRUE(concave.normals.empty());
  EXPECT_EQ(concave.material, 1u);

  const ScenePolygon& patch = scene.polygons[2];
  ASSERT_EQ(patch.polygon.vertices.size(), 3u);
  ASSERT_EQ(patch.normals.size(), 3u);
  expect_vec3(patch.polygon.vertices[0], 0.f, 0.f, 2.f);
  expect_vec3(patch.polygon.vertices[1], 1.f, 0.f, 2.f);
  expect_vec3(patch.polygon.vertices[2], 0.f, 1.f, 2.f);
  expect_vec3(patch.normals[0], 0.f, 0.f, 1.f);
  expect_vec3(patch.normals[1], 0.f, 0.6f, 0.8f);
  expect_vec3(patch.normals[2], 0.6f, 0.f, 0.8f);
  EXPECT_EQ(patch.material, 1u);

  ASSERT_EQ(scene.cones.size(), 4u);
  const ConeDesc& cylinder_three_lines = scene.cones[0].cone;
  expect_vec3(cylinder_three_lines.base, 0.f, 0.f, 0.f);
  EXPECT_EQ(cylinder_three_lines.base_radius, 1.f);
  expect_vec3(cylinder_three_lines.apex, 0.f, 0.f, 2.f);
  EXPECT_EQ(cylinder_three_lines.apex_radius, 1.f);
  const ConeDesc& cone_one_line = scene.cones[1].cone;
  expect_vec3(cone_one_line.base, 0.f, 0.f, 0.f);
  EXPECT_EQ(cone_one_line.base_radius, 1.5f);
  expect_vec3(cone_one_line.apex, 0.f, 0.f, 3.f);
  EXPECT_EQ(cone_one_line.apex_radius, 0.25f);
  const ConeDesc& cone_three_lines = scene.cones[2].cone;
  expect_vec3(cone_three_lines.base, 1.f, 1.f, 1.f);
  EXPECT_EQ(cone_three_lines.base_radius, 0.5f);
  expect_vec3(cone_three_lines.apex, 1.f, 1.f, -1.f);
  EXPECT_EQ(cone_three_lines.apex_radius, 0.f);
  const ConeDesc& cylinder_one_line = scene.cones[3].cone;
  expect_vec3(cylinder_one_line.base, 2.f, 0.f, 0.f);
  EXPECT_EQ(cylinder_one_line.base_radius, 0.75f);
  expect_vec3(cylinder_one_line.apex, 2.f, 0.f, 4.f);
  EXPECT_EQ(cylinder_one_line.apex_radius, 0.75f);
  for (const SceneCone& cone : scene.cones) EXPECT_EQ(cone.material, 1u);
}

TEST(NffReader, ReadsCrlfLineEndings) {
  const SceneDesc scene = read_nff(kTestData / "crlf.nff");
  ASSERT_EQ(scene.spheres.size(), 1u);
  expect_vec3(scene.spheres[0].sphere.center, 1.f, 2.f, 3.f);
  EXPECT_EQ(scene.spheres[0].sphere.radius, 4.f);
  ASSERT_EQ(scene.polygons.size(), 1u);
  expect_vec3(scene.polygons[0].polygon.vertices[2], 0.f, 1.f, 0.f);
}

TEST(NffReader, CameraAndBackgroundAreOptional) {
  const SceneDesc scene = read_nff(kTestData / "minimal_no_camera.nff");
  EXPECT_FALSE(scene.camera.has_value());
  EXPECT_FALSE(scene.background.has_value());
  EXPECT_EQ(scene.spheres.size(), 1u);
}

TEST(NffReader, NumberSpellings) {
  const SceneDesc scene = parse_nff(with_material("s +1 .5 -.5e1 2E0\ns 1e-50 -1e-50 1e-40 1\n"), "n.nff");
  ASSERT_EQ(scene.spheres.size(), 2u);
  expect_vec3(scene.spheres[0].sphere.center, 1.f, 0.5f, -5.f);
  EXPECT_EQ(scene.spheres[0].sphere.radius, 2.f);
  // Below float's range: a signed zero, as strtof gives; subnormals are kept.
  const Vec3<float> tiny = scene.spheres[1].sphere.center;
  EXPECT_EQ(tiny.x, 0.f);
  EXPECT_FALSE(std::signbit(tiny.x));
  EXPECT_EQ(tiny.y, 0.f);
  EXPECT_TRUE(std::signbit(tiny.y));
  EXPECT_EQ(tiny.z, 1e-40f);
  EXPECT_GT(tiny.z, 0.f);
}

// ---- patches face where their normals face ----

// A `pp` triangle in the plane z = 0 wound clockwise seen from +z (its
// Newell normal is -z) with vertex normals toward +z.
constexpr std::string_view kClockwisePatch =
    "pp 3\n"
    "-5 -5 0 0 0 1\n"
    "0 5 0 0 0.6 0.8\n"
    "5 -5 0 0.6 0 0.8\n";

TEST(NffReader, PatchWoundAgainstItsNormalsIsReversed) {
  const SceneDesc scene = parse_nff(with_material(kClockwisePatch), "patch.nff");
  ASSERT_EQ(scene.polygons.size(), 1u);
  const ScenePolygon& patch = scene.polygons[0];
  ASSERT_EQ(patch.polygon.vertices.size(), 3u);
  ASSERT_EQ(patch.normals.size(), 3u);
  // Vertices and normals reversed together: each normal stays with its vertex.
  expect_vec3(patch.polygon.vertices[0], 5.f, -5.f, 0.f);
  expect_vec3(patch.polygon.vertices[1], 0.f, 5.f, 0.f);
  expect_vec3(patch.polygon.vertices[2], -5.f, -5.f, 0.f);
  expect_vec3(patch.normals[0], 0.6f, 0.f, 0.8f);
  expect_vec3(patch.normals[1], 0.f, 0.6f, 0.8f);
  expect_vec3(patch.normals[2], 0.f, 0.f, 1.f);
  // A plain polygon has no normals to agree with: kept as written.
  const SceneDesc plain = parse_nff(with_material("p 3\n-5 -5 0\n0 5 0\n5 -5 0\n"), "polygon.nff");
  ASSERT_EQ(plain.polygons.size(), 1u);
  expect_vec3(plain.polygons[0].polygon.vertices[0], -5.f, -5.f, 0.f);
  expect_vec3(plain.polygons[0].polygon.vertices[2], 5.f, -5.f, 0.f);
}

TEST(NffReader, PatchWoundAgainstItsNormalsRendersLit) {
  // Camera and light on +z, where the normals point; the material is
  // one-sided (T = 0). Kd 1 and one uncoloured light (intensity 0.5, the
  // ambient too): the ambient term alone is 0.5, lit head-on 1.
  const std::string text = std::string(kCamera) + "l 0 0 5\n" + std::string(kMaterial) +
                           "pp 3\n-5 -5 0 0 0 1\n0 5 0 0 0 1\n5 -5 0 0 0 1\n";
  const Scene scene = build_scene(parse_nff(text, "patch.nff"), {});
  RenderSettings settings;
  settings.width = settings.height = 33;
  settings.isa = best_supported_isa();
  const Framebuffer image = render(scene, settings).image;
  const std::size_t centre = 16 * 33 + 16;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.rgb[3 * centre + std::size_t(c)], 1.f, 1e-5f) << "channel " << c;
}

// ---- one test per error path: exact position and expected text ----

TEST(NffErrors, MalformedNumber) {
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 x 4\n"), 2, 7, "expected a number (sphere center z), found 'x'"));
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 1.5x 4\n"), 2, 7, "found '1.5x'"));
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 0x10 4\n"), 2, 7, "found '0x10'"));
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 +-3 4\n"), 2, 7, "found '+-3'"));
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 1e 4\n"), 2, 7, "found '1e'"));
}

TEST(NffErrors, MissingValueAtEndOfLine) {
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 3\n"), 2, 8, "expected a number (sphere radius), found end of line"));
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 3  # radius missing\n"), 2, 8, "found end of line"));
}

TEST(NffErrors, ExtraTokenOnLine) {
  EXPECT_TRUE(parse_error_at(with_material("s 1 2 3 4 5\n"), 2, 11,
                             "expected end of line after the sphere (x y z radius), found '5'"));
  EXPECT_TRUE(parse_error_at("b 0 0 0 0\n", 1, 9, "end of line after the background colour, found '0'"));
}

TEST(NffErrors, UnknownEntity) {
  EXPECT_TRUE(parse_error_at("\n  q 1 2\n", 2, 3, "expected an NFF entity (v, b, l, f, c, s, p, pp), found 'q'"));
  EXPECT_TRUE(parse_error_at("from 0 0 0\n", 1, 1, "found 'from'"));  // outside a v block
  EXPECT_TRUE(parse_error_at("\x01\xff\n", 1, 1, "found '\\x01\\xFF'"));
}

TEST(NffErrors, LongTokensAreShortenedInMessages) {
  const std::string long_token(100, 'z');
  EXPECT_TRUE(parse_error_at(long_token, 1, 1, "found '" + std::string(40, 'z') + "...'"));
}

TEST(NffErrors, NanAndInfinity) {
  EXPECT_TRUE(parse_error_at(with_material("s nan 0 0 1\n"), 2, 3, "expected a finite number (sphere center x), found 'nan'"));
  EXPECT_TRUE(parse_error_at(with_material("s 0 -inf 0 1\n"), 2, 5, "a finite number (sphere center y), found '-inf'"));
  EXPECT_TRUE(parse_error_at(with_material("s 0 0 0 Infinity\n"), 2, 9, "a finite number (sphere radius)"));
  EXPECT_TRUE(parse_error_at(with_material("s 0 0 0 1e39\n"), 2, 9,
                             "expected a number within float range (sphere radius), found '1e39'"));
  EXPECT_TRUE(parse_error_at("l 0 0 0 1 NAN 1\n", 1, 11, "a finite number (light colour g)"));
}

TEST(NffErrors, NegativeWhereOnlyNonNegativeMakesSense) {
  EXPECT_TRUE(parse_error_at("b 0.1 -0.2 0\n", 1, 7, "expected a non-negative number (background colour g), found '-0.2'"));
  EXPECT_TRUE(parse_error_at("f 1 1 1 1 -0.5 1 0 1\n", 1, 11, "a non-negative number (material Ks)"));
}

TEST(NffErrors, BadVertexCounts) {
  const std::string expected = "expected a polygon vertex count from 3 to 1000000";
  EXPECT_TRUE(parse_error_at(with_material("p -3\n"), 2, 3, expected + ", found '-3'"));
  EXPECT_TRUE(parse_error_at(with_material("p 0\n"), 2, 3, expected + ", found '0'"));
  EXPECT_TRUE(parse_error_at(with_material("p 2\n0 0 0\n1 0 0\n"), 2, 3, expected + ", found '2'"));
  EXPECT_TRUE(parse_error_at(with_material("p 3.0\n"), 2, 3, expected + ", found '3.0'"));
  EXPECT_TRUE(parse_error_at(with_material("p\n"), 2, 2, expected + ", found end of line"));
  EXPECT_TRUE(parse_error_at(with_material("p 3 4\n"), 2, 5, "end of line after the vertex count, found '4'"));
  EXPECT_TRUE(parse_error_at(with_material("pp 99999999999999999999\n"), 2, 4,
                             "expected a patch vertex count from 3 to 1000000, found '99999999999999999999'"));
}

TEST(NffErrors, TruncatedPolygonBlock) {
  const std::string expected = "expected a polygon vertex line (x y z), found end of file";
  EXPECT_TRUE(parse_error_at(with_material("p 3\n0 0 0\n1 0 0\n"), 5, 1, expected));
  EXPECT_TRUE(parse_error_at(with_material("p 3\n0 0 0\n1 0 0"), 4, 6, expected));  // no final newline
  EXPECT_TRUE(parse_error_at(with_material("p 3\n0 0 0\n1 0 0\n# comment\n"), 6, 1, expected));
  EXPECT_TRUE(parse_error_at(with_material("pp 3\n0 0 0 0 0 1\n"), 4, 1,
                             "expected a patch vertex line (x y z nx ny nz), found end of file"));
}

TEST(NffErrors, MalformedVertexLines) {
  // Too few vertex lines: the next entity is read as a vertex.
  EXPECT_TRUE(parse_error_at(with_material("p 4\n0 0 0\n1 0 0\n0 1 0\ns 0 0 0 1\n"), 6, 1,
                             "expected a number (vertex x), found 's'"));
  EXPECT_TRUE(parse_error_at(with_material("p 3\n0 0 0 1\n"), 3, 7, "end of line after the vertex (x y z), found '1'"));
  EXPECT_TRUE(parse_error_at(with_material("pp 3\n0 0 0\n"), 3, 6, "expected a number (vertex normal x), found end of line"));
}

TEST(NffErrors, PrimitiveBeforeAnyMaterial) {
  const std::string expected = "expected an 'f' material line before the first primitive";
  EXPECT_TRUE(parse_error_at("b 0 0 0\ns 0 0 0 1\n", 2, 1, expected + ", found 's'"));
  EXPECT_TRUE(parse_error_at("p 3\n0 0 0\n1 0 0\n0 1 0\n", 1, 1, expected + ", found 'p'"));
  EXPECT_TRUE(parse_error_at("pp 3\n", 1, 1, expected + ", found 'pp'"));
  EXPECT_TRUE(parse_error_at("c 0 0 0 1 0 0 1 1\n", 1, 1, expected + ", found 'c'"));
}

TEST(NffErrors, IncompleteMaterialAndLight) {
  EXPECT_TRUE(parse_error_at("f 1 1 1 1 0 1 0\n", 1, 16, "expected a number (material index of refraction), found end of line"));
  EXPECT_TRUE(parse_error_at("l 1 2 3 0.5\n", 1, 12, "expected a number (light colour g), found end of line"));
  EXPECT_TRUE(parse_error_at("l 1 2 3 1 1 1 1\n", 1, 15, "end of line after the light, found '1'"));
}

TEST(NffErrors, MalformedCones) {
  EXPECT_TRUE(parse_error_at(with_material("c 0 0 0 1 0 0 1\n"), 2, 16, "expected a number (cone apex radius), found end of line"));
  EXPECT_TRUE(parse_error_at(with_material("c\n0 0 0 1 0\n"), 3, 9, "end of line after the cone base (x y z radius), found '0'"));
  EXPECT_TRUE(parse_error_at(with_material("c\n0 0 0 1\n"), 4, 1, "expected the cone apex line (x y z radius), found end of file"));
  EXPECT_TRUE(parse_error_at(with_material("c\n"), 3, 1, "expected the cone base line (x y z radius), found end of file"));
}

TEST(NffErrors, CameraBlockOutOfOrderOrTruncated) {
  EXPECT_TRUE(parse_error_at("v\nat 0 0 0\n", 2, 1, "expected 'from' (next line of the 'v' camera block), found 'at'"));
  EXPECT_TRUE(parse_error_at("v\nfrom 0 0 5\nat 0 0 0\n", 4, 1, "expected 'up' (next line of the 'v' camera block), found end of file"));
  EXPECT_TRUE(parse_error_at("v 1\n", 1, 3, "end of line after 'v'"));
  EXPECT_TRUE(parse_error_at(std::string(kCamera) + "v\n", 8, 1, "expected at most one 'v' camera block, found 'v'"));
  EXPECT_TRUE(parse_error_at("v\nfrom 0 0 5 1\n", 2, 12, "end of line after the 'from' point, found '1'"));
}

TEST(NffErrors, CameraGeometryThatDefinesNoView) {
  EXPECT_TRUE(parse_error_at("v\nfrom 1 2 3\nat 1 2 3\n", 3, 4, "expected an 'at' point different from 'from', found '1'"));
  EXPECT_TRUE(parse_error_at("v\nfrom 0 0 5\nat 0 0 0\nup 0 0 -2\n", 4, 4, "expected an 'up' vector not parallel to at - from"));
  EXPECT_TRUE(parse_error_at("v\nfrom 0 0 5\nat 0 0 0\nup 0 0 0\n", 4, 4, "not parallel to at - from (nor zero)"));
}

TEST(NffErrors, AngleOutsideOpenRange) {
  const std::string head = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\n";
  const std::string expected = "expected a field of view strictly between 0 and 180 degrees";
  EXPECT_TRUE(parse_error_at(head + "angle 0\n", 5, 7, expected + ", found '0'"));
  EXPECT_TRUE(parse_error_at(head + "angle 180\n", 5, 7, expected + ", found '180'"));
  EXPECT_TRUE(parse_error_at(head + "angle -45\n", 5, 7, expected + ", found '-45'"));
  EXPECT_TRUE(parse_error_at(head + "angle nan\n", 5, 7, "a finite number (field of view in degrees)"));
  EXPECT_TRUE(parse_error_at(head + "angle 45\nhither -1\n", 6, 8, "a non-negative number (hither distance), found '-1'"));
}

TEST(NffErrors, ResolutionOutOfBounds) {
  const std::string head = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n";
  EXPECT_TRUE(parse_error_at(head + "resolution 0 512\n", 7, 12, "expected an image width from 1 to 65536, found '0'"));
  EXPECT_TRUE(parse_error_at(head + "resolution 512 65537\n", 7, 16, "expected an image height from 1 to 65536, found '65537'"));
  EXPECT_TRUE(parse_error_at(head + "resolution 512.0 512\n", 7, 12, "an image width from 1 to 65536, found '512.0'"));
  EXPECT_TRUE(parse_error_at(head + "resolution 512\n", 7, 15, "an image height from 1 to 65536, found end of line"));
  // Each side allowed, the product (2^29) not.
  EXPECT_TRUE(parse_error_at(head + "resolution 65536 8192\n", 7, 12,
                             "expected at most 268435456 pixels (width * height), found '65536 8192'"));
  const std::string largest = head + "resolution 65536 4096\n" + with_material("s 0 0 0 1\n");  // exactly 2^28
  EXPECT_TRUE(parse_nff(largest, "ok.nff").camera.has_value());
}

// An empty NFF renders a blank image: issue 28 makes it an error, as is
// any NFF without an object (a camera, lights and materials alone).
TEST(NffErrors, NoObjectsIsAnErrorAtTheEndOfTheFile) {
  EXPECT_TRUE(
      parse_error_at("", 1, 1, "expected at least one object (s, c, p or pp), found end of file with no objects"));
  EXPECT_TRUE(parse_error_at("# only a comment\n\n", 3, 1, "found end of file with no objects"));
  EXPECT_TRUE(parse_error_at(std::string(kCamera) + "l 1 1 1\n" + std::string(kMaterial) + "b 0 0 0", 10, 8,
                             "found end of file with no objects"));
  for (const char* object : {"s 0 0 0 1\n", "c\n0 0 0 1\n0 1 0 1\n", "p 3\n0 0 0\n1 0 0\n0 1 0\n",
                             "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n"}) {
    EXPECT_NO_THROW(parse_nff(with_material(object), "test.nff")) << object;
  }
}

TEST(NffErrors, UnreadableFile) {
  const fs::path missing = kTestData / "no_such_file.nff";
  try {
    read_nff(missing);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), missing.string() + ": cannot read an NFF scene: no such file");
    EXPECT_EQ(error.line(), 0u);
  }
  try {
    read_nff(kTestData);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), kTestData.string() + ": cannot read an NFF scene: it is a directory");
  }
}

TEST(NffErrors, AFifoIsRefusedWithoutBlocking) {
  const testing::TemporaryDirectory folder("quiver_nff_fifo");
  const fs::path fifo = folder.path() / "scene.nff";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    read_nff(fifo);  // opening a FIFO with no writer would block
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), fifo.string() + ": cannot read an NFF scene: not a regular file");
  }
}

// ---- bounds: absurd counts fail before anything large is allocated ----

TEST(NffBounds, HugeCountsAndSizesFailWithoutLargeAllocations) {
  const std::string head = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n";
  std::string many_zeros;
  for (int i = 0; i < (1 << 19); ++i) many_zeros += " 0";
  struct Case {
    std::string text;
    std::size_t line, column;
    std::string fragment;
  };
  const std::vector<Case> cases{
      {with_material("p 2000000000\n0 0 0\n"), 2, 3, "found '2000000000'"},
      // At the bound, but the input holds two vertices: nothing may be sized from the count.
      {with_material("p 1000000\n0 0 0\n1 0 0\n"), 5, 1, "found end of file"},
      {with_material("pp 1000000\n0 0 0 0 0 1\n"), 4, 1, "found end of file"},
      {head + "resolution 1000000 1000000\n", 7, 12, "an image width from 1 to 65536, found '1000000'"},
      {with_material("s nan inf 0 1\n"), 2, 3, "a finite number"},
      // A megabyte-long line of tokens: read one at a time, never collected.
      {with_material("s" + many_zeros + "\n"), 2, 11, "end of line after the sphere (x y z radius), found '0'"},
  };
  constexpr std::size_t kLargeAllocation = 64 * 1024;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text.substr(0, 40));
    g_largest_allocation = 0;
    g_track_allocations = true;
    const ::testing::AssertionResult result = parse_error_at(c.text, c.line, c.column, c.fragment);
    g_track_allocations = false;
    EXPECT_TRUE(result);
    EXPECT_LT(g_largest_allocation.load(), kLargeAllocation);
  }
}

// ---- the SPD scenes in ../shared/scenes/spd ----

// Counts from ../shared/scenes/spd/README.md; polygons split by vertex count.
struct SpdCounts {
  std::string_view file;
  std::size_t spheres;
  std::size_t polygons, triangles, quads, gons144;
  std::size_t patches;  // `pp`, all triangles
  std::size_t lights, f_lines, f_transmissive;
};

constexpr SpdCounts kSpdScenes[] = {
    {"balls-s1.nff", 10, 1, 0, 1, 0, 0, 3, 2, 0},
    {"balls-s2.nff", 91, 1, 0, 1, 0, 0, 3, 2, 0},
    {"balls-s4.nff", 7381, 1, 0, 1, 0, 0, 3, 2, 0},
    {"gears-s1.nff", 0, 147, 0, 145, 2, 0, 5, 2, 1},
    {"gears-s4.nff", 0, 9345, 0, 9217, 128, 0, 5, 65, 13},
    {"teapot-s2.nff", 0, 4, 0, 4, 0, 240, 2, 3, 0},
    {"teapot-s6.nff", 0, 36, 0, 36, 0, 2256, 2, 3, 0},
    {"teapot-s12.nff", 0, 144, 0, 144, 0, 9120, 2, 3, 0},
    {"tetra-s1.nff", 0, 4, 4, 0, 0, 0, 1, 1, 0},
    {"tetra-s6.nff", 0, 4096, 4096, 0, 0, 0, 1, 1, 0},
};

fs::path spd_directory() {
  const char* from_environment = std::getenv("QUIVER_SHARED_DIR");
  const fs::path shared = from_environment && *from_environment ? fs::path(from_environment) : fs::path(QUIVER_SHARED_DIR);
  return shared / "scenes" / "spd";
}

TEST(NffSpd, EveryFileLoadsWithTheReadmeCounts) {
  const fs::path directory = spd_directory();
  if (!fs::is_directory(directory)) {
    GTEST_SKIP() << directory << " not found; set QUIVER_SHARED_DIR (CMake cache or environment) "
                 << "to the folder holding scenes/spd";
  }
  for (const SpdCounts& expected : kSpdScenes) {
    SCOPED_TRACE(expected.file);
    const fs::path path = directory / expected.file;
    ASSERT_TRUE(fs::exists(path));
    const SceneDesc scene = read_nff(path);

    EXPECT_EQ(scene.spheres.size(), expected.spheres);
    EXPECT_EQ(scene.cones.size(), 0u);
    EXPECT_EQ(scene.lights.size(), expected.lights);
    EXPECT_EQ(scene.materials.size(), expected.f_lines);
    EXPECT_EQ(std::count_if(scene.materials.begin(), scene.materials.end(),
                            [](const MaterialDesc& m) { return m.kt > 0.f; }),
              static_cast<std::ptrdiff_t>(expected.f_transmissive));

    std::map<std::size_t, std::size_t> polygons_by_vertex_count;
    std::size_t patches = 0;
    for (const ScenePolygon& polygon : scene.polygons) {
      if (polygon.normals.empty()) {
        ++polygons_by_vertex_count[polygon.polygon.vertices.size()];
      } else {
        ++patches;
        EXPECT_EQ(polygon.polygon.vertices.size(), 3u);
        EXPECT_EQ(polygon.normals.size(), 3u);
      }
      EXPECT_LT(polygon.material, scene.materials.size());
    }
    EXPECT_EQ(scene.polygons.size() - patches, expected.polygons);
    EXPECT_EQ(patches, expected.patches);
    std::map<std::size_t, std::size_t> expected_by_vertex_count;
    if (expected.triangles) expected_by_vertex_count[3] = expected.triangles;
    if (expected.quads) expected_by_vertex_count[4] = expected.quads;
    if (expected.gons144) expected_by_vertex_count[144] = expected.gons144;
    EXPECT_EQ(polygons_by_vertex_count, expected_by_vertex_count);

    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->width, 512);
    EXPECT_EQ(scene.camera->height, 512);
    EXPECT_EQ(scene.camera->angle_degrees, 45.f);
    ASSERT_TRUE(scene.background.has_value());
    expect_vec3(*scene.background, 0.078f, 0.361f, 0.753f);
  }
  // Every other .nff there (held-out scenes, for instance) must load too.
  for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
    if (entry.path().extension() != ".nff") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(read_nff(entry.path()));
  }
}

}  // namespace
}  // namespace quiver
