#include "integrator/surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "integrator/texture.h"

namespace quiver {

namespace {

// The rounding error of an instance's hit beyond the world ray's: the ray
// carried in (W o and W d, each a 3-term sum per row, bounded with the same
// ulps as hit_point_error), the hit in the instance's coordinates, both
// taken back by |M|.
Vec3<float> instance_error(const Scene& scene, std::size_t row, const Ray<float>& ray, float t) {
  const AffineTransform& to_object = scene.instances.world_to_object[row];
  const AffineTransform to_object_abs = absolute(to_object);
  const Vec3<float> origin = apply_point(to_object, ray.origin);
  const Vec3<float> direction = apply_vector(to_object, ray.direction);
  const Vec3<float> abs_origin{std::fabs(ray.origin.x), std::fabs(ray.origin.y), std::fabs(ray.origin.z)};
  const Vec3<float> abs_direction{std::fabs(ray.direction.x), std::fabs(ray.direction.y), std::fabs(ray.direction.z)};
  const float e = kOffsetErrorUlps * std::numeric_limits<float>::epsilon();
  const Vec3<float> carried = apply_point(to_object_abs, abs_origin) + apply_vector(to_object_abs, abs_direction) * t;
  const Vec3<float> in_object = hit_point_error(origin, direction, t) + carried * e;
  return apply_vector(absolute(scene.instances.object_to_world[row]), in_object);
}

// The material's colour at the point: times its texture where textured,
// filtered over the footprint when there is one.
Vec3<float> surface_colour(const Scene& scene, const SurfaceDetail& s, const MappingQuery& q,
                           const PointDifferentials* footprint) {
  const Vec3<float>& position = q.position;
  const Vec3<float>* const dp = q.dp;
  const float* const du = s.du;
  const float* const dv = s.dv;
  if (!q.textured) return s.material->color;
  if (footprint == nullptr) {
    return mul(evaluate(scene.textures[*s.material->texture], s.u, s.v, position), s.material->color);
  }
  // The footprint's centre, to first order on the surface (a centred
  // footprint keeps the point's bits, whatever the differentials).
  const float cx = footprint->centre_x, cy = footprint->centre_y;
  const bool shifted = cx != 0.f || cy != 0.f;
  const float u = shifted ? std::fma(cy, du[1], std::fma(cx, du[0], s.u)) : s.u;
  const float v = shifted ? std::fma(cy, dv[1], std::fma(cx, dv[0], s.v)) : s.v;
  const Vec3<float> centre = shifted ? position + dp[0] * cx + dp[1] * cy : position;
  const TextureFootprint f{du[0], dv[0], du[1], dv[1], dp[0], dp[1]};
  return mul(evaluate_filtered(scene.textures[*s.material->texture], u, v, centre, f), s.material->color);
}

}  // namespace

SurfaceDetail surface_detail(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit,
                             const PointDifferentials* footprint) {
  SurfaceDetail s;
  s.ref = scene.locate(hit.id);
  const bool instanced = s.ref.instance >= 0;
  const std::size_t row = instanced ? std::size_t(s.ref.instance) : 0;
  s.material_index = scene.origin(s.ref).material;
  s.material = &scene.materials[s.material_index];
  // Texture coordinates only for textured materials (atan2 and asin are dear).
  const bool textured = s.material->texture.has_value();
  MappingQuery q{hit,
                 s.ref.local,
                 textured,
                 footprint != nullptr,
                 textured || footprint != nullptr ? hit_position(ray, hit.t) : Vec3<float>(0.f, 0.f, 0.f),
                 {footprint != nullptr ? footprint->dx : Vec3<float>(0.f, 0.f, 0.f),
                  footprint != nullptr ? footprint->dy : Vec3<float>(0.f, 0.f, 0.f)},
                 nullptr,
                 nullptr};
  if (instanced) {
    const AffineTransform& to_object = scene.instances.world_to_object[row];
    q.position = apply_point(to_object, q.position);
    for (Vec3<float>& d : q.dp) d = apply_vector(to_object, d);
    q.world_to_object = &to_object;
    q.object_to_world = &scene.instances.object_to_world[row];
    s.instance_error = instance_error(scene, row, ray, hit.t);
  }
  s.u = hit.u;
  s.v = hit.v;
  visit_kind(s.ref.kind, [&]<class K>(K) { map_surface(scene.store_of<K>(s.ref), q, s); });
  s.color = surface_colour(scene, s, q, footprint);
  return s;
}
SurfacePoint surface_at(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit) {
  const SurfaceDetail d = surface_detail(scene, ray, hit);
  SurfaceFrame<float> frame = surface_frame(ray, hit, d.smooth, d.interpolated);
  frame.error = frame.error + d.instance_error;
  return {frame, d};
}

}  // namespace quiver
