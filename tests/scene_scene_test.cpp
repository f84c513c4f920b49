// The built scene (scene/scene.h): its bounds hold every built primitive of
// every kind in both layers, whichever comes first in its store.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include "geometry/primitive_bounds.h"

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

template <class Store>
void expect_held(const Scene& scene, const Store& store) {
  for (std::size_t i = 0; i < store.count; ++i) EXPECT_TRUE(holds(scene.bounds_min, scene.bounds_max, primitive_box(store, i)));
}

TEST(Scene, BoundsHoldEveryBuiltPrimitiveOfEveryKindAndLayer) {
  SceneDesc desc;
  desc.camera = kCamera;
  MaterialDesc glass;
  glass.kt = 0.8f;
  desc.materials = {MaterialDesc{}, glass};
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
  SceneDesc cone_alone;
  cone_alone.camera = kCamera;
  cone_alone.materials = {MaterialDesc{}};
  cone_alone.cones.push_back({{{5.f, 5.f, 5.f}, 1.f, {5.f, 8.f, 5.f}, 1.f}, 0});
  const Scene alone = build_scene(cone_alone, {});
  expect_held(alone, alone.opaque.store<ConeKind>());
  EXPECT_GE(alone.bounds_min.x, 3.f);
}

}  // namespace
}  // namespace quiver
