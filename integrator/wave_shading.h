// Shading a wave in packets: for every hit, the surface in lanes (point,
// error bound, geometric and shading normals, side), the materials gathered
// from their columns, the ambient term (for misses, the background or the
// area light the ray sees), every light sample (point, directional,
// stratified rectangle and sphere samples) with its Phong diffuse and
// specular terms and its shadow ray (from the lifted point near a smooth
// triangle's terminator), and the reflection and refraction rays (Snell,
// total internal reflection, Fresnel where the material asks), weights and
// the min-weight cut-off. Written once as templates
// over the lane type; integrator/wave_shading.cpp is compiled per kernel
// unit, the scalar unit being the reference, so every width gives the same
// bits. Masks: padding lanes and misses cast nothing; a packet with no
// lit lane skips the lights, one with no lane to append skips the append.
// What lanes cannot do alone is done per lane by the same scalar code at
// every width: the random numbers (64-bit hashes) and a sphere light's
// cos/sin. Appends keep lane order, so the rays a wave spawns and the
// order their light is added in do not depend on the width.
#pragma once

#include <cstdint>
#include <vector>

#include "integrator/wave.h"
#include "scene/scene.h"

namespace quiver {

struct WaveShadingInput {
  const Scene* scene;
  const MaterialTable* materials;
  const RaySoA* rays;
  const HitSoA* hits;
  const PathColumns* paths;
  const SurfaceColumns* surfaces;  // from surface_detail, per ray
  const DifferentialColumns* differentials;  // per ray; null when rays carry none
  bool spawn;                      // below the maximum depth
  float min_weight;
  std::uint64_t seed;
  bool spawn_every_ray;  // TraceSettings::spawn_every_ray
};

// What shading a wave counted, for TraceStats.
struct WaveShadingCounts {
  std::uint64_t hits = 0, reflection = 0, refraction = 0;
  // Lanes a per-packet masked recursion would issue (trace_stats.h).
  std::uint64_t shadow_uncompacted = 0, next_uncompacted = 0;
  // Lanes issued by the light sample iterations of packets with a lit lane
  // (active: the lanes that cast a shadow ray).
  std::uint64_t light_active = 0, light_issued = 0;
};

// Where a wave's shading appends: the tracer's buffers, borrowed.
struct WaveAppendTargets {
  std::vector<ShadowSlot>* slots;           // one per light sample slot
  RaySoA* next_rays;                        // the spawned rays, appended densely
  PathColumns* next_paths;
  DifferentialColumns* next_differentials;  // appended to with next_rays; null when rays carry none
};

// What a wave's shading owns and writes: per ray, the light it adds at once
// (the ambient term, or the background on a miss), sized by the call; and
// what it counted, added to.
struct WaveShadingOutput {
  AlignedFloats emitted_r, emitted_g, emitted_b;
  WaveShadingCounts counts;
};

// Shades the wave of in: out's emitted light and counts, the shadow rays
// and spawned rays appended to `to`.
template <KernelUnit U>
void shade_wave(const WaveShadingInput& in, const WaveAppendTargets& to, WaveShadingOutput& out);

using ShadeWaveFunction = void (*)(const WaveShadingInput&, const WaveAppendTargets&, WaveShadingOutput&);

}  // namespace quiver
