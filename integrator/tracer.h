// The Whitted integrator as a masked iterative loop over wavefronts, no
// recursion and no per-ray virtual calls. For one batch of camera samples:
//   wave 0 = the primary rays (made in lanes: camera_rays.h); each wave:
//   closest hits of the whole wave (packets of the kernel unit's width) ->
//   the scalar pass resolves each hit's primitive, material, interpolated
//   normal and texture colour -> the lanes shade the wave (integrator/wave_shading.h): ambient terms,
//   one shadow ray per light sample into that sample slot's stream, and the
//   reflection and refraction rays appended densely, which compacts them
//   into full packets for the next wave -> each slot's shadow stream (rays
//   toward one light sample: coherent packets) is any-hit against the
//   opaque layer, and its survivors walk the transmissive layer hit by hit
//   (transparent shadows).
// A ray carries the sample it adds to and its weight; contributions are
// added in wave order (ambient terms in ray order, then the light seen, by
// ray and slot), so a sample's colour is the same for every width, tile and
// thread count.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "scene/scene.h"
#include "integrator/camera.h"
#include "integrator/camera_rays.h"
#include "integrator/hit_footprints.h"
#include "integrator/sample_hash.h"
#include "integrator/scene_intersector.h"
#include "integrator/surface.h"
#include "integrator/trace_stats.h"
#include "integrator/visible_lights.h"
#include "integrator/wave.h"
#include "integrator/wave_shading.h"

namespace quiver {

struct TraceSettings {
  int max_depth = kDefaultMaxDepth;        // bounces after the primary ray; 0 = ray casting
  float min_weight = kDefaultMinWeight;    // a secondary ray whose largest weight is below this is not cast; 0 disables
  std::uint64_t seed = 0;    // area-light sampling
  // The SPD procedure's ray tree (--preset spd): every hit on a reflective
  // (Ks > 0) or transmissive surface spawns a reflection ray, every hit on a
  // transmissive one a refraction ray unless totally internally reflected,
  // and every lit hit a shadow ray toward each light it faces, whatever the
  // weights (zero-weight rays are traced and add nothing to the image).
  bool spawn_every_ray = false;
  // Box-filter checker textures over each hit's footprint, from ray
  // differentials carried through reflection and refraction
  // (integrator/ray_differentials.h); only in scenes with textures. Off:
  // textures are point-sampled.
  bool filter_textures = true;
  // Time each phase of a frame into TraceStats::phases (clock reads in
  // every wave and walk: only when the times are reported). Off, the
  // phases stay 0.
  bool time_phases = false;
};

// Rays carry differentials (and textures are filtered) when the settings
// ask for filtering and the scene has a texture to filter.
bool rays_carry_differentials(const Scene& scene, const TraceSettings& settings);

// What a camera ray met first, for the AOVs and refine's edge test: nothing
// (the defaults), or the distance along the ray (in units of its
// direction's length times that length: the distance for any direction) and
// the material; for the AOVs also the primitive's kind and index in the
// SceneDesc and the shading normal facing the ray.
struct FirstSurface {
  float depth = std::numeric_limits<float>::infinity();
  Vec3<float> normal{0.f, 0.f, 0.f};
  std::int32_t kind = kNoKind;
  std::int32_t id = -1;
  std::int32_t material = -1;
};

// The first surface of ray at distance t, of that material: what refine's
// edge test reads. The AOVs add the primitive's kind and index and the
// normal, which they alone ask for.
FirstSurface first_surface(const Ray<float>& ray, float t, std::uint32_t material);

class Tracer {
 public:
  Tracer(const Scene& scene, const SceneIntersector& intersector, const TraceSettings& settings);

  // colors[i] = the radiance of the camera's sample at film point i; adds
  // its rays and lanes to stats. A sample's random numbers come from its key
  // (sample_key of its film point); with differentials, its rays' change over
  // its cell's side, its texture footprints centred on the cell (zero and
  // on the point when the batch keeps no cells). With `surfaces` (as long as
  // the batch), also what each sample met first.
  void trace(const Camera& camera, const FilmSamples& film, std::span<Vec3<float>> colors, TraceStats& stats,
             std::span<FirstSurface> surfaces = {});

  // The first hit of each ray (unit directions).
  void first_hits(std::span<const Ray<float>> rays, std::span<FirstSurface> out);

 private:
  // Wave 0: the film's camera rays, their paths and differentials.
  void start_at_camera(const Camera& camera, const FilmSamples& film, TraceStats& stats);
  // Each camera ray's first surface, by its sample.
  void record_first_surfaces(std::span<FirstSurface> surfaces) const;
  // Shades the wave into shaded_ (the emitted light, shadow streams and the
  // next wave's rays); depth: the wave's.
  void shade(int depth);
  void count_shading(int depth, TraceStats& stats) const;
  // The spawned rays become the wave (padded for the lanes), counted.
  void next_wave(int depth, TraceStats& stats);
  // surface_detail of every hit of the wave into surfaces_, one hit at a
  // time, after the packets' passes: the area lights the rays see and, when
  // differentials are carried, the hits' footprints (hit_footprints.h).
  void resolve_surfaces();
  void resolve_surface_with_footprint(std::size_t i);
  void store_surface(std::size_t i, const SurfaceDetail& detail);
  // Traces every slot's shadow stream and adds the light seen to colors
  // (one_ray_per_sample: no sample has two rays in the wave).
  void resolve_shadows(std::span<Vec3<float>> colors, std::uint64_t uncompacted, bool one_ray_per_sample,
                       TraceStats& stats);
  // Transparent shadows: scales the slot's transmittance by each
  // transmissive surface its unoccluded rays cross; adds the walks' time to walk_time.
  void transmit(std::size_t slot, std::uint64_t& walk_time);

  const Scene& scene_;
  const SceneIntersector& intersector_;
  TraceSettings settings_;
  std::size_t width_;
  bool differentials_;  // rays carry differentials: filter_textures in a scene with textures
  bool area_lights_;    // some light is a rectangle or a sphere, which rays see (visible_lights.h)
  MaterialTable materials_;
  ShadeWaveFunction shade_wave_;
  CameraRaysFunction camera_rays_;
  CameraDirectionChangesFunction camera_direction_changes_;
  SeeAreaLightsFunction see_area_lights_;
  HitFootprintsFunction hit_footprints_;

  RaySoA rays_, next_rays_, transit_rays_;
  HitSoA hits_, transit_hits_;
  PathColumns paths_, next_paths_;
  DifferentialColumns differentials_of_rays_, next_differentials_;
  SurfaceColumns surfaces_;
  WaveShadingOutput shaded_;
  // Per light sample slot (sum of the lights' sample counts).
  std::vector<ShadowSlot> slots_;
  std::vector<OcclusionSoA> occlusion_;
  std::vector<std::vector<Vec3<float>>> transmittance_;
  std::vector<std::size_t> cursor_;
  // A slot's columns that resolve_shadows adds up, as plain pointers: the
  // colours written in between cannot change them, so they need not be
  // read again per ray.
  struct SlotLight {
    const std::int32_t* occluded;
    const std::int32_t* point;
    const float *r, *g, *b;
    const Vec3<float>* transmittance;
    std::size_t count;
  };
  std::vector<SlotLight> slot_lights_;
  std::vector<std::uint32_t> transit_index_;
  std::vector<float> transit_tmin_;
};

}  // namespace quiver
