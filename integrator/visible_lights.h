// Area lights seen by camera, reflection and refraction rays. A rectangle
// light (corner + a edge_u + b edge_v, a and b in [0, 1], seen from both
// sides, as it lights both) and a sphere light are met where a ray crosses
// them in (tmin, t), t the ray's closest hit so far (its tmax on a miss):
// the ray ends there, showing the light's colour unshaded. Shadow rays do
// not see them (a light does not hide itself). One formula for every width
// (meets_area_light over lanes of F; the scalar one is the reference), so
// the widths agree bit for bit: a rectangle by its plane and edges, a
// sphere light by the robust sphere kernel (geometry/kinds/sphere.h).
#pragma once

#include <cstddef>
#include <optional>

#include "geometry/kinds/sphere.h"
#include "geometry/soa.h"
#include "integrator/wave.h"
#include "scene/scene.h"

namespace quiver {

// A rectangle light's plane normal n = u x v and n.n, found once per light
// rather than once per ray.
struct RectangleFrame {
  Vec3<float> n;
  float nn;
};

inline RectangleFrame rectangle_frame(const LightDesc& light) {
  const Vec3<float> n = cross(light.edge_u, light.edge_v);
  return {n, dot(n, n)};
}

inline namespace QUIVER_UNIT_NAMESPACE {

// The active lanes whose ray meets the area light (frame: its
// rectangle_frame) within (tmin, t_limit), t set to that distance in the
// ray's direction units (other lanes' t undefined). A rectangle: its plane
// at t = ((p - o).n) / (d.n) (a ray parallel to it never meets it), the hit
// q - p = a u + b v with a = ((q - p) x v).n / n.n and b = (u x (q - p)).n
// / n.n in [0, 1]. A sphere: the robust kernel's nearer root past tmin, the
// farther one from inside.
template <class F>
Mask<F> meets_area_light(const LightDesc& light, const RectangleFrame& frame, const Ray<F>& ray, const F& t_limit,
                         const Mask<F>& active, F& t) {
  if (light.kind == LightDesc::Kind::sphere) {
    const SphereLanes<F> sphere{Vec3<F>(light.position), F(light.radius * light.radius), F(1.f / light.radius)};
    Candidate<F> hit;
    const Mask<F> met = SphereRobust::intersect(prepare_sphere_ray(ray), sphere, t_limit, active, hit);
    t = hit.t;
    return met;
  }
  if (light.kind != LightDesc::Kind::rectangle) return Mask<F>(false);
  const Vec3<F> n(frame.n);
  const F facing = dot(ray.direction, n);
  t = dot(Vec3<F>(light.position) - ray.origin, n) / facing;
  const Mask<F> in_range = active & (facing != F(0.f)) & (t > ray.tmin) & (t < t_limit);
  if (none(in_range)) return in_range;
  const Vec3<F> w = ray.origin + ray.direction * t - Vec3<F>(light.position);
  const F a = dot(cross(w, Vec3<F>(light.edge_v)), n) / F(frame.nn);
  const F b = dot(cross(Vec3<F>(light.edge_u), w), n) / F(frame.nn);
  return in_range & (a >= F(0.f)) & (a <= F(1.f)) & (b >= F(0.f)) & (b <= F(1.f));
}

}  // namespace QUIVER_UNIT_NAMESPACE

// The distance along ray (in its direction's units) at which it meets the
// area light within (ray.tmin, t_limit); nothing for point and directional
// lights and for rays that pass it (meets_area_light in one lane).
std::optional<float> area_light_distance(const LightDesc& light, const Ray<float>& ray, float t_limit);

bool has_area_lights(const Scene& scene);

// For each of the first rays.count rays that meets an area light before
// its hit: the hit cleared (id kNoHit, t the light's distance) and entry i
// of seen set to the nearest such light's colour; the other entries keep
// their values. Every column padded to whole packets of the unit's lanes.
// Compiled per kernel unit (integrator/visible_lights_lanes.cpp).
template <KernelUnit U>
void see_area_lights(const Scene& scene, const RaySoA& rays, HitSoA& hits, Vec3Columns& seen);

using SeeAreaLightsFunction = void (*)(const Scene&, const RaySoA&, HitSoA&, Vec3Columns&);

}  // namespace quiver
