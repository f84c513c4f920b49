// The built scene (scene/scene.h): its bounds hold every built primitive of
// every kind in both layers, whichever comes first in its store; polygons of
// three vertices are built as triangles that keep their origin.
#include "scene/scene.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/primitive_bounds.h"
#include "tests/support/same_bits.h"

namespace quiver {
namespace {

// lo <= box.lo and box.hi <= hi on every axis.
::testing::AssertionResult holds(const Vec3<float>& lo, const Vec3<float>& hi, const Box& box) {
  for (int a = 0; a < 3; ++a) {
    if (!(lo[a] <= box.lo[a] && box.hi[a] <= hi[a])) {
      return ::testing::AssertionFailure() << "axis " << a << ": [" << box.lo[a] << ", " << box.hi[a]
                                           << "] outside [" << lo[a] << ", " << hi[a] << "]";
    }
  }
  return ::testing::AssertionSuccess();
}

const CameraDesc kCamera{{0.f, 0.f, 200.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.f, 16, 16};

// A scene seen from kCamera with these materials and `textures` default textures.
SceneDesc scene_with(std::vector<MaterialDesc> materials, std::size_t textures = 0) {
  SceneDesc desc;
  desc.camera = kCamera;
  desc.materials = std::move(materials);
  desc.textures.resize(textures);
  return desc;
}

template <class Store>
void expect_held(const Scene& scene, const Store& store) {
  for (std::size_t i = 0; i < store.count; ++i) EXPECT_TRUE(holds(scene.bounds_min, scene.bounds_max, primitive_box(store, i)));
}

TEST(Scene, BoundsHoldEveryBuiltPrimitiveOfEveryKindAndLayer) {
  MaterialDesc glass;
  glass.kt = 0.8f;
  SceneDesc desc = scene_with({MaterialDesc{}, glass});
  // Each kind's first primitive lies farthest out, on an axis of its own.
  for (std::size_t m = 0; m < 2; ++m) {
    const float side = m == 0 ? 1.f : -1.f;
    desc.spheres.push_back({{{40.f * side, 0.f, 0.f}, 1.f}, m});
    desc.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, m});
    desc.cones.push_back({{{0.f, 50.f * side, 0.f}, 2.f, {0.f, 52.f * side, 0.f}, 1.f}, m});
    desc.cones.push_back({{{1.f, 0.f, 0.f}, 0.5f, {1.f, 1.f, 0.f}, 0.f}, m});
    SceneTriangle far_triangle{};
    far_triangle.triangle.p = {Vec3<float>{0.f, 0.f, 60.f * side}, Vec3<float>{1.f, 0.f, 60.f * side},
                               Vec3<float>{0.f, 1.f, 60.f * side}};
    far_triangle.material = m;
    desc.triangles.push_back(far_triangle);
    desc.polygons.push_back({{{{70.f * side, 70.f, 0.f}, {71.f * side, 70.f, 0.f}, {71.f * side, 71.f, 0.f},
                               {70.f * side, 71.f, 0.f}, {70.5f * side, 71.5f, 0.f}}},
                             {},
                             m});
  }
  const Scene scene = build_scene(desc, {});
  for (const GeometryLayer* layer : {&scene.opaque, &scene.transmissive}) {
    EXPECT_EQ(layer->store<ConeKind>().count, 2u);
    expect_held(scene, layer->store<SphereKind>());
    expect_held(scene, layer->store<TriangleKind>());
    expect_held(scene, layer->store<PolygonKind>());
    expect_held(scene, layer->store<ConeKind>());
  }
  // A scene of one cone alone is bounded by it.
  SceneDesc cone_alone = scene_with({MaterialDesc{}});
  cone_alone.cones.push_back({{{5.f, 5.f, 5.f}, 1.f, {5.f, 8.f, 5.f}, 1.f}, 0});
  const Scene alone = build_scene(cone_alone, {});
  expect_held(alone, alone.opaque.store<ConeKind>());
  EXPECT_GE(alone.bounds_min.x, 3.f);
  // A scene of one triangle in the plane x = 7: a flat box, not an empty one.
  SceneDesc flat = scene_with({MaterialDesc{}});
  SceneTriangle upright{};
  upright.triangle.p = {Vec3<float>{7.f, 0.f, 0.f}, Vec3<float>{7.f, 1.f, 0.f}, Vec3<float>{7.f, 0.f, 1.f}};
  flat.triangles.push_back(upright);
  const Scene flat_scene = build_scene(flat, {});
  expect_held(flat_scene, flat_scene.opaque.store<TriangleKind>());
  EXPECT_EQ(flat_scene.bounds_min.x, 7.f);
  EXPECT_EQ(flat_scene.bounds_max.x, 7.f);
}

// A material naming a texture past the last, or a primitive a material past
// the last, is refused (the last one itself is fine).
TEST(Scene, RefusesIndicesOnePastTheEnd) {
  MaterialDesc textured;
  textured.texture = 1;
  SceneDesc desc = scene_with({MaterialDesc{}, textured}, 2);
  desc.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, 1});
  EXPECT_NO_THROW(build_scene(desc, {}));
  desc.materials[1].texture = 2;
  EXPECT_THROW(build_scene(desc, {}), std::invalid_argument);
  desc.materials[1].texture = 1;
  desc.spheres.push_back({{{3.f, 0.f, 0.f}, 1.f}, 2});
  EXPECT_THROW(build_scene(desc, {}), std::invalid_argument);
}

// Polygons of three vertices (after consecutive duplicates go) become
// triangles, as stored, with their origin (kind polygon, their index) and,
// textured, the polygon kernel's u, v (each corner projected on the
// dominant plane relative to the first vertex); quads and polygons the
// polygon builder drops stay polygons.
TEST(Scene, ThreeVertexPolygonsAreBuiltAsTrianglesThatKeepTheirOrigin) {
  MaterialDesc textured;
  textured.texture = 0;
  SceneDesc desc = scene_with({MaterialDesc{}, textured}, 1);
  using V = Vec3<float>;
  // Normal mostly along x (the dropped axis): u along y, v along z.
  const std::vector<V> slanted{{0.f, 0.f, 0.f}, {0.25f, 2.f, 0.f}, {0.5f, 0.f, 3.f}};
  desc.polygons.push_back({{slanted}, {}, 0});
  desc.polygons.push_back({{{{0.f, 0.f, 5.f}, {1.f, 0.f, 5.f}, {1.f, 1.f, 5.f}, {0.f, 1.f, 5.f}}}, {}, 0});  // a quad
  desc.polygons.push_back({{{{2.f, 0.f, 5.f}, {3.f, 0.f, 5.f}, {3.f, 0.f, 5.f}, {2.f, 1.f, 5.f}}}, {}, 0});  // a repeat
  desc.polygons.push_back({{{{0.f, 0.f, 9.f}, {1.f, 0.f, 9.f}, {2.f, 0.f, 9.f}}}, {}, 0});  // collinear
  desc.polygons.push_back({{slanted}, {}, 1});
  const Scene scene = build_scene(desc, {});
  const TriangleSoA& triangles = scene.opaque.store<TriangleKind>();
  const std::vector<PrimitiveOrigin>& origins = scene.opaque.origins<TriangleKind>();
  ASSERT_EQ(triangles.count, 3u);
  ASSERT_EQ(origins.size(), 3u);
  std::vector<std::uint32_t> indices;
  for (const PrimitiveOrigin& o : origins) {
    EXPECT_EQ(o.kind, kind_tag<PolygonKind>);
    indices.push_back(o.index);
  }
  std::sort(indices.begin(), indices.end());
  auto xyz = [](const V& v) { return std::array<float, 3>{v.x, v.y, v.z}; };
  EXPECT_EQ(indices, (std::vector<std::uint32_t>{0, 2, 4}));
  EXPECT_EQ(scene.opaque.store<PolygonKind>().count, 1u);
  EXPECT_EQ(scene.counts.kinds[kind_index(kind_tag<PolygonKind>)].dropped_degenerate, 1u);
  ASSERT_TRUE(triangles.has_uvs());
  for (std::size_t i = 0; i < triangles.count; ++i) {
    if (origins[i].index == 2) {
      EXPECT_EQ(xyz(triangles.vertex(i, 1)), xyz(V{3.f, 0.f, 5.f}));
      EXPECT_EQ(xyz(triangles.vertex(i, 2)), xyz(V{2.f, 1.f, 5.f}));
      continue;
    }
    for (int k = 0; k < 3; ++k) EXPECT_EQ(xyz(triangles.vertex(i, k)), xyz(slanted[std::size_t(k)]));
    if (origins[i].index != 4) continue;
    for (int k = 0; k < 3; ++k) {
      const std::array<float, 2> expected{slanted[std::size_t(k)].y, slanted[std::size_t(k)].z};
      EXPECT_EQ(triangles.uv(i, k), expected) << "corner " << k;
    }
  }
}

// Object ids number every primitive as read once over the whole scene:
// each kind's list in kind order (spheres 0 and 1, then the plane 2, the
// triangle 3, the polygon 4, the cone 5), then each instance's mesh
// triangles in the order the instances were read, whichever layer, store
// order or BVH order the builders gave them.
// Every kind in both layers, and instances of two meshes.
SceneDesc every_kind_scene() {
  SceneDesc desc;
  desc.camera = CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.f, 8, 8};
  desc.materials.resize(2);
  desc.materials[1].kt = 0.5f;  // a transmissive layer too
  desc.spheres = {{{{0.f, 0.f, 0.f}, 1.f}, 1}, {{{3.f, 0.f, 0.f}, 1.f}, 0}};
  desc.planes = {{{{0.f, -2.f, 0.f}, {0.f, 1.f, 0.f}}, 0}};
  SceneTriangle t;
  t.triangle.p = {Vec3<float>{0.f, 0.f, 0.f}, Vec3<float>{1.f, 0.f, 0.f}, Vec3<float>{0.f, 1.f, 0.f}};
  t.material = 0;
  desc.triangles = {t};
  ScenePolygon quad;
  quad.polygon.vertices = {{-1.f, -1.f, -1.f}, {1.f, -1.f, -1.f}, {1.f, 1.f, -1.f}, {-1.f, 1.f, -1.f}};
  quad.material = 0;
  desc.polygons = {quad};
  desc.cones = {{{{0.f, 0.f, 0.f}, 1.f, {0.f, 2.f, 0.f}, 0.5f}, 0}};
  SceneMesh small{"small", {t, t, t}}, large{"large", {t, t, t, t, t}};
  for (std::size_t k = 0; k < small.triangles.size(); ++k) small.triangles[k].triangle.p[0].z = float(k);
  for (std::size_t k = 0; k < large.triangles.size(); ++k) large.triangles[k].triangle.p[0].z = float(k);
  large.triangles[2].material = 1;
  desc.meshes = {small, large};
  AffineTransform moved{};
  moved.m = {1.f, 0.f, 0.f, 5.f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f};
  desc.instances = {{1, AffineTransform{}}, {0, moved}, {1, moved}};
  return desc;
}

TEST(Scene, ObjectIdsNumberEveryPrimitiveOnceOverTheWholeScene) {
  const SceneDesc desc = every_kind_scene();
  const Scene scene = build_scene(desc, {});
  // Every hit id: the stores' (material_of_id covers them), then each instance's.
  std::vector<std::int32_t> hit_ids;
  for (std::int32_t id = 0; std::size_t(id) < scene.material_of_id.size(); ++id) hit_ids.push_back(id);
  for (std::size_t row = 0; row < scene.instances.size(); ++row) {
    const std::size_t count = scene.meshes[scene.instances.mesh[row]].triangle_count();
    for (std::size_t k = 0; k < count; ++k) hit_ids.push_back(scene.instances.id_base[row] + std::int32_t(k));
  }
  std::vector<std::uint64_t> ids, sphere_ids, firsts;
  for (const std::int32_t id : hit_ids) {
    const PrimitiveRef ref = scene.locate(id);
    ids.push_back(scene.object_id(ref));
    if (ref.kind == kind_tag<SphereKind> && ref.instance < 0) sphere_ids.push_back(ids.back() * 10 + scene.origin(ref).index);
    if (ref.instance >= 0 && scene.origin(ref).index == 0) firsts.push_back(ids.back());
  }
  std::sort(ids.begin(), ids.end());
  std::vector<std::uint64_t> every(2 + 1 + 1 + 1 + 1 + 5 + 3 + 5);
  for (std::size_t k = 0; k < every.size(); ++k) every[k] = k;
  EXPECT_EQ(ids, every);
  std::sort(sphere_ids.begin(), sphere_ids.end());
  EXPECT_EQ(sphere_ids, (std::vector<std::uint64_t>{0, 11}));  // sphere i is object i
  // The first instance (of the large mesh) starts at 6, the second (small) at 11, the third at 14.
  std::sort(firsts.begin(), firsts.end());
  EXPECT_EQ(firsts, (std::vector<std::uint64_t>{6, 11, 14}));
}

using quiver::testing::same_bits;

// Releasing the triangles' descriptions while building changes nothing built:
// the same stores bit for bit in both layers (in leaf order, under the same
// BVH), origins, object ids and tables; desc keeps everything else.
TEST(Scene, ReleasingTheTrianglesBuildsTheSameScene) {
  SceneDesc desc = every_kind_scene();
  // Enough triangles in both layers for a BVH (their reorder reads the stores' columns only).
  for (int k = 0; k < 300; ++k) {
    SceneTriangle t;
    const float x = float(k % 20), y = float(k / 20);
    t.triangle.p = {Vec3<float>{x, y, 1.f}, Vec3<float>{x + 1.f, y, 1.f}, Vec3<float>{x, y + 1.f, 1.5f}};
    t.triangle.normals =
        std::array{Vec3<float>{0.f, 0.f, 1.f}, Vec3<float>{0.f, 0.1f, 1.f}, Vec3<float>{0.1f, 0.f, 1.f}};
    t.material = k % 3 == 0 ? 1 : 0;
    desc.triangles.push_back(t);
  }
  ScenePolygon corner;  // built as a triangle
  corner.polygon.vertices = {{0.f, 0.f, 2.f}, {1.f, 0.f, 2.f}, {0.f, 1.f, 2.f}};
  corner.material = 1;
  desc.polygons.push_back(corner);
  const Scene kept = build_scene(desc, {});
  ASSERT_FALSE(kept.bvh<TriangleKind>().empty());
  const std::size_t polygons = desc.polygons.size(), instances = desc.instances.size();
  const Scene released = build_scene_releasing_triangles(desc, {});
  EXPECT_TRUE(desc.triangles.empty());
  EXPECT_EQ(desc.triangles.capacity(), 0u);
  EXPECT_EQ(desc.polygons.size(), polygons);
  EXPECT_EQ(desc.instances.size(), instances);
  for (bool transmissive : {false, true}) {
    const auto& a = (transmissive ? kept.transmissive : kept.opaque).kinds.of<TriangleKind>();
    const auto& b = (transmissive ? released.transmissive : released.opaque).kinds.of<TriangleKind>();
    ASSERT_EQ(a.store.count, b.store.count);
    EXPECT_GT(a.store.count, 100u);
    EXPECT_EQ(a.store.source, b.store.source);
    const auto columns_a = a.store.columns(), columns_b = b.store.columns();
    ASSERT_EQ(columns_a.size(), columns_b.size());
    for (std::size_t c = 0; c < columns_a.size(); ++c) EXPECT_TRUE(same_bits(*columns_a[c], *columns_b[c])) << c;
    ASSERT_EQ(a.origins.size(), b.origins.size());
    for (std::size_t i = 0; i < a.origins.size(); ++i) {
      EXPECT_EQ(a.origins[i].material, b.origins[i].material);
      EXPECT_EQ(a.origins[i].kind, b.origins[i].kind);
      EXPECT_EQ(a.origins[i].index, b.origins[i].index);
    }
  }
  EXPECT_TRUE(same_bits(kept.bvh<TriangleKind>().nodes, released.bvh<TriangleKind>().nodes));
  EXPECT_EQ(kept.material_of_id, released.material_of_id);
  EXPECT_EQ(kept.plain_of_id, released.plain_of_id);
  EXPECT_EQ(kept.object_id_base, released.object_id_base);
  EXPECT_EQ(kept.instance_object_id_base, released.instance_object_id_base);
  EXPECT_EQ(kept.primitive_count(), released.primitive_count());
}

}  // namespace
}  // namespace quiver
