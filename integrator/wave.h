// A wave's columns besides its rays and hits, as the tracer
// (integrator/tracer.h) and the lane shading (integrator/wave_shading.h)
// share them: each ray's path (the sample it adds to, its weight, its random
// key), what the scalar pass resolved per hit (material, interpolated
// normal, colour), the materials as columns for gathers, and the shadow
// rays of one light sample slot. Columns are padded like every SoA
// (geometry/soa.h), so any width loads whole packets.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/soa.h"
#include "scene/scene_desc.h"

namespace quiver {

// Three float columns: one vector per ray.
struct Vec3Columns {
  AlignedFloats x, y, z;

  void clear();
  void push(const Vec3<float>& v);
  void pad(std::size_t count);
  void assign(std::size_t padded);  // zeros
  void set(std::size_t i, const Vec3<float>& v);
  Vec3<float> get(std::size_t i) const { return {x[i], y[i], z[i]}; }
  // Lanes [first, first + lanes of F) (aligned: first a multiple of them).
  template <class F>
  Vec3<F> load(std::size_t first) const {
    return load_vec3<F>(x, y, z, first);
  }
  template <class F>
  void store(std::size_t first, const Vec3<F>& v) {
    store_lanes(v.x, x.data() + first);
    store_lanes(v.y, y.data() + first);
    store_lanes(v.z, z.data() + first);
  }
  std::array<AlignedFloats*, 3> columns() { return {&x, &y, &z}; }
};

// Per ray, its differentials (integrator/ray_differentials.h): the change
// of origin and unit direction over one sample spacing along film x and y,
// and its camera sample's footprint centre (FilmSamples).
struct DifferentialColumns {
  Vec3Columns origin_dx, origin_dy, direction_dx, direction_dy;
  AlignedFloats centre_x, centre_y;

  void clear();
  void pad(std::size_t count);
  void resize(std::size_t size);  // unpadded
  std::array<Vec3Columns*, 4> vectors() { return {&origin_dx, &origin_dy, &direction_dx, &direction_dy}; }
  std::array<AlignedFloats*, 2> centres() { return {&centre_x, &centre_y}; }
};

struct PathColumns {
  AlignedInts sample;
  AlignedFloats weight_r, weight_g, weight_b;
  std::vector<std::uint64_t> key;
  std::size_t count = 0;

  void clear();
  void push(std::uint32_t sample_index, const Vec3<float>& weight, std::uint64_t path_key);
  // n camera paths: path i of sample i, weight 1, keys to be written.
  void start_at_camera(std::size_t n);
  void pad();  // after the last push or key
  std::array<AlignedFloats*, 3> weights() { return {&weight_r, &weight_g, &weight_b}; }
};

// Per ray of a wave; misses hold material 0, no normal and black.
struct SurfaceColumns {
  AlignedInts material;
  AlignedInts smooth;                  // 1: (nx, ny, nz) is the interpolated shading normal
  AlignedFloats nx, ny, nz;            // unit, the primitive's orientation
  AlignedFloats color_r, color_g, color_b;
  Vec3Columns error;                   // SurfaceDetail::instance_error (0 off instances)
  Vec3Columns shadow_lift;             // SurfaceMapping::shadow_lift (0 where not smooth)
  // What a ray that misses every surface sees (the background, or an area
  // light: integrator/visible_lights.h); empty when the scene has no area light.
  Vec3Columns seen;
  // With ray differentials only: the point's change and the shading
  // normal's (in the primitive's orientation) over one sample spacing.
  Vec3Columns point_dx, point_dy, normal_dx, normal_dy;

  void resize(std::size_t padded, bool differentials);
};

// Every material's parameters, one column each (two_sided and fresnel as 0 or 1).
struct MaterialTable {
  AlignedFloats ka, kd, ks, shininess, kr, kt, ior, two_sided, fresnel;

  explicit MaterialTable(const std::vector<MaterialDesc>& materials);
};

// The shadow rays of one light sample slot (light l's sample j), in the
// order of the points that cast them, and the light each carries (added
// where the light is seen, times the transmittance of what it crosses).
struct ShadowSlot {
  RaySoA rays;
  AlignedInts point;  // index of the casting ray in its wave
  AlignedFloats light_r, light_g, light_b;

  // Empties the slot for a wave of at most `capacity` shadow rays (one per
  // ray of the wave at most): its columns sized once, rays.count 0.
  void open(std::size_t capacity);
  // n more rays, unset; returns the first one's index.
  std::size_t grow(std::size_t n) {
    const std::size_t first = rays.count;
    rays.count += n;
    return first;
  }
};

// The spawned rays' columns (and their differentials, when given) grown by
// n unset entries; returns the first new index. Growth lives in the host
// unit, not in the lane code: vector growth instantiated in every kernel
// unit would be one function defined in several (the units' symbol test).
std::size_t grow_spawned(std::size_t n, RaySoA& rays, PathColumns& paths, DifferentialColumns* differentials);

// Shadow rays per side of a light's sample grid: n x n for area lights, one ray otherwise.
int samples_per_side(const LightDesc& light);

}  // namespace quiver
