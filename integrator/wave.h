// A wave's columns besides its rays and hits, as the tracer
// (integrator/tracer.h) and the lane shading (integrator/wave_shading.h)
// share them: each ray's path (the sample it adds to, its weight, its random
// key), what the scalar pass resolved per hit (material, interpolated
// normal, colour), the materials as columns for gathers, and the shadow
// rays of one light sample slot. Columns are padded like every SoA
// (geometry/soa.h), so any width loads whole packets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/soa.h"
#include "scene/scene_desc.h"

namespace quiver {

struct PathColumns {
  AlignedInts sample;
  AlignedFloats weight_r, weight_g, weight_b;
  std::vector<std::uint64_t> key;
  std::size_t count = 0;

  void clear();
  void push(std::uint32_t sample_index, const Vec3<float>& weight, std::uint64_t path_key);
  void pad();  // after the last push
};

// Per ray of a wave; misses hold material 0, no normal and black.
struct SurfaceColumns {
  AlignedInts material;
  AlignedInts smooth;                  // 1: (nx, ny, nz) is the interpolated shading normal
  AlignedFloats nx, ny, nz;            // unit, the primitive's orientation
  AlignedFloats color_r, color_g, color_b;

  void resize(std::size_t padded);
};

// Every material's parameters, one column each (two_sided as 0 or 1).
struct MaterialTable {
  AlignedFloats ka, kd, ks, shininess, kr, kt, ior, two_sided;

  explicit MaterialTable(const std::vector<MaterialDesc>& materials);
};

// The shadow rays of one light sample slot (light l's sample j), in the
// order of the points that cast them, and the light each carries (added
// where the light is seen, times the transmittance of what it crosses).
struct ShadowSlot {
  RaySoA rays;
  AlignedInts point;  // index of the casting ray in its wave
  AlignedFloats light_r, light_g, light_b;

  void clear();
};

// Shadow rays per side of a light's sample grid: n x n for area lights, one ray otherwise.
int samples_per_side(const LightDesc& light);

}  // namespace quiver
