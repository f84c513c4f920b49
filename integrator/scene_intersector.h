// The scene's intersection queries for one kernel unit: each kind in turn,
// through the kind's BVH over both layers where it has one
// (geometry/bvh/bvh_streams.h; leaves of untested layers are skipped), else
// through each tested layer's packet streams (W rays against one primitive),
// with the watertight triangle, crossing polygon, anchored plane and quadric cone
// methods, and the sphere method chosen per scene: the seed's algebraic test
// where no ray origin is more than kAlgebraicSphereMaxDistanceRatio radii from
// a sphere's centre (kAlgebraicSphereMaxDistanceRatio says why), else the
// robust one. HitSoA carries the closest t, so the stores compose; every
// path reports the smallest (t, id), so the order does not matter.
// Instances go through their top-level BVH (geometry/instance_leaves.h)
// into their meshes' triangle BVHs, with the same triangle method.
#pragma once

#include "geometry/instance_streams.h"
#include "geometry/kind_streams.h"
#include "scene/scene.h"

namespace quiver {

// per_scene: the cheaper sphere test where the scene cannot trigger its
// failure; most_robust: the robust methods everywhere.
enum class MethodChoice { per_scene, most_robust };

// Rays start at the camera eye or at hit points; both lie in the box holding
// the scene's bounded primitives and the eye (plane hits are unbounded). The
// largest distance from a sphere's centre to that box over the sphere's
// radius, the largest over the scene's spheres: infinity when the scene has
// planes, 0 without spheres.
double sphere_origin_distance_ratio(const Scene& scene);

// The algebraic sphere test is wrong on clear rays from 100 radii on and
// clean through 31.6 (tests/accuracy_failure_points_test.cpp); its error
// band grows as ratio^2, so 10 keeps it 10x inside the last clean point,
// near enough that the robust offset still clears the surface a ray leaves.
inline constexpr double kAlgebraicSphereMaxDistanceRatio = 10.0;

// algebraic when the scene has spheres and every ray origin is within the
// ratio above (per_scene); robust otherwise.
SphereMethod choose_sphere_method(const Scene& scene, MethodChoice choice);

// The streams a SceneIntersector runs, one set per kind and the instances'
// top level, all of one unit.
struct SceneStreams {
  ProductStreams kinds;
  BvhStreams<InstanceLeaves> instance_bvh;
};

// The product's streams in unit: the methods above, BVHs of node width
// kProductNodeWidth (tests/support/study_streams.h has every width).
SceneStreams product_scene_streams(KernelUnit unit, SphereMethod sphere);

class SceneIntersector {
 public:
  explicit SceneIntersector(KernelUnit unit, SphereMethod sphere = SphereMethod::robust);
  // streams: unit's streams, with sphere's method for spheres.
  SceneIntersector(KernelUnit unit, SphereMethod sphere, SceneStreams streams);

  KernelUnit unit() const { return unit_; }
  SphereMethod sphere_method() const { return sphere_method_; }
  // How packets walk the BVHs (automatic: together when coherent).
  void set_traversal(BvhTraversal traversal) { traversal_ = traversal; }
  int lanes() const { return lane_width(unit_); }

  // Closest hits in the given layers (hits.t starts as each ray's tmax).
  void closest(const Scene& scene, const RaySoA& rays, HitSoA& hits, Layers layers = Layers::both) const;
  // Any hit in the given layers within (tmin, tmax).
  void occluded(const Scene& scene, const RaySoA& rays, OcclusionSoA& result, Layers layers) const;

 private:
  InstanceLeaves instance_leaves(const Scene& scene, Layers layers) const;

  KernelUnit unit_;
  SphereMethod sphere_method_;
  BvhTraversal traversal_ = BvhTraversal::automatic;
  SceneStreams streams_;
};

}  // namespace quiver
