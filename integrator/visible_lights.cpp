#include "integrator/visible_lights.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "geometry/kinds/sphere.h"

namespace quiver {

namespace {

// A rectangle light's plane normal n = u x v and n.n, found once per light
// rather than once per ray.
struct RectangleFrame {
  Vec3<float> n;
  float nn;
};

RectangleFrame rectangle_frame(const LightDesc& light) {
  const Vec3<float> n = cross(light.edge_u, light.edge_v);
  return {n, dot(n, n)};
}

// The parallelogram's plane at t = ((p - o).n) / (d.n); a t outside
// (tmin, t_limit) ends the test before the hit q - p = a u + b v is solved:
// a = ((q - p) x v).n / n.n and b = (u x (q - p)).n / n.n.
std::optional<float> rectangle_distance(const LightDesc& light, const RectangleFrame& frame, const Ray<float>& ray,
                                        float t_limit) {
  const float facing = dot(ray.direction, frame.n);
  if (facing == 0.f) return std::nullopt;
  const float t = dot(light.position - ray.origin, frame.n) / facing;
  if (!(t > ray.tmin && t < t_limit)) return std::nullopt;
  const Vec3<float> w = ray.origin + ray.direction * t - light.position;
  const float a = dot(cross(w, light.edge_v), frame.n) / frame.nn, b = dot(cross(light.edge_u, w), frame.n) / frame.nn;
  if (!(a >= 0.f && a <= 1.f && b >= 0.f && b <= 1.f)) return std::nullopt;
  return t;
}

// The robust sphere kernel (geometry/kinds/sphere.h) in one lane: the
// nearer root past tmin, the farther one from inside, within (tmin, t_limit).
std::optional<float> sphere_distance(const LightDesc& light, const Ray<float>& ray, float t_limit) {
  const SphereLanes<float> sphere{light.position, light.radius * light.radius, 1.f / light.radius};
  Candidate<float> hit;
  if (!SphereRobust::intersect(prepare_sphere_ray(ray), sphere, t_limit, true, hit)) return std::nullopt;
  return hit.t;
}

// The light's distance along ray in (tmin, t_limit), its rectangle frame
// found beforehand: each test keeps that range itself.
std::optional<float> light_distance(const LightDesc& light, const RectangleFrame& frame, const Ray<float>& ray,
                                    float t_limit) {
  if (light.kind == LightDesc::Kind::rectangle) return rectangle_distance(light, frame, ray, t_limit);
  if (light.kind == LightDesc::Kind::sphere) return sphere_distance(light, ray, t_limit);
  return std::nullopt;
}

bool is_area_light(const LightDesc& light) {
  return light.kind == LightDesc::Kind::rectangle || light.kind == LightDesc::Kind::sphere;
}

}  // namespace

std::optional<float> area_light_distance(const LightDesc& light, const Ray<float>& ray, float t_limit) {
  return light_distance(light, rectangle_frame(light), ray, t_limit);
}

bool has_area_lights(const Scene& scene) {
  return std::any_of(scene.lights.begin(), scene.lights.end(), is_area_light);
}

void see_area_lights(const Scene& scene, const RaySoA& rays, HitSoA& hits, Vec3Columns& seen) {
  std::vector<std::pair<const LightDesc*, RectangleFrame>> area_lights;
  for (const LightDesc& light : scene.lights) {
    if (is_area_light(light)) area_lights.emplace_back(&light, rectangle_frame(light));
  }
  for (std::size_t i = 0; i < rays.count; ++i) {
    const Ray<float> ray = rays.get(i);
    for (const auto& [light, frame] : area_lights) {
      const std::optional<float> t = light_distance(*light, frame, ray, hits.t[i]);
      if (!t) continue;
      hits.t[i] = *t;
      hits.id[i] = kNoHit;
      seen.set(i, light->color);
    }
  }
}

}  // namespace quiver
