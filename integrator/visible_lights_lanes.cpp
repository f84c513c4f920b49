// Area lights seen by a wave's rays, in packets (the contract:
// visible_lights.h). Compiled once per kernel unit; F is the unit's lane
// type. Each packet's lanes take the lights in scene order, each light's
// test limited by the nearest hit so far, as one ray at a time would.
#include <utility>
#include <vector>

#include "integrator/visible_lights.h"

namespace quiver {

template <KernelUnit U>
void see_area_lights(const Scene& scene, const RaySoA& rays, HitSoA& hits, Vec3Columns& seen) {
  using F = UnitLanes<U>;
  std::vector<std::pair<const LightDesc*, RectangleFrame>> area_lights;
  for (const LightDesc& light : scene.lights) {
    if (light.is_area()) area_lights.emplace_back(&light, rectangle_frame(light));
  }
  for (std::size_t first = 0; first < rays.count; first += std::size_t(lane_count<F>)) {
    const Mask<F> active = first_lanes<F>(rays.count - first);
    const Ray<F> ray = rays.load<F>(first);
    F t = load_lanes<F>(hits.t.data() + first);
    IntLanes<F> id = load_int_lanes<F>(hits.id.data() + first);
    Vec3<F> color = seen.load<F>(first);
    Mask<F> cleared(false);
    for (const auto& [light, frame] : area_lights) {
      F light_t;
      const Mask<F> met = meets_area_light(*light, frame, ray, t, active, light_t);
      t = select(met, light_t, t);
      color = select(met, Vec3<F>(light->color), color);
      cleared = cleared | met;
    }
    if (none(cleared)) continue;
    store_lanes(t, hits.t.data() + first);
    store_int_lanes<F>(select(cleared, IntLanes<F>(kNoHit), id), hits.id.data() + first);
    seen.store(first, color);
  }
}

template void see_area_lights<kThisUnit>(const Scene&, const RaySoA&, HitSoA&, Vec3Columns&);

}  // namespace quiver
