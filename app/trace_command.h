// `quiver trace SCENE`: raw closest-hit throughput of the primary rays alone.
// One ray through each pixel centre (the camera of integrator/camera.h, as
// `--aa none`), no shading, no secondary rays. The rays are generated once,
// in 16x16 pixel tiles, before timing; each repeat times only the closest-hit
// queries (SceneIntersector::closest on one RaySoA per tile, tiles spread over
// oneTBB threads). hits counts the rays that hit; t_sum adds their hit
// distances in double, tile by tile in a fixed order, so both are the same
// for every thread count and SIMD width. --occluded times any-hit queries
// instead (hits counts the occluded rays, t_sum is 0); --shuffle traces the
// same rays in a fixed random order, in batches of a tile's size
// (incoherent rays: the other end of the coherence scale). No CLI11 here (app/main.cpp
// parses the flags into TraceOptions).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/soa.h"
#include "integrator/camera.h"
#include "integrator/render.h"
#include "integrator/thread_arena.h"
#include "scene/scene.h"
#include "app/render_options.h"
#include "simd/isa.h"

namespace quiver {

inline constexpr int kDefaultTraceRepeat = 5;
inline constexpr int kMaxTraceRepeat = 10'000;
// The rays are all held at once (32 bytes each): at most 2^24 pixels.
inline constexpr std::int64_t kMaxTracePixels = std::int64_t{1} << 24;
// Tile side in pixels (as the renderer's default).
inline constexpr int kTraceTileSide = 16;

// The flags of `quiver trace`; an absent flag is an empty optional.
struct TraceOptions {
  std::optional<int> width, height;  // absent: as `quiver render` (the camera's, else 512)
  int threads = 0;                   // 0: every core
  int repeat = kDefaultTraceRepeat;
  std::optional<std::string> simd;  // absent: QUIVER_SIMD, else auto
  std::optional<double> crease_angle;  // degrees, every OBJ mesh's (SceneLoadOptions)
  bool strict = false;                 // SceneLoadOptions::strict
  bool allow_outside_paths = false;    // SceneLoadOptions::allow_outside_paths
  CameraFlags camera;
  bool occluded = false;  // any-hit queries instead of closest hits
  bool shuffled = false;  // the rays in kTraceShuffleSeed's permutation
};

// The permutation --shuffle applies: std::shuffle with std::mt19937_64 of this seed.
inline constexpr std::uint64_t kTraceShuffleSeed = 1;

// Checks every flag alone, before the scene is read; throws UsageError.
void check_trace_options(const TraceOptions& options);
// The image size (as image_size() for `quiver render`), checked against
// kMaxTracePixels; throws UsageError.
std::pair<int, int> trace_image_size(const TraceOptions& options, const std::optional<CameraDesc>& camera);

// desc's view for `quiver trace`: the image size (trace_image_size), then
// set_view (app/render_options.h) of that size; returns the size.
std::pair<int, int> set_trace_view(const TraceOptions& options, SceneDesc& desc);

// The pixel-centre rays of one tile into rays (cleared, then padded), in
// groups of 4x2 pixels (row-major inside a group, groups row-major), so each
// 8 consecutive rays of a whole group form one compact 8-wide packet.
void tile_primary_rays(const Camera& camera, const PixelTile& tile, RaySoA& rays);

struct PrimaryTraceResult {
  std::uint64_t rays = 0, hits = 0;
  double t_sum = 0.0;      // hit distances of the last repeat (every repeat finds the same)
  std::vector<double> ms;  // wall time of each repeat, milliseconds
  int threads = 0;         // threads actually used
  Isa isa = Isa::scalar;
};

// What trace_primary asks of the rays: closest hits or occlusion, in tile or shuffled order.
struct TraceQuery {
  bool occluded = false;
  bool shuffled = false;
};

// The primary rays in batches: one per tile (tile_primary_rays), or
// (shuffled) the same rays in kTraceShuffleSeed's permutation, cut into
// batches of a tile's size (256 rays). The tiles are made on arena's threads.
std::vector<RaySoA> primary_batches(const Camera& camera, int width, int height, ThreadArena& arena, bool shuffled);

// Traces the primary rays of a width x height image `repeat` times (>= 1)
// with `threads` threads (0: every core) at the given SIMD width.
PrimaryTraceResult trace_primary(const Scene& scene, int width, int height, Isa isa, int threads, int repeat,
                                 TraceQuery query = {});

// The one-line JSON report: mrays_per_s (median over the repeats of
// rays / repeat time), hits, t_sum, rays, ms_median, threads, simd, lanes,
// build_ms, plus width, height, repeat, primitives and acceleration_bytes
// (the BVH's; 0 when every ray scans every primitive), query and order. No newline.
std::string trace_json_line(const PrimaryTraceResult& result, const Scene& scene, int width, int height,
                            double build_ms, TraceQuery query = {});

double median(std::vector<double> values);

}  // namespace quiver
