// Instancing (geometry/instances.h, geometry/instance_leaves.h): affine
// maps and their inverses; instances hit what the same meshes flattened
// into world space hit; every unit and traversal finds the same hits bit
// for bit; any-hit agrees with closest-hit per layer; rays leaving an
// instance's surface by the offset rule (with the instance's error bound)
// never hit it again, under transforms that stretch, mirror and move far;
// a scene of many instances stores its mesh once.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "integrator/scene_intersector.h"
#include "integrator/surface.h"
#include "simd/isa.h"

namespace quiver {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// A rotation by `degrees` about the unit axis a, scaled per axis, then moved.
AffineTransform placement(Vec3<double> axis, double degrees, Vec3<double> scale, Vec3<double> shift) {
  const double n = std::sqrt(dot(axis, axis));
  const double x = axis.x / n, y = axis.y / n, z = axis.z / n;
  const double c = std::cos(degrees * std::numbers::pi / 180.0), s = std::sin(degrees * std::numbers::pi / 180.0);
  const double r[3][3] = {{c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s},
                          {y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s},
                          {z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)}};
  const double k[3] = {scale.x, scale.y, scale.z}, b[3] = {shift.x, shift.y, shift.z};
  AffineTransform t;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) t.m[std::size_t(4 * row + col)] = float(r[row][col] * k[col]);
    t.m[std::size_t(4 * row + 3)] = float(b[row]);
  }
  return t;
}

// A bumpy closed sphere of unit size (concave places shadow themselves):
// `rings` x 2 `rings` quads as triangles, with vertex normals; every fifth
// triangle uses material 1 (glass) when `glass`.
std::vector<SceneTriangle> bumpy_sphere(int rings, bool glass) {
  const auto point = [&](int i, int j) {
    const float theta = kPi * float(i) / float(rings), phi = 2.f * kPi * float(j) / float(2 * rings);
    const float r = 1.f + 0.25f * std::sin(3.f * theta) * std::cos(2.f * phi);
    return Vec3<float>(r * std::sin(theta) * std::cos(phi), r * std::cos(theta), r * std::sin(theta) * std::sin(phi));
  };
  std::vector<SceneTriangle> out;
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < 2 * rings; ++j) {
      const Vec3<float> a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      for (const std::array<Vec3<float>, 3>& tri : {std::array{a, b, c}, std::array{a, c, d}}) {
        TriangleDesc t{tri, std::array{normalize(tri[0]), normalize(tri[1]), normalize(tri[2])}, {}};
        const std::size_t material = glass && out.size() % 5 == 0 ? 1 : 0;
        out.push_back({t, material});
      }
    }
  }
  return out;
}

// Placements that exercise the transform: as is, moved, turned and
// stretched, mirrored, stretched 64:1, far away, and sheared.
std::vector<AffineTransform> hard_placements() {
  return {placement({0, 1, 0}, 0, {1, 1, 1}, {0, 0, 0}),
          placement({0, 1, 0}, 30, {1, 1, 1}, {3, 0, 0}),
          placement({1, 2, 3}, 71, {0.5, 2.0, 1.25}, {-3, 1, 0.5}),
          placement({0, 0, 1}, 45, {-1, 1, 1}, {0, 3, -1}),
          placement({1, 1, 0}, 33, {8.0, 0.125, 1.0}, {0, -3, 2}),
          placement({0, 1, 1}, 120, {1, 1, 1}, {4096.5, -2048.25, 1024.125}),
          AffineTransform{{1.f, 40.f, 0.f, -6.f, 0.f, 1.f, 0.f, 0.5f, 0.3f, 12.f, 1.f, 4.f}}};  // sheared 40:1
}

SceneDesc instanced_scene(const std::vector<SceneTriangle>& mesh, const std::vector<AffineTransform>& where) {
  SceneDesc d;
  d.camera = CameraDesc{{0.f, 0.f, 10.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.f, 64, 64};
  d.materials = {MaterialDesc{}, MaterialDesc{.kt = 0.8f, .ior = 1.5f}};
  d.meshes.push_back({"bumpy", mesh});
  for (const AffineTransform& t : where) d.instances.push_back({0, t});
  return d;
}

// The same triangles placed into world space (in double, rounded once) as
// plain triangles, instance after instance; a mirroring placement reverses
// the winding, so front faces stay front faces (as [[meshes]] does).
SceneDesc flattened_scene(const std::vector<SceneTriangle>& mesh, const std::vector<AffineTransform>& where) {
  SceneDesc d = instanced_scene(mesh, {});
  d.meshes.clear();
  for (const AffineTransform& t : where) {
    for (SceneTriangle tri : mesh) {
      for (Vec3<float>& p : tri.triangle.p) {
        Vec3<float> q;
        for (int r = 0; r < 3; ++r) {
          q[r] = float(double(t.at(r, 0)) * p.x + double(t.at(r, 1)) * p.y + double(t.at(r, 2)) * p.z + t.at(r, 3));
        }
        p = q;
      }
      const Vec3<double> a(t.at(0, 0), t.at(0, 1), t.at(0, 2)), b(t.at(1, 0), t.at(1, 1), t.at(1, 2)),
          c(t.at(2, 0), t.at(2, 1), t.at(2, 2));
      if (dot(a, cross(b, c)) < 0.0) std::swap(tri.triangle.p[1], tri.triangle.p[2]);
      tri.triangle.normals.reset();
      d.triangles.push_back(tri);
    }
  }
  return d;
}

// Rays from a box around the scene toward random points near the instances.
RaySoA random_rays(const std::vector<AffineTransform>& where, std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  RaySoA rays;
  for (std::size_t i = 0; i < n; ++i) {
    const AffineTransform& t = where[i % where.size()];
    const Vec3<float> target = apply_point(t, Vec3<float>(unit(rng), unit(rng), unit(rng)));
    const Vec3<float> from = target + Vec3<float>(unit(rng), unit(rng), unit(rng)) * 12.f;
    rays.push({from, target - from, 0.f, std::numeric_limits<float>::infinity()});
  }
  rays.pad();
  return rays;
}

HitSoA closest(const Scene& scene, const RaySoA& rays, Isa isa, BvhTraversal traversal = BvhTraversal::automatic,
               Layers layers = Layers::both) {
  SceneIntersector intersector(kernel_unit_for(isa));
  intersector.set_traversal(traversal);
  HitSoA hits(rays);
  intersector.closest(scene, rays, hits, layers);
  return hits;
}

TEST(AffineTransform, InverseNormalsAndSingularMaps) {
  const AffineTransform m = placement({1, 2, 3}, 71, {0.5, 2.0, -1.25}, {-3, 1, 0.5});
  const std::optional<AffineTransform> w = inverse(m);
  ASSERT_TRUE(w.has_value());
  const Vec3<float> p{0.3f, -1.7f, 2.2f};
  const Vec3<float> back = apply_point(*w, apply_point(m, p));
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(back[a], p[a], 1e-5f);
  // A normal stays normal to every tangent under the inverse transpose.
  const Vec3<float> n = normalize(Vec3<float>(1.f, 1.f, 0.f)), tangent{1.f, -1.f, 0.5f};
  ASSERT_EQ(dot(n, Vec3<float>(1.f, -1.f, 0.f)), 0.f);
  const Vec3<float> along{1.f, -1.f, 0.f};
  EXPECT_NEAR(dot(apply_vector(m, along), apply_normal(*w, n)), 0.f, 1e-5f);
  EXPECT_NE(dot(apply_vector(m, tangent), apply_normal(*w, n)), 0.f);
  AffineTransform flat = m;
  for (int c = 0; c < 3; ++c) flat.m[std::size_t(8 + c)] = 0.f;  // third row zero
  EXPECT_FALSE(inverse(flat).has_value());
  AffineTransform tiny;
  tiny.m[0] = tiny.m[5] = tiny.m[10] = 1e-40f;  // its inverse overflows float
  EXPECT_FALSE(inverse(tiny).has_value());
}

// Flat boxes too (a planar mesh's, of zero extent on one axis): they hold a
// surface, so they are not empty.
TEST(Instances, TransformedBoxesHoldEveryPlacedPoint) {
  const Box boxes[] = {{{-1.f, -2.f, -0.5f}, {1.f, 0.5f, 3.f}},
                       {{0.25f, -2.f, -0.5f}, {0.25f, 0.5f, 3.f}},
                       {{-1.f, 0.5f, -0.5f}, {1.f, 0.5f, 3.f}},
                       {{-1.f, -2.f, 3.f}, {1.f, 0.5f, 3.f}}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  for (const Box& box : boxes) {
    ASSERT_FALSE(is_empty(box));
    for (const AffineTransform& t : hard_placements()) {
      const Box world = transformed_box(box, t);
      for (int k = 0; k < 2000; ++k) {
        Vec3<float> p;
        for (int a = 0; a < 3; ++a) p[a] = k < 8 ? ((k >> a) & 1 ? box.hi[a] : box.lo[a]) : box.lo[a] + unit(rng) * (box.hi[a] - box.lo[a]);
        const Vec3<float> q = apply_point(t, p);
        for (int a = 0; a < 3; ++a) {
          ASSERT_LE(world.lo[a], q[a]);
          ASSERT_GE(world.hi[a], q[a]);
        }
      }
    }
  }
  EXPECT_TRUE(is_empty(transformed_box(empty_box(), hard_placements()[2])));
}

TEST(Instances, BuildRefusesSingularMapsBadMeshesAndIdOverflow) {
  std::vector<InstancedMesh> meshes(1);
  meshes[0].stores[0].count = std::size_t(1) << 30;  // counts only: the build reads bounds and counts
  meshes[0].bounds = {{0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}};
  InstanceTable table;
  const BvhBuildOptions options;
  AffineTransform singular;
  singular.m[5] = 0.f;
  EXPECT_THROW(build_instances(std::vector<Placement>{{0, singular}}, meshes, 0, options, table),
               std::invalid_argument);
  EXPECT_THROW(build_instances(std::vector<Placement>{{1, AffineTransform{}}}, meshes, 0, options, table),
               std::invalid_argument);
  EXPECT_NO_THROW(build_instances(std::vector<Placement>{{0, {}}}, meshes, 0, options, table));
  EXPECT_THROW(build_instances(std::vector<Placement>{{0, {}}, {0, {}}}, meshes, 0, options, table),
               std::length_error);
}

// Each instance hit names the instance and the mesh triangle its flattened
// twin hits, at the same distance to rounding; hit or miss differs only on
// rays that graze an edge (a few in a thousand at most).
TEST(Instances, HitWhatTheFlattenedMeshesHit) {
  const std::vector<SceneTriangle> mesh = bumpy_sphere(12, true);
  const std::vector<AffineTransform> where = hard_placements();
  const Scene instanced = build_scene(instanced_scene(mesh, where), {});
  const Scene flat = build_scene(flattened_scene(mesh, where), {});
  ASSERT_EQ(instanced.instances.size(), where.size());
  ASSERT_EQ(instanced.meshes.size(), 1u);
  const RaySoA rays = random_rays(where, 6000, 11);
  const Isa isa = best_supported_isa();
  const HitSoA a = closest(instanced, rays, isa), b = closest(flat, rays, isa);
  std::size_t hits = 0, differ = 0;
  for (std::size_t i = 0; i < rays.count; ++i) {
    if ((a.id[i] == kNoHit) != (b.id[i] == kNoHit)) {
      ++differ;
      continue;
    }
    if (a.id[i] == kNoHit) continue;
    ++hits;
    const PrimitiveRef ra = instanced.locate(a.id[i]), rb = flat.locate(b.id[i]);
    ASSERT_GE(ra.instance, 0);
    const std::size_t placed = instanced.instances.source[std::size_t(ra.instance)] * mesh.size() +
                               instanced.origin(ra).index;
    if (placed != flat.origin(rb).index) {
      ++differ;
      continue;
    }
    // The same facing normal, in world space.
    const Vec3<float> na = normalize(Vec3<float>(a.ngx[i], a.ngy[i], a.ngz[i]));
    const Vec3<float> nb = normalize(Vec3<float>(b.ngx[i], b.ngy[i], b.ngz[i]));
    EXPECT_GT(dot(na, nb), 0.9999f) << "ray " << i;
    // The same distance but for the rounding of the flattened vertices
    // (16 ulps of the magnitudes), stretched along the ray by its slant.
    const Ray<float> ray = rays.get(i);
    const float length = std::sqrt(dot(ray.direction, ray.direction));
    const float slant = std::max(std::fabs(dot(ray.direction, nb)) / length, 0.01f);
    const float magnitude = std::max({std::fabs(ray.origin.x), std::fabs(ray.origin.y), std::fabs(ray.origin.z)}) +
                            b.t[i] * length;
    EXPECT_LE(std::fabs(a.t[i] - b.t[i]) * length, 16.f * std::numeric_limits<float>::epsilon() * magnitude / slant)
        << "ray " << i;
  }
  EXPECT_GT(hits, rays.count / 2);
  EXPECT_LE(differ, rays.count / 500) << differ << " of " << rays.count;
}

// Every unit and traversal (packets together, one by one, automatic)
// finds the same hits as the scalar unit, bit for bit.
TEST(Instances, EveryUnitAndTraversalFindsTheSameHits) {
  const std::vector<AffineTransform> where = hard_placements();
  const Scene scene = build_scene(instanced_scene(bumpy_sphere(10, true), where), {});
  const RaySoA rays = random_rays(where, 3001, 5);
  const HitSoA reference = closest(scene, rays, Isa::scalar);
  for (Isa isa : kIsas) {
    if (!isa_supported(isa)) continue;
    for (BvhTraversal traversal : {BvhTraversal::automatic, BvhTraversal::packets, BvhTraversal::single}) {
      const HitSoA hits = closest(scene, rays, isa, traversal);
      for (std::size_t i = 0; i < rays.count; ++i) {
        ASSERT_EQ(hits.id[i], reference.id[i]) << isa_name(isa) << " ray " << i;
        ASSERT_EQ(hits.t[i], reference.t[i]) << isa_name(isa) << " ray " << i;
        ASSERT_EQ(hits.u[i], reference.u[i]);
        ASSERT_EQ(hits.v[i], reference.v[i]);
        ASSERT_EQ(hits.ngx[i], reference.ngx[i]);
        ASSERT_EQ(hits.ngy[i], reference.ngy[i]);
        ASSERT_EQ(hits.ngz[i], reference.ngz[i]);
      }
    }
  }
}

// Any hit within (tmin, tmax) exactly where a closest hit lies there, per
// tested layer (the instances' glass triangles are the transmissive one).
TEST(Instances, AnyHitAgreesWithClosestHitPerLayer) {
  const std::vector<AffineTransform> where = hard_placements();
  const Scene scene = build_scene(instanced_scene(bumpy_sphere(10, true), where), {});
  ASSERT_GT(scene.meshes[0].stores[1].count, 0u);
  RaySoA rays = random_rays(where, 2003, 9);
  for (std::size_t i = 0; i < rays.count; ++i) rays.tmax[i] = 0.5f + 0.1f * float(i % 7);  // some end short
  rays.pad();
  for (Isa isa : kIsas) {
    if (!isa_supported(isa)) continue;
    SceneIntersector intersector(kernel_unit_for(isa));
    for (Layers layers : {Layers::opaque, Layers::transmissive, Layers::both}) {
      const HitSoA hits = closest(scene, rays, isa, BvhTraversal::automatic, layers);
      OcclusionSoA occluded(rays);
      intersector.occluded(scene, rays, occluded, layers);
      std::size_t blocked = 0;
      for (std::size_t i = 0; i < rays.count; ++i) {
        ASSERT_EQ(occluded.occluded[i] != 0, hits.id[i] != kNoHit) << isa_name(isa) << " ray " << i;
        if (hits.id[i] == kNoHit) continue;
        ++blocked;
        const bool glass = scene.locate(hits.id[i]).transmissive;
        if (layers != Layers::both) {
          EXPECT_EQ(glass, layers == Layers::transmissive) << "ray " << i;
        }
      }
      EXPECT_GT(blocked, 0u);
    }
  }
}

// Rays leaving an instance hit from the offset origin (the frame's error
// bound plus the instance's) into either side's half space never hit that
// triangle again, under every placement; from the hit point itself they
// do (the test sees acne). (The world ray's bound alone also passed here:
// the instance's term is the analysis' bound on what carrying the ray in
// can lose, kept for transforms no test reaches.)
TEST(Instances, OffsetRaysNeverHitTheirOwnTriangleAgain) {
  const std::vector<AffineTransform> where = hard_placements();
  const Scene scene = build_scene(instanced_scene(bumpy_sphere(16, false), where), {});
  const RaySoA rays = random_rays(where, 4000, 3);
  const Isa isa = best_supported_isa();
  const HitSoA first = closest(scene, rays, isa);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  RaySoA leaving, unmoved;
  std::vector<std::int32_t> from_id;
  for (std::size_t i = 0; i < rays.count; ++i) {
    if (first.id[i] == kNoHit) continue;
    const SurfacePoint s = surface_at(scene, rays.get(i), first.get(i));
    for (float side : {1.f, -1.f}) {
      const Vec3<float> normal = s.geometric * side;
      const Vec3<float> origin = offset_origin(s.position, s.error, normal);
      for (int k = 0; k < 4; ++k) {
        Vec3<float> d{unit(rng), unit(rng), unit(rng)};
        if (dot(d, normal) < 0.f) d = -d;
        d = d + normal * 1e-3f;  // never exactly in the plane
        leaving.push({origin, d, 0.f, std::numeric_limits<float>::infinity()});
        unmoved.push({s.position, d, 0.f, std::numeric_limits<float>::infinity()});
        from_id.push_back(first.id[i]);
      }
    }
  }
  leaving.pad();
  unmoved.pad();
  ASSERT_GT(leaving.count, 8000u);
  const auto self_hits = [&](const RaySoA& rays) {
    const HitSoA again = closest(scene, rays, isa);
    std::size_t n = 0;
    for (std::size_t i = 0; i < rays.count; ++i) n += again.id[i] == from_id[i] ? 1 : 0;
    return n;
  };
  EXPECT_EQ(self_hits(leaving), 0u) << "of " << leaving.count;
  EXPECT_GT(self_hits(unmoved), leaving.count / 100);
}

// The error bound of an instance's hit holds: the computed point lies
// within it of the triangle's true plane (the object triangle placed in
// double), measured along the unit normal, for rays whose direction the
// sheared placement nearly cancels (W d small beside |W| |d|) and for rays
// from far away, where the carried direction's rounding times t is the
// largest part of the error.
TEST(Instances, HitPointsLieWithinTheirErrorBoundOfTheTruePlane) {
  const std::vector<SceneTriangle> mesh = bumpy_sphere(8, false);
  const std::vector<AffineTransform> where = hard_placements();
  const Scene scene = build_scene(instanced_scene(mesh, where), {});
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  RaySoA rays;
  for (std::size_t i = 0; i < 20000; ++i) {
    const AffineTransform& t = where[i % where.size()];
    const Vec3<float> target = apply_point(t, Vec3<float>(unit(rng), unit(rng), unit(rng)) * 0.8f);
    // Along the shear's near-null direction (40, -1, ...) half the time, else from 10^4 away.
    const Vec3<float> along = i % 2 == 0 ? Vec3<float>(40.f, -1.f, 0.3f * unit(rng)) * 1000.f
                                         : Vec3<float>(unit(rng), unit(rng), unit(rng)) * 1e4f;
    rays.push({target + along, -along, 0.f, std::numeric_limits<float>::infinity()});
  }
  rays.pad();
  const HitSoA hits = closest(scene, rays, best_supported_isa());
  std::size_t checked = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < rays.count; ++i) {
    if (hits.id[i] == kNoHit) continue;
    const SurfacePoint s = surface_at(scene, rays.get(i), hits.get(i));
    if (s.ref.instance < 0) continue;
    const std::size_t row = std::size_t(s.ref.instance);
    const AffineTransform& m = scene.instances.object_to_world[row];
    const TriangleDesc& tri = mesh[scene.origin(s.ref).index].triangle;
    std::array<std::array<double, 3>, 3> v{};
    for (int k = 0; k < 3; ++k) {
      for (int r = 0; r < 3; ++r) {
        v[k][r] = double(m.at(r, 0)) * tri.p[k].x + double(m.at(r, 1)) * tri.p[k].y + double(m.at(r, 2)) * tri.p[k].z +
                  double(m.at(r, 3));
      }
    }
    const std::array<double, 3> e1{v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const std::array<double, 3> e2{v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double distance = 0.0, bound = 0.0;
    for (int a = 0; a < 3; ++a) {
      n[a] /= length;
      distance += n[a] * (double(s.position[a]) - v[0][a]);
      bound += std::fabs(n[a]) * double(s.error[a]);
    }
    worst = std::max(worst, std::fabs(distance) / bound);
    EXPECT_LE(std::fabs(distance), bound) << "ray " << i;
    ++checked;
  }
  ASSERT_GT(checked, 5000u);
  RecordProperty("worst_distance_over_bound", std::to_string(worst));
}

// A scene has transmissive surfaces when an instanced mesh has glass
// triangles, even with none outside the meshes; opaque meshes give none.
TEST(Instances, GlassInAnInstancedMeshMakesTheSceneTransmissive) {
  const std::vector<AffineTransform> where{placement({0, 1, 0}, 0, {1, 1, 1}, {0, 0, 0})};
  std::vector<SceneTriangle> glass = bumpy_sphere(6, false);
  for (SceneTriangle& t : glass) t.material = 1;
  const Scene all_glass = build_scene(instanced_scene(glass, where), {});
  ASSERT_EQ(all_glass.meshes.at(0).stores[0].count, 0u);
  EXPECT_TRUE(all_glass.has_transmissive());
  EXPECT_TRUE(build_scene(instanced_scene(bumpy_sphere(6, true), where), {}).has_transmissive());
  const Scene opaque = build_scene(instanced_scene(bumpy_sphere(6, false), where), {});
  ASSERT_GT(opaque.meshes.at(0).stores[0].count, 0u);
  EXPECT_FALSE(opaque.has_transmissive());
}

// A scene's bytes count each part once, an instanced mesh's stores (not
// its tree, which counts as acceleration) and the origins of both stores.
TEST(Instances, AScenesBytesCountEachInstancedMeshsStoresAndOrigins) {
  const Scene scene =
      build_scene(instanced_scene(bumpy_sphere(8, true), {placement({0, 1, 0}, 0, {1, 1, 1}, {0, 0, 0})}), {});
  ASSERT_EQ(scene.meshes.size(), 1u);
  const InstancedMesh& mesh = scene.meshes[0];
  ASSERT_GT(mesh.stores[0].count, 0u);
  ASSERT_GT(mesh.stores[1].count, 0u);
  const std::size_t origins = bytes_of(scene.mesh_origins[0].of_store[0]) + bytes_of(scene.mesh_origins[0].of_store[1]);
  EXPECT_EQ(origins, sizeof(PrimitiveOrigin) * (scene.mesh_origins[0].of_store[0].capacity() +
                                                scene.mesh_origins[0].of_store[1].capacity()));
  EXPECT_EQ(scene.memory_bytes(), scene.opaque.memory_bytes() + scene.transmissive.memory_bytes() +
                                      bytes_of(scene.material_of_id) + bytes_of(scene.plain_of_id) +
                                      scene.instances.memory_bytes() + mesh.memory_bytes() - mesh.bvh.memory_bytes() +
                                      origins);
  EXPECT_EQ(scene.acceleration_bytes(), scene.instance_bvh.memory_bytes() + mesh.bvh.memory_bytes());
}

// 200 instances store the mesh once: memory within 5% of one instance's
// plus the table and top-level tree.
TEST(Instances, ManyInstancesStoreTheirMeshOnce) {
  const std::vector<SceneTriangle> mesh = bumpy_sphere(24, false);
  std::vector<AffineTransform> many;
  for (int i = 0; i < 200; ++i) many.push_back(placement({0, 1, 0}, 7.0 * i, {1, 1, 1}, {3.0 * (i % 20), 0, 3.0 * (i / 20)}));
  const Scene one = build_scene(instanced_scene(mesh, {many[0]}), {});
  const Scene scene = build_scene(instanced_scene(mesh, many), {});
  const auto total = [](const Scene& s) { return double(s.memory_bytes() + s.acceleration_bytes()); };
  const double table = double(scene.instances.memory_bytes() + scene.instance_bvh.memory_bytes());
  EXPECT_LE(total(scene), 1.05 * (total(one) + table));
  EXPECT_EQ(scene.primitive_count(), one.primitive_count());
}

}  // namespace
}  // namespace quiver
