// The scene intersector (integrator/scene_intersector.h) and the product's
// streams: through the study's streams (tests/support/study_streams.h),
// BVHs of every node width over every bounded kind, both layers and
// instances give the scan's closest hits and occlusion bit for bit; the
// product's streams walk its node width only and refuse another by name, as
// its kind functions refuse the methods only the study builds.
#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrator/scene_intersector.h"
#include "simd/isa.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver {
namespace {

using testing::RaySampler;

// A triangle at corner c with its other corners within size of it.
TriangleDesc shard(RaySampler& s, const Vec3<float>& c, float size) {
  const Vec3<float> b = c + s.in_box({0, 0, 0}, {size, size, size});
  return TriangleDesc{{c, b, c + s.in_box({0, 0, 0}, {size, size, size})}, {}, {}};
}

// Every bounded kind in both layers (material 1 transmits), a plane, and
// a mesh placed twice.
SceneDesc every_kind_in_both_layers(RaySampler& s) {
  SceneDesc d;
  d.camera = CameraDesc{{0.f, 0.f, -12.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.f, 64, 48};
  d.materials = {MaterialDesc{}, MaterialDesc{}};
  d.materials[1].kt = 0.5f;
  const Vec3<float> lo{-4.f, -4.f, -4.f}, hi{4.f, 4.f, 4.f};
  for (int i = 0; i < 60; ++i) {
    const std::size_t m = std::size_t(i % 2);
    const Vec3<float> c = s.in_box(lo, hi);
    d.spheres.push_back({{c, s.uniform(0.1f, 0.4f)}, m});
    d.triangles.push_back({shard(s, c, 1.f), m});
    const Vec3<float> p = s.in_box(lo, hi);
    d.polygons.push_back({{{p, p + Vec3<float>(0.6f, 0.f, 0.f), p + Vec3<float>(0.7f, 0.5f, 0.f),
                            p + Vec3<float>(0.f, 0.4f, 0.1f)}},
                          {},
                          m});
    const Vec3<float> b = s.in_box(lo, hi);
    d.cones.push_back({{b, 0.3f, b + s.in_box({-1, -1, -1}, {1, 1, 1}), s.uniform(0.f, 0.3f)}, m});
  }
  d.planes.push_back({{{0.f, -5.f, 0.f}, {0.f, 1.f, 0.f}}, 0});
  SceneMesh mesh{"shards", {}};
  for (int i = 0; i < 40; ++i) {
    const Vec3<float> c = s.in_box({-1, -1, -1}, {1, 1, 1});
    mesh.triangles.push_back({shard(s, c, 0.5f), std::size_t(i % 2)});
  }
  d.meshes.push_back(mesh);
  AffineTransform left, right;
  left.m[3] = -2.f;
  right.m[3] = 2.5f;
  right.m[0] = 1.5f;
  d.instances = {{0, left}, {0, right}};
  return d;
}

RaySoA random_rays(RaySampler& s, std::size_t count) {
  RaySoA rays;
  for (std::size_t i = 0; i < count; ++i) {
    rays.push(s.toward(s.in_box({-6, -6, -6}, {6, 6, 6}), s.in_box({-4, -4, -4}, {4, 4, 4})));
  }
  rays.pad();
  return rays;
}

struct Answers {
  HitSoA hits;
  OcclusionSoA occlusion;
};

Answers answers(const SceneIntersector& intersector, const Scene& scene, const RaySoA& rays) {
  Answers a{HitSoA(rays), OcclusionSoA(rays)};
  intersector.closest(scene, rays, a.hits);
  intersector.occluded(scene, rays, a.occlusion, Layers::both);
  return a;
}

TEST(SceneIntersector, EveryNodeWidthGivesTheScansHitsInEveryUnit) {
  RaySampler s(5);
  const SceneDesc desc = every_kind_in_both_layers(s);
  const RaySoA rays = random_rays(s, 3000);
  SceneBuildOptions scan;
  scan.acceleration = Acceleration::none;
  const Scene scanned = build_scene(desc, scan);
  const Answers expected = answers(SceneIntersector(KernelUnit::scalar), scanned, rays);
  ASSERT_GT(expected.hits.hit_count(), rays.count / 10);
  for (int width : kStudyNodeWidths) {
    SceneBuildOptions indexed;
    indexed.bvh_min_primitives = 1;
    indexed.bvh.width = width;
    const Scene scene = build_scene(desc, indexed);
    ASSERT_FALSE(scene.bvh<TriangleKind>().empty());
    ASSERT_FALSE(scene.instance_bvh.empty());
    for (const KernelUnit unit : kKernelUnits) {
      if (!kernel_unit_supported(unit)) continue;  // this CPU lacks it: the others still run
      SCOPED_TRACE(::testing::Message() << "node width " << width << ", " << kernel_unit_name(unit));
      const SceneIntersector study(unit, SphereMethod::robust, study_scene_streams(unit, SphereMethod::robust));
      const Answers got = answers(study, scene, rays);
      // Hits are compared by what they hit (a BVH reorders its stores, so ids differ).
      std::size_t differing = 0;
      for (std::size_t i = 0; i < rays.count; ++i) {
        const bool same_t = got.hits.t[i] == expected.hits.t[i];
        const bool same_miss = (got.hits.id[i] == kNoHit) == (expected.hits.id[i] == kNoHit);
        const bool same_block = got.occlusion.occluded[i] == expected.occlusion.occluded[i];
        differing += !(same_t && same_miss && same_block);
      }
      EXPECT_EQ(differing, 0u);
    }
  }
}

TEST(SceneIntersector, TheProductWalksItsNodeWidthOnly) {
  RaySampler s(6);
  const SceneDesc desc = every_kind_in_both_layers(s);
  const RaySoA rays = random_rays(s, 64);
  for (int width : kStudyNodeWidths) {
    SceneBuildOptions indexed;
    indexed.bvh_min_primitives = 1;
    indexed.bvh.width = width;
    const Scene scene = build_scene(desc, indexed);
    const SceneIntersector product(KernelUnit::scalar);
    HitSoA hits(rays);
    if (width == kProductNodeWidth) {
      EXPECT_NO_THROW(product.closest(scene, rays, hits));
      continue;
    }
    try {
      product.closest(scene, rays, hits);
      ADD_FAILURE() << "the product walked a tree of node width " << width;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("node width " + std::to_string(width)), std::string::npos) << e.what();
    }
  }
}

TEST(SceneIntersector, TheProductsKindsRefuseTheStudysMethods) {
  constexpr KernelUnit U = KernelUnit::scalar;
  EXPECT_THROW((product_streams_of<U, SphereKind>(SphereMethod::geometric)), std::invalid_argument);
  EXPECT_THROW((product_streams_of<U, TriangleKind>(TriangleMethod::moller_trumbore)), std::invalid_argument);
  EXPECT_THROW((product_streams_of<U, PlaneKind>(PlaneMethod::seed)), std::invalid_argument);
  // The product runs packets: no scan orientation, one node width; no walks for unbounded kinds.
  const ProductStreams product = product_kind_streams<U>(KindMethods{});
  for_each_kind([&]<class K>(K) {
    const KindStreams<K>& streams = product.of<K>();
    EXPECT_NE(streams.scan.closest_packets, nullptr) << K::name;
    EXPECT_EQ(streams.scan.closest_scan, nullptr) << K::name;
    for (int width : kStudyNodeWidths) EXPECT_EQ(streams.tree.walks(width), K::bounded && width == kProductNodeWidth) << K::name << " " << width;
  });
}

}  // namespace
}  // namespace quiver
