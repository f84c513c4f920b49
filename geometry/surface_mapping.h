// What a kind's surface mapping reads at a hit and what it gives: texture
// coordinates (u, v), their change per film axis, and, where the kind
// interpolates one, the shading normal and its change. Each kind's
// map_surface (geometry/kinds/<kind>.cpp) fills a SurfaceMapping; shading
// (integrator/surface.h) reaches it through the list of kinds.
#pragma once

#include <cstdint>
#include <numbers>

#include "geometry/affine_transform.h"
#include "geometry/hit.h"
#include "simd/vec3.h"

namespace quiver {

struct MappingQuery {
  const Hit<float>& hit;
  std::uint32_t index;  // the primitive in its store
  bool textured;        // (u, v) wanted
  bool footprint;       // their change wanted (dp is the point's change)
  Vec3<float> position;  // the hit point in the store's coordinates (an instance's own)
  Vec3<float> dp[2];     // its change per film axis (x, y); zero without a footprint
  const AffineTransform* world_to_object;  // an instance's, for its normals; nullptr when not instanced
  const AffineTransform* object_to_world;  // the same instance's inverse; nullptr when not instanced
};

struct SurfaceMapping {
  float u, v;  // texture coordinates; the kernel's u, v where the kind leaves them
  float du[2] = {0.f, 0.f}, dv[2] = {0.f, 0.f};  // their change per film axis
  bool smooth = false;                           // the shading normal is interpolated
  Vec3<float> interpolated{0.f, 0.f, 0.f};       // unit; set where smooth
  // The shading normal's change per film axis (the primitive's orientation):
  // spheres and interpolated normals; 0 on flat surfaces and, as an
  // approximation, on cones.
  Vec3<float> normal_change[2] = {{0.f, 0.f, 0.f}, {0.f, 0.f, 0.f}};
  // Where smooth on a triangle: the step in world space from the hit point
  // up to the curved surface its vertex normals describe, from which shadow
  // rays leave so that a coarse mesh's shadow edge follows the shading
  // (0 where the face is not below that surface).
  Vec3<float> shadow_lift{0.f, 0.f, 0.f};
};

inline constexpr float kInvTwoPi = float(0.5 / std::numbers::pi);
inline constexpr float kInvPi = float(1.0 / std::numbers::pi);

// d(atan2(y, x)) for a change (dx, dy) of (x, y), over 2 pi: the change of a
// longitude u.
inline float longitude_change(float x, float y, float dx, float dy) {
  return (x * dy - y * dx) / (x * x + y * y) * kInvTwoPi;
}

}  // namespace quiver
