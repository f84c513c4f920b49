// The `quiver info` report (app/scene_info.h): per-kind memory adds up to the
// layers' own totals, and the count rows show what was read, kept and
// dropped, split into opaque and transmissive.
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/scene_info.h"

namespace quiver {
namespace {

SceneDesc mixed_scene() {
  SceneDesc desc;
  CameraDesc camera{};
  camera.from = {0.f, 0.f, 5.f};
  camera.at = {0.f, 0.f, 0.f};
  camera.up = {0.f, 1.f, 0.f};
  camera.angle_degrees = 45.f;
  camera.width = 8;
  camera.height = 8;
  desc.camera = camera;
  desc.materials.resize(2);
  desc.materials[1].kt = 0.5f;  // transmissive
  const float nan = std::numeric_limits<float>::quiet_NaN();
  desc.spheres = {{{{0.f, 0.f, 0.f}, 1.f}, 0},
                  {{{2.f, 0.f, 0.f}, 0.5f}, 1},
                  {{{3.f, 0.f, 0.f}, 0.f}, 0},     // degenerate
                  {{{nan, 0.f, 0.f}, 1.f}, 0}};    // non-finite
  SceneTriangle triangle;
  triangle.triangle.p = {Vec3<float>{0.f, 0.f, 0.f}, Vec3<float>{1.f, 0.f, 0.f}, Vec3<float>{0.f, 1.f, 0.f}};
  triangle.material = 1;
  desc.triangles = {triangle};
  ScenePolygon quad;
  quad.polygon.vertices = {{-1.f, -1.f, -1.f}, {1.f, -1.f, -1.f}, {1.f, 1.f, -1.f}, {-1.f, 1.f, -1.f}};
  quad.material = 0;
  desc.polygons = {quad};
  desc.planes = {{{{0.f, -2.f, 0.f}, {0.f, 1.f, 0.f}}, 0}};
  desc.cones = {{{{0.f, 0.f, 0.f}, 1.f, {0.f, 2.f, 0.f}, 0.5f}, 1}};
  return desc;
}

// The numbers on the report line starting with "  <name> ".
std::vector<std::size_t> row(const std::string& report, const std::string& name) {
  std::istringstream lines(report);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  " + name + " ", 0) != 0) continue;
    std::istringstream cells(line.substr(name.size() + 2));
    std::vector<std::size_t> numbers;
    for (std::size_t n; cells >> n;) numbers.push_back(n);
    return numbers;
  }
  return {};
}

TEST(SceneInfo, MemoryByKindAddsUpToEachLayer) {
  const Scene scene = build_scene(mixed_scene(), {});
  for (const GeometryLayer* layer : {&scene.opaque, &scene.transmissive}) {
    const auto bytes = memory_by_kind(*layer);
    std::size_t sum = 0;
    for (std::size_t b : bytes) sum += b;
    EXPECT_EQ(sum, layer->memory_bytes());
  }
  const auto opaque = memory_by_kind(scene.opaque);
  EXPECT_GT(opaque[std::size_t(kind_tag<SphereKind>)], 0u);
  EXPECT_GT(opaque[std::size_t(kind_tag<PlaneKind>)], 0u);
  EXPECT_GT(opaque[std::size_t(kind_tag<PolygonKind>)], 0u);
  EXPECT_EQ(opaque[std::size_t(kind_tag<ConeKind>)], 0u);
  const auto transmissive = memory_by_kind(scene.transmissive);
  EXPECT_GT(transmissive[std::size_t(kind_tag<ConeKind>)], 0u);
  EXPECT_GT(transmissive[std::size_t(kind_tag<TriangleKind>)], 0u);
  EXPECT_EQ(transmissive[std::size_t(kind_tag<PlaneKind>)], 0u);
}

// The context of a report on `desc` as read, loaded in 1 ms and built in 2,
// with the process's peak when given.
SceneInfoContext context_of(const SceneDesc& desc, std::optional<std::size_t> peak = std::nullopt) {
  SceneInfoContext context;
  context.scene = "mixed";
  context.load_ms = 1.0;
  context.build_ms = 2.0;
  context.peak_resident_bytes = peak;
  context.read = read_counts(desc);
  return context;
}

TEST(SceneInfo, CountRows) {
  const SceneDesc desc = mixed_scene();
  const Scene scene = build_scene(desc, {});
  std::ostringstream out;
  write_scene_info(out, desc, scene, context_of(desc));
  const std::string report = out.str();
  // read, kept, non-finite, degenerate, opaque, transmissive
  EXPECT_EQ(row(report, "spheres"), (std::vector<std::size_t>{4, 2, 1, 1, 1, 1}));
  EXPECT_EQ(row(report, "planes"), (std::vector<std::size_t>{1, 1, 0, 0, 1, 0}));
  EXPECT_EQ(row(report, "triangles"), (std::vector<std::size_t>{1, 1, 0, 0, 0, 1}));
  EXPECT_EQ(row(report, "polygons"), (std::vector<std::size_t>{1, 1, 0, 0, 1, 0}));
  EXPECT_EQ(row(report, "cones"), (std::vector<std::size_t>{1, 1, 0, 0, 0, 1}));
  EXPECT_EQ(row(report, "total"), (std::vector<std::size_t>{8, 6, 1, 1, 3, 3}));
  EXPECT_NE(report.find("materials       2"), std::string::npos);
  EXPECT_NE(report.find("kt 0.5"), std::string::npos);
  EXPECT_NE(report.find(std::to_string(scene.memory_bytes())), std::string::npos);
}

// A three-vertex polygon is built as a triangle: the report counts it read
// as a polygon, kept as a triangle, and says so on a line of its own.
TEST(SceneInfo, SaysWhichPolygonsWereBuiltAsTriangles) {
  SceneDesc desc = mixed_scene();
  ScenePolygon corner;
  corner.polygon.vertices = {{0.f, 0.f, 1.f}, {1.f, 0.f, 1.f}, {0.f, 1.f, 1.f}};
  corner.material = 0;
  desc.polygons.push_back(corner);
  const Scene scene = build_scene(desc, {});
  std::ostringstream out;
  write_scene_info(out, desc, scene, context_of(desc));
  const std::string report = out.str();
  EXPECT_EQ(row(report, "triangles"), (std::vector<std::size_t>{1, 2, 0, 0, 1, 1}));
  EXPECT_EQ(row(report, "polygons"), (std::vector<std::size_t>{2, 1, 0, 0, 1, 0}));
  EXPECT_NE(report.find("polygons built as triangles: 1 (0 read with vertex normals), as 1 of the triangles kept"),
            std::string::npos)
      << report;
}

// Each light kind, texture kind and wrap, the instances and the face
// tallies get their own line, with the values that describe them.
TEST(SceneInfo, NamesEveryLightTextureInstanceAndFaceTally) {
  SceneDesc desc = mixed_scene();
  LightDesc point, directional, rectangle, sphere, spot;
  point.position = {1.f, 2.f, 3.f};
  directional.kind = LightDesc::Kind::directional;
  directional.direction = {0.f, -1.f, 0.f};
  rectangle.kind = LightDesc::Kind::rectangle;
  rectangle.position = {0.f, 4.f, 0.f};
  rectangle.samples = 3;
  sphere.kind = LightDesc::Kind::sphere;
  sphere.position = {5.f, 5.f, 5.f};
  sphere.radius = 0.25f;
  spot.kind = LightDesc::Kind::spot;
  spot.position = {0.f, 3.f, 0.f};
  spot.cone_inner_cos = 0.5f;  // 60 degrees
  spot.cone_outer_cos = 0.f;   // 90 degrees
  desc.lights = {point, directional, rectangle, sphere, spot};
  TextureDesc checks, solid, image;
  checks.scale = 2.f;
  solid.kind = TextureDesc::Kind::checker3d;
  image.kind = TextureDesc::Kind::image;
  image.wrap = WrapMode::mirror;
  image.width = image.height = 1;
  image.rgb = {1.f, 0.f, 0.f};
  desc.textures = {checks, solid, image};
  SceneMesh mesh{"box.obj", desc.triangles};
  desc.meshes = {mesh};
  desc.instances = {{0, AffineTransform{}}, {0, AffineTransform{}}};
  desc.face_tallies = {{"box.obj", 3, 1}, {"whole.ply", 2, 2}};
  const Scene scene = build_scene(desc, {});
  std::ostringstream out;
  write_scene_info(out, desc, scene, context_of(desc));
  const std::string report = out.str();
  for (const char* line :
       {"lights          5\n", "  0: point position (1 2 3) colour (1 1 1)\n",
        "  1: directional direction (0 -1 0) colour (1 1 1)\n",
        "  2: rectangle corner (0 4 0) edges (1 0 0) (0 0 1) colour (1 1 1) samples 3x3\n",
        "  3: sphere centre (5 5 5) radius 0.25 colour (1 1 1) samples 4x4\n",
        "  4: spot position (0 3 0) direction (0 -1 0) cone 60 to 90 degrees colour (1 1 1)\n",
        "textures        3\n",
        "  0: checker2d colours (1 1 1) (0 0 0) scale 2\n", "  1: checker3d colours",
        "  2: image (in memory) 1x1 wrap mirror\n", "instances       2 placed (of 2 read) of 1 mesh, stored once: 1",
        "  mesh 0: box.obj, 1 triangles\n", "mesh faces      declared, kept\n",
        "  box.obj: 3, 1 (2 not drawn: see the warnings)\n", "  whole.ply: 2, 2\n"}) {
    EXPECT_NE(report.find(line), std::string::npos) << "no '" << line << "' in\n" << report;
  }
  // The instanced mesh's stores once, without its tree (an acceleration structure), and the table.
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_GT(scene.meshes[0].bvh.memory_bytes(), 0u);
  for (const std::string& line :
       {"instanced meshes (stores, once each)  " +
            std::to_string(scene.meshes[0].memory_bytes() - scene.meshes[0].bvh.memory_bytes()) + "\n",
        "instance table                        " + std::to_string(scene.instances.memory_bytes()) + "\n"}) {
    EXPECT_NE(report.find(line), std::string::npos) << "no '" << line << "' in\n" << report;
  }
}

// The peak resident memory against what the scene keeps, when given; the
// process's peak covers memory it has touched.
TEST(SceneInfo, PeakMemoryAgainstWhatTheSceneKeeps) {
  SceneDesc desc = mixed_scene();
  // Enough spheres for a tree: what the scene keeps counts its acceleration too.
  for (int i = 0; i < 20; ++i) desc.spheres.push_back({{{float(i), 9.f, 0.f}, 0.25f}, 0});
  const Scene scene = build_scene(desc, {});
  ASSERT_GT(scene.acceleration_bytes(), 0u);
  std::ostringstream without;
  write_scene_info(without, desc, scene, context_of(desc));
  EXPECT_EQ(without.str().find("peak memory"), std::string::npos);
  std::ostringstream with;
  write_scene_info(with, desc, scene, context_of(desc, 123456789));
  const std::string line = "peak memory     123456789 bytes resident at most (loading and building), for " +
                           std::to_string(scene.memory_bytes() + scene.acceleration_bytes()) +
                           " kept (memory and acceleration totals)\n";
  EXPECT_NE(with.str().find(line), std::string::npos) << with.str();
  std::vector<char> touched(std::size_t(64) << 20);
  for (std::size_t i = 0; i < touched.size(); i += 4096) touched[i] = 1;
  asm volatile("" : : "r"(touched.data()) : "memory");  // the stores happen before the measurement
  EXPECT_GE(peak_resident_bytes(), touched.size());

  EXPECT_EQ(with.str().find("build peak"), std::string::npos);
  SceneInfoContext building = context_of(desc, 123456789);
  building.build_peak_resident_bytes = 23456789;
  building.build_start_resident_bytes = 3456789;
  std::ostringstream build_peak;
  write_scene_info(build_peak, desc, scene, building);
  EXPECT_NE(build_peak.str().find(line + "build peak      23456789 bytes resident at most while the scene was built, "
                                         "from 3456789 when it began (the scene as read)\n"),
            std::string::npos)
      << build_peak.str();
}

// A restarted high-water mark forgets memory touched and freed before, and
// counts what is touched after.
TEST(SceneInfo, ResidentHighWaterRestartsAtTheMemoryResidentNow) {
  constexpr std::size_t kMiB = std::size_t(1) << 20;
  {
    std::vector<char> freed(128 * kMiB, 1);  // a block of its own (mmap): its pages go back when freed
    asm volatile("" : : "r"(freed.data()) : "memory");
  }
  const std::optional<std::size_t> with_freed = process_status_bytes("VmHWM");
  ASSERT_TRUE(with_freed.has_value()) << "/proc/self/status gives no VmHWM";
  const std::optional<std::size_t> resident = process_status_bytes("VmRSS");
  ASSERT_TRUE(resident.has_value()) << "/proc/self/status gives no VmRSS";
  EXPECT_LT(*resident + 64 * kMiB, *with_freed);
  EXPECT_FALSE(process_status_bytes("VmHW").has_value()) << "a key is matched whole";
  EXPECT_GE(*with_freed, 128 * kMiB);
  if (!restart_resident_high_water()) GTEST_SKIP() << "/proc/self/clear_refs refuses to restart the high-water mark";
  const std::size_t restarted = process_status_bytes("VmHWM").value();
  EXPECT_LT(restarted + 64 * kMiB, *with_freed);
  // Above glibc's largest mmap threshold (32 MiB), so fresh pages, never heap memory an earlier test freed.
  std::vector<char> touched(64 * kMiB, 1);
  asm volatile("" : : "r"(touched.data()) : "memory");
  EXPECT_GE(process_status_bytes("VmHWM").value(), restarted + 60 * kMiB);
}

}  // namespace
}  // namespace quiver
