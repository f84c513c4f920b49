// The Whitted integrator as a masked iterative loop over wavefronts, no
// recursion and no per-ray virtual calls. For one batch of camera samples:
//   wave 0 = the primary rays; each wave: closest hits of the whole wave
//   (packets of the kernel unit's width) -> shade every hit (ambient now,
//   direct light as shadow rays collected for the whole wave) -> any-hit
//   the shadow wave against the opaque layer, then walk the survivors
//   through the transmissive layer hit by hit (transparent shadows) ->
//   the reflection and refraction rays spawned are appended densely, which
//   compacts them into full packets for the next wave.
// A ray carries the sample it adds to and its weight; contributions are
// added in wave order, so a sample's colour is the same for every width,
// tile and thread count. Shading is scalar code shared by every width.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scene/scene.h"
#include "integrator/scene_intersector.h"
#include "integrator/surface.h"
#include "integrator/trace_stats.h"

namespace quiver {

struct TraceSettings {
  int max_depth = 5;         // bounces after the primary ray; 0 = ray casting
  float min_weight = 1e-3f;  // a secondary ray whose largest weight is below this is not cast; 0 disables
  std::uint64_t seed = 0;    // area-light sampling
};

struct CameraSample {
  Ray<float> ray;
  std::uint64_t key;  // identifies the sample for random numbers (see sample_key)
};

// A key for the camera sample at film point (x, y) (same point, same key).
std::uint64_t sample_key(double x, double y, std::uint64_t seed);
// A uniform number in [0, 1) from a key and two indices.
float hash_uniform(std::uint64_t key, std::uint64_t a, std::uint64_t b);

// First-hit data for AOVs: distance along the unit ray, shading normal
// facing the ray, and the primitive's kind and index in the SceneDesc.
struct FirstHit {
  float depth;
  Vec3<float> normal;
  std::int32_t kind;
  std::int32_t id;
};

class Tracer {
 public:
  Tracer(const Scene& scene, const SceneIntersector& intersector, const TraceSettings& settings);

  // colors[i] = the radiance of samples[i]; adds its rays and lanes to stats.
  void trace(std::span<const CameraSample> samples, std::span<Vec3<float>> colors, TraceStats& stats);

  // The first hit of each ray (unit directions).
  void first_hits(std::span<const Ray<float>> rays, std::span<FirstHit> out);

 private:
  enum class RayKind : std::uint8_t { primary, reflection, refraction };
  struct Path {
    std::uint32_t sample;
    Vec3<float> weight;
    std::uint64_t key;
  };
  struct ShadowPath {
    std::uint32_t sample;
    Vec3<float> contribution;  // added when the light is seen, times transmittance
  };

  void shade(std::size_t i, const Ray<float>& ray, const Hit<float>& hit, std::span<Vec3<float>> colors,
             int depth, TraceStats& stats);
  void add_direct_light(const Path& path, const SurfacePoint& s, const Vec3<float>& color,
                        const Vec3<float>& to_eye);
  void spawn_secondary(const Path& path, const SurfacePoint& s, const Vec3<float>& color,
                       const Vec3<float>& incident, TraceStats& stats);
  void resolve_shadows(std::span<Vec3<float>> colors, TraceStats& stats);
  void count_uncompacted(WaveLanes& lanes);

  const Scene& scene_;
  const SceneIntersector& intersector_;
  TraceSettings settings_;
  std::size_t width_;
  int light_slots_;  // shadow rays per shading point at most (sum of light samples)

  RaySoA rays_, next_rays_, shadow_rays_, transit_rays_;
  HitSoA hits_, transit_hits_;
  OcclusionSoA occlusion_;
  std::vector<Path> paths_, next_paths_;
  std::vector<ShadowPath> shadow_paths_;
  // Per spawned ray: its parent's index and kind / slot, for the uncompacted lane count.
  std::vector<std::uint32_t> child_parent_, shadow_parent_;
  std::vector<std::uint8_t> child_kind_;
  std::vector<std::uint16_t> shadow_slot_;
  std::vector<Vec3<float>> transmittance_;
  std::vector<std::uint32_t> transit_index_;
};

}  // namespace quiver
