#include "integrator/visible_lights.h"

#include <algorithm>

namespace quiver {

std::optional<float> area_light_distance(const LightDesc& light, const Ray<float>& ray, float t_limit) {
  float t = 0.f;
  if (!meets_area_light(light, rectangle_frame(light), ray, t_limit, true, t)) return std::nullopt;
  return t;
}

bool has_area_lights(const Scene& scene) {
  return std::any_of(scene.lights.begin(), scene.lights.end(), [](const LightDesc& l) { return l.is_area(); });
}

}  // namespace quiver
