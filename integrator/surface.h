// What shading needs at a hit: the point, its error bound, normals, texture
// coordinates and the material. Each kind maps its own surface (texture
// coordinates, shading normal and their change: map_surface in
// geometry/kinds/<kind>.cpp), reached through the list of kinds.
// An instance's triangle is shaded in its mesh's coordinates (the point and
// footprint carried in, so solid textures move with the instance), its
// normals carried out by the inverse transpose.
#pragma once

#include <cstdint>

#include "geometry/hit.h"
#include "geometry/surface_mapping.h"
#include "integrator/surface_frame.h"
#include "scene/scene.h"

namespace quiver {

// What a hit needs beyond its frame (integrator/surface_frame.h), which the
// wave's lanes compute: its kind's surface mapping (texture coordinates,
// the interpolated shading normal where the primitive has one, their change
// over a footprint; geometry/surface_mapping.h), the primitive, its
// material and the colour.
struct SurfaceDetail : SurfaceMapping {
  PrimitiveRef ref;
  std::uint32_t material_index;
  const MaterialDesc* material;
  Vec3<float> color;  // the material's colour at the point (texture times colour)
  // A bound on the hit point's error beyond what the world ray's o + t d
  // carries (SurfaceFrame::error): for an instance, the rounding of
  // carrying the ray into it and of its hit there, mapped back to world
  // space; 0 elsewhere.
  Vec3<float> instance_error{0.f, 0.f, 0.f};
};

// The hit point's change over one sample spacing along film x and y
// (integrator/ray_differentials.h), and where the texture footprint is
// centred, in those spacings from the point (FilmSamples).
struct PointDifferentials {
  Vec3<float> dx, dy;
  float centre_x = 0.f, centre_y = 0.f;
};

// One ray's surface: its frame and its detail.
struct SurfacePoint : SurfaceFrame<float>, SurfaceDetail {};

// The detail of hit (id != kNoHit) of ray (unit or not; t in its units).
// With a footprint the texture is box-filtered over it (texture.h), its
// (u, v) derivatives from the primitive's mapping: exact on planes and
// triangles, differentiated on spheres and cones, by a finite difference
// of the inverse bilinear map on quads.
SurfaceDetail surface_detail(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit,
                             const PointDifferentials* footprint = nullptr);

// The surface at hit (id != kNoHit) of ray (unit or not; t in its units).
SurfacePoint surface_at(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit);

}  // namespace quiver
