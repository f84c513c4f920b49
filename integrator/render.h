// A whole image: the film cut into tiles, each tile's camera samples traced
// as one wavefront batch (integrator/tracer.h), tiles spread over the cores
// with oneTBB. Each tile writes only its own pixels and every random number
// comes from the sample's film position, so the image is the same for any
// thread count, tile order and SIMD width, and for any split of the tiles
// between renderers (FrameRenderer: render() is one renderer given every
// tile; app/mpi_render.h gives each process some).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "scene/anti_aliasing.h"
#include "integrator/framebuffer.h"
#include "scene/scene.h"
#include "integrator/trace_stats.h"
#include "integrator/tracer.h"
#include "simd/isa.h"

namespace quiver {

struct RenderSettings {
  int width = 512, height = 512;
  AntiAliasing aa;
  TraceSettings trace;
  int threads = 0;  // 0: every core
  Isa isa = Isa::scalar;
  bool aov_depth = false, aov_normal = false, aov_id = false;  // id also writes the kind
  int tile_size = 16;
  MethodChoice methods = MethodChoice::per_scene;  // most_robust: robust sphere test in every scene
};

struct RenderResult {
  Framebuffer image;
  TraceStats stats;
  double render_ms = 0.0;
  int threads = 0;  // threads actually used
  SphereMethod sphere_method = SphereMethod::robust;  // the one the render used
  std::size_t tiles_done = 0, tiles_total = 0;
  // The stop flag was seen: tiles not yet started were skipped, the image is incomplete.
  bool stopped() const { return tiles_done < tiles_total; }
};

// A rectangle of pixels: the renderer's unit of work.
struct PixelTile {
  int x0, y0, width, height;
};

// The pixels of [x0, x1) x [y0, y1) in groups of 4 x 4, the groups row by
// row, partial groups at the right and bottom edges. Traced in this order,
// 16 consecutive samples (one 16-wide packet) cover a 4 x 4 footprint and
// eight (one 8-wide packet) a 4 x 2 footprint, not a row, and stay closer
// together through the BVH.
inline constexpr int kPixelGroupWidth = 4, kPixelGroupHeight = 4;
template <class Visit>
void for_each_pixel_in_groups(int x0, int y0, int x1, int y1, Visit&& visit) {
  for (int gy = y0; gy < y1; gy += kPixelGroupHeight) {
    for (int gx = x0; gx < x1; gx += kPixelGroupWidth) {
      for (int y = gy; y < std::min(gy + kPixelGroupHeight, y1); ++y) {
        for (int x = gx; x < std::min(gx + kPixelGroupWidth, x1); ++x) visit(x, y);
      }
    }
  }
}

// Tiles of at most side x side pixels covering width x height, row by row.
// Throws std::invalid_argument for side < 1.
std::vector<PixelTile> pixel_tiles(int width, int height, int side);

// A render's progress: tiles done of total, and the share of the frame's
// work done (WorkDone over FrameRenderer::estimate_costs), so a time-left
// estimate holds when tiles cost unevenly.
struct RenderProgressState {
  std::size_t tiles_done = 0, tiles_total = 0;
  double work_done = 0.0;  // 0 to 1
  double tile_seconds = 0.0;  // since the first tile started: the time the work done took
};

// One ray per this many pixels on a side estimates a tile's cost
// (FrameRenderer::estimate_costs: for quiver-mpi's schedule and progress).
inline constexpr int kTileCostStride = 8;

// The share of a frame's work done, tiles weighted by their estimated cost
// in microseconds, plus a hundredth so that no tile weighs nothing (a larger
// floor would make the many cheap tiles of a frame's empty parts weigh more
// than their share).
class WorkDone {
 public:
  static double weight(double estimated_cost) { return std::max(estimated_cost, 0.0) + 0.01; }
  void add_to_total(double weight) { total_ += weight; }
  void add_done(double weight) { done_ += weight; }
  // 0 to 1; 1 for a frame of no work.
  double share() const { return total_ > 0.0 ? std::min(done_ / total_, 1.0) : 1.0; }

 private:
  double total_ = 0.0, done_ = 0.0;
};

// Called after each tile, from worker threads one at a time.
using RenderProgress = std::function<void(const RenderProgressState&)>;

// stop, when given, is read before each tile: once it is true no further
// tile starts and the result says stopped (a signal handler may set it).
// With a progress callback, the tiles' costs are estimated first (pixels
// at a stride of kTileCostStride, not counted in the result's stats; the
// image is the same).
RenderResult render(const Scene& scene, const RenderSettings& settings, const RenderProgress& progress = {},
                    const std::atomic<bool>* stop = nullptr);

// What tiles write: the image with its AOVs and, in corners mode, the
// (W + 1) x (H + 1) corner colours that FrameRenderer::finish averages into
// the pixels once every tile is in.
struct Film {
  Framebuffer image;
  std::vector<Vec3<float>> corners;
};

// The next tile to render (an index into FrameRenderer::tiles()), or none
// when there is no more. Called from the worker threads, concurrently; it
// may block until a tile is there.
using TileSource = std::function<std::optional<std::size_t>()>;
// Called from the worker thread that rendered the tile, once the film holds
// it, with its time in milliseconds; concurrently.
using TileDone = std::function<void(std::size_t tile, double ms)>;

// One frame's tiles (pixel_tiles of the settings' size and tile side), a
// worker per thread (kept from call to call) and the film's layout. A tile
// writes only its own part of a film (its pixels and AOVs; in corners mode
// its corners, not its pixels), the same bits whichever renderer, thread or
// film renders it, so tiles rendered into several films, packed and
// unpacked into one, then finished, give render()'s image bit for bit.
class FrameRenderer {
 public:
  // Throws std::invalid_argument for a tile size below 1.
  FrameRenderer(const Scene& scene, const RenderSettings& settings);
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  const std::vector<PixelTile>& tiles() const;
  // A film of the settings' size, with the AOVs asked for and the corner
  // buffer in corners mode.
  Film make_film() const;

  // Renders the tiles next() gives into film until it gives none or *stop
  // (read before each tile) is true; at most tiles().size() tiles per call.
  // Returns how many tiles it rendered.
  std::size_t render_tiles(Film& film, const TileSource& next, const TileDone& done = {},
                           const std::atomic<bool>* stop = nullptr);

  // A cheap estimate of each tile's cost, for scheduling the costliest
  // first and for the time left: the microseconds taken to trace (every ray
  // kind) from one ray per stride x stride pixels through their centres,
  // without anti-aliasing; time, not a count of rays, as a ray's cost
  // differs from one part of a frame to another. Leaves stats() as it was.
  std::vector<double> estimate_costs(std::span<const std::size_t> tiles, int stride) const;

  // A tile's part of a film as bytes: its colours (corners mode: the corners
  // it owns), then each AOV asked for, row by row; tile_bytes of them.
  std::size_t tile_bytes(std::size_t tile) const;
  void pack_tile(const Film& film, std::size_t tile, std::vector<std::byte>& out) const;  // appends
  // Throws std::invalid_argument when bytes is not tile_bytes(tile) long.
  void unpack_tile(Film& film, std::size_t tile, std::span<const std::byte> bytes) const;

  // Completes a film whose every tile is in (corners mode: averages the corners).
  void finish(Film& film) const;

  TraceStats stats() const;  // every render_tiles call so far, summed over the threads
  int threads() const;
  SphereMethod sphere_method() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace quiver
