#include "integrator/visible_lights.h"

#include <cmath>

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

// |o + t d - c|^2 = r^2, the nearer root in front of tmin (the farther one
// from inside); the half-b form, b' = (o - c).d.
std::optional<float> sphere_distance(const LightDesc& light, const Ray<float>& ray) {
  const Vec3<float> oc = ray.origin - light.position;
  const float a = dot(ray.direction, ray.direction), half_b = dot(oc, ray.direction);
  const float c = dot(oc, oc) - light.radius * light.radius;
  const float discriminant = half_b * half_b - a * c;
  if (!(discriminant >= 0.f) || !(a > 0.f)) return std::nullopt;
  const float root = std::sqrt(discriminant);
  const float near = (-half_b - root) / a, far = (-half_b + root) / a;
  return near > ray.tmin ? near : far;
}

}  // namespace

std::optional<float> area_light_distance(const LightDesc& light, const Ray<float>& ray, float t_limit) {
  std::optional<float> t;
  if (light.kind == LightDesc::Kind::rectangle) t = rectangle_distance(light, ray);
  if (light.kind == LightDesc::Kind::sphere) t = sphere_distance(light, ray);
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
