#include "integrator/trace_stats.h"

namespace quiver {

namespace {
void add_lanes(WaveLanes& a, const WaveLanes& b) {
  a.active += b.active;
  a.issued_compacted += b.issued_compacted;
  a.issued_uncompacted += b.issued_uncompacted;
}
}  // namespace

WaveLanes& TraceStats::wave(std::size_t depth) {
  if (waves.size() <= depth) waves.resize(depth + 1);
  return waves[depth];
}

void TraceStats::add(const TraceStats& o) {
  rays.primary += o.rays.primary;
  rays.primary_hits += o.rays.primary_hits;
  rays.shadow += o.rays.shadow;
  rays.reflection += o.rays.reflection;
  rays.refraction += o.rays.refraction;
  for (std::size_t d = 0; d < o.waves.size(); ++d) add_lanes(wave(d), o.waves[d]);
  add_lanes(shadow, o.shadow);
  shading_active += o.shading_active;
  light_sample_active += o.light_sample_active;
  light_sample_issued += o.light_sample_issued;
  phases.camera_and_film += o.phases.camera_and_film;
  phases.intersection += o.phases.intersection;
  phases.shading += o.phases.shading;
  phases.shadows += o.phases.shadows;
  phases.shadow_walks += o.phases.shadow_walks;
}

}  // namespace quiver
