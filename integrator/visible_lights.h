// Area lights seen by camera, reflection and refraction rays. A rectangle
// light (corner + a edge_u + b edge_v, a and b in [0, 1], seen from both
// sides, as it lights both) and a sphere light are met where a ray crosses
// them in (tmin, t), t the ray's closest hit so far (its tmax on a miss):
// the ray ends there, showing the light's colour unshaded. Shadow rays do
// not see them (a light does not hide itself). One scalar test serves every
// kernel unit, so the widths agree bit for bit: a sphere light by the
// robust sphere kernel (geometry/kinds/sphere.h) in one lane.
#pragma once

#include <cstddef>
#include <optional>

#include "geometry/soa.h"
#include "integrator/wave.h"
#include "scene/scene.h"

namespace quiver {

// The distance along ray (in its direction's units) at which it meets the
// area light within (ray.tmin, t_limit); nothing for point and directional
// lights and for rays that pass it.
std::optional<float> area_light_distance(const LightDesc& light, const Ray<float>& ray, float t_limit);

bool has_area_lights(const Scene& scene);

// For each of the first rays.count rays that meets an area light before
// its hit: the hit cleared (id kNoHit, t the light's distance) and entry i
// of seen set to the nearest such light's colour; the other entries keep
// their values.
void see_area_lights(const Scene& scene, const RaySoA& rays, HitSoA& hits, Vec3Columns& seen);

}  // namespace quiver
