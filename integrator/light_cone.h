// A spot light's share of its light in a direction: 1 within its inner
// cone, 0 beyond its outer one, and between them the square of the linear
// ramp in the cosine of the angle off its axis, as KHR_lights_punctual
// (glTF 2.0) defines its falloff:
//   x = clamp((cos - cos_outer) / (cos_inner - cos_outer), 0, 1), share = x^2,
// with cos = -axis . to_light (axis the unit way the light travels,
// to_light unit from the lit point to the light). One formula for every
// width (F a float or a packet of lanes).
#pragma once

#include <algorithm>

#include "scene/scene_desc.h"
#include "simd/vec3.h"

namespace quiver {
inline namespace QUIVER_UNIT_NAMESPACE {

// axis: the light's unit direction (normalize(light.direction), found once per light).
template <class F>
F spot_light_share(const LightDesc& light, const Vec3<float>& axis, const Vec3<F>& to_light) {
  const F cosine = -dot(Vec3<F>(axis), to_light);
  // The cones' cosines at least 2^-20 apart, so the ramp never divides by 0.
  const float span = std::max(light.cone_inner_cos - light.cone_outer_cos, 0x1p-20f);
  const F ramp = min(max((cosine - F(light.cone_outer_cos)) / F(span), F(0.f)), F(1.f));
  return ramp * ramp;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
