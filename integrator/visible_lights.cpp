#include "integrator/visible_lights.h"

#include <cmath>

#include "geometry/kinds/sphere.h"

namespace quiver {

namespace {

// The parallelogram's plane at t = ((p - o).n) / (d.n), n = u x v; the hit
// q - p = a u + b v gives a = ((q - p) x v).n / n.n and b = (u x (q - p)).n / n.n.
std::optional<float> rectangle_distance(const LightDesc& light, const Ray<float>& ray) {
  const Vec3<float> n = cross(light.edge_u, light.edge_v);
  const float facing = dot(ray.direction, n);
  if (facing == 0.f) return std::nullopt;
  const float t = dot(light.position - ray.origin, n) / facing;
  const Vec3<float> w = ray.origin + ray.direction * t - light.position;
  const float nn = dot(n, n);
  const float a = dot(cross(w, light.edge_v), n) / nn, b = dot(cross(light.edge_u, w), n) / nn;
  if (!(a >= 0.f && a <= 1.f && b >= 0.f && b <= 1.f)) return std::nullopt;
  return t;
}

// The robust sphere kernel (geometry/kinds/sphere.h) in one lane: the
// nearer root past tmin, the farther one from inside.
std::optional<float> sphere_distance(const LightDesc& light, const Ray<float>& ray, float t_limit) {
  const SphereLanes<float> sphere{light.position, light.radius * light.radius, 1.f / light.radius};
  Candidate<float> hit;
  if (!SphereRobust::intersect(prepare_sphere_ray(ray), sphere, t_limit, true, hit)) return std::nullopt;
  return hit.t;
}

}  // namespace

std::optional<float> area_light_distance(const LightDesc& light, const Ray<float>& ray, float t_limit) {
  std::optional<float> t;
  if (light.kind == LightDesc::Kind::rectangle) t = rectangle_distance(light, ray);
  if (light.kind == LightDesc::Kind::sphere) t = sphere_distance(light, ray, t_limit);
  if (!t || !(*t > ray.tmin && *t < t_limit)) return std::nullopt;
  return t;
}

bool has_area_lights(const Scene& scene) {
  for (const LightDesc& light : scene.lights) {
    if (light.kind == LightDesc::Kind::rectangle || light.kind == LightDesc::Kind::sphere) return true;
  }
  return false;
}

void see_area_lights(const Scene& scene, const RaySoA& rays, HitSoA& hits, Vec3Columns& seen) {
  for (std::size_t i = 0; i < rays.count; ++i) {
    const Ray<float> ray = rays.get(i);
    for (const LightDesc& light : scene.lights) {
      const std::optional<float> t = area_light_distance(light, ray, hits.t[i]);
      if (!t) continue;
      hits.t[i] = *t;
      hits.id[i] = kNoHit;
      seen.set(i, light.color);
    }
  }
}

}  // namespace quiver
