// A built scene's fields (scene/scene_fields.h): a scene copied field by
// field through bytes renders the same bits as the scene it was copied from,
// colour and every AOV, for a scene with every kind in both layers and in
// BVHs, image and checker textures, instanced meshes and every light kind
// (what quiver-mpi's ranks receive from rank 0).
#include "scene/scene_fields.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "integrator/render.h"
#include "io/scene_loader.h"
#include "tests/support/same_bits.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = fs::path(QUIVER_TEST_DATA_DIR) / "toml";

struct ByteWriter {
  static constexpr bool kReading = false;
  std::vector<std::byte> out;

  void bytes(const void* data, std::size_t size) {
    const auto* at = static_cast<const std::byte*>(data);
    out.insert(out.end(), at, at + size);
  }
  void count(const std::size_t& n, std::size_t) { bytes(&n, sizeof n); }
};

struct ByteReader {
  static constexpr bool kReading = true;
  std::span<const std::byte> in;
  std::size_t at = 0;

  void bytes(void* data, std::size_t size) {
    if (size > in.size() - at) throw std::out_of_range("scene bytes end early");
    std::memcpy(data, in.data() + at, size);
    at += size;
  }
  void count(std::size_t& n, std::size_t element_bytes) {
    bytes(&n, sizeof n);
    if (element_bytes != 0 && n > (in.size() - at) / element_bytes) {
      throw std::out_of_range("a list longer than the bytes left");
    }
  }
};

// every_key.toml (every light kind, checker and image textures, a
// transmissive material, meshes placed as instances) with enough of every
// bounded kind in both layers that each gets a BVH.
SceneDesc rich_scene() {
  SceneLoadOptions options;
  options.allow_outside_paths = true;  // its image lies in a sibling folder
  SceneDesc desc = load_scene(kTestData / "every_key.toml", options);
  std::size_t opaque = 0, transmissive = 0;
  while (transmissive < desc.materials.size() && !(desc.materials[transmissive].kt > 0.f)) ++transmissive;
  EXPECT_LT(transmissive, desc.materials.size()) << "a transmissive material";
  while (opaque < desc.materials.size() && desc.materials[opaque].kt > 0.f) ++opaque;
  for (int i = 0; i < 24; ++i) {
    const float x = float(i % 6) - 2.5f, z = float(i / 6) - 1.5f;
    const std::size_t material = i % 2 == 0 ? opaque : transmissive;
    desc.spheres.push_back({{{x, 0.2f, z}, 0.15f}, material});
    SceneTriangle triangle{};
    triangle.triangle.p = {Vec3<float>{x, 0.5f, z}, {x + 0.3f, 0.5f, z}, {x, 0.8f, z + 0.1f}};
    triangle.material = material;
    desc.triangles.push_back(triangle);
    desc.cones.push_back({{{x, -0.5f, z}, 0.1f, {x, -0.2f, z}, 0.05f}, material});
    ScenePolygon quad;
    quad.polygon.vertices = {{x, 1.f, z}, {x + 0.3f, 1.f, z}, {x + 0.3f, 1.2f, z}, {x, 1.25f, z}};
    quad.material = material;
    desc.polygons.push_back(quad);
  }
  // A mesh of both layers placed twice, once mirrored.
  SceneMesh mesh{"fan", {}};
  for (int i = 0; i < 20; ++i) {
    const float a = 0.3f * float(i), b = 0.3f * float(i + 1);
    SceneTriangle t{};
    t.triangle.p = {Vec3<float>{0.f, 0.f, 0.f}, {std::cos(a), 0.3f, std::sin(a)}, {std::cos(b), 0.3f, std::sin(b)}};
    t.material = i % 3 == 0 ? transmissive : opaque;
    mesh.triangles.push_back(t);
  }
  desc.meshes.push_back(mesh);
  AffineTransform moved, mirrored;
  moved.m[3] = -1.f;
  mirrored.m[0] = -0.5f;
  mirrored.m[11] = 0.5f;
  desc.instances.push_back({desc.meshes.size() - 1, moved});
  desc.instances.push_back({desc.meshes.size() - 1, mirrored});
  return desc;
}

TEST(SceneFields, ASceneCopiedThroughBytesRendersTheSameBits) {
  SceneDesc desc = rich_scene();
  const Scene scene = build_scene(desc, SceneBuildOptions{});
  EXPECT_FALSE(scene.bvh<SphereKind>().empty());
  EXPECT_FALSE(scene.bvh<TriangleKind>().empty());
  EXPECT_FALSE(scene.bvh<PolygonKind>().empty());
  EXPECT_FALSE(scene.bvh<ConeKind>().empty());
  ASSERT_GT(scene.instances.size(), 0u);
  ASSERT_TRUE(scene.has_transmissive());

  ByteWriter writer;
  transfer_scene(writer, scene);
  ByteReader reader{writer.out};
  Scene copy;
  transfer_scene(reader, copy);
  EXPECT_EQ(reader.at, writer.out.size()) << "every byte read";
  EXPECT_EQ(copy.primitive_count(), scene.primitive_count());

  RenderSettings settings;
  settings.width = 64;
  settings.height = 40;
  settings.aa = parse_anti_aliasing("jitter:2");
  settings.aov_depth = settings.aov_normal = settings.aov_id = true;
  settings.threads = 1;
  const Framebuffer a = render(scene, settings).image, b = render(copy, settings).image;
  EXPECT_TRUE(testing::same_bits(a.rgb, b.rgb));
  EXPECT_TRUE(testing::same_bits(a.depth, b.depth));
  EXPECT_TRUE(testing::same_bits(a.normal, b.normal));
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.id, b.id);
  std::size_t hit = 0;
  for (const std::int32_t id : a.id) hit += id >= 0 ? 1 : 0;
  EXPECT_GT(hit, a.id.size() / 4) << "the view sees the scene";
}

TEST(SceneFields, BytesThatEndEarlyAreRefused) {
  SceneDesc desc = rich_scene();
  const Scene scene = build_scene(desc, SceneBuildOptions{});
  ByteWriter writer;
  transfer_scene(writer, scene);
  for (const std::size_t keep : {std::size_t{0}, std::size_t{7}, writer.out.size() / 2, writer.out.size() - 1}) {
    ByteReader reader{std::span(writer.out).first(keep)};
    Scene copy;
    EXPECT_THROW(transfer_scene(reader, copy), std::out_of_range) << keep << " bytes";
  }
}

}  // namespace
}  // namespace quiver
