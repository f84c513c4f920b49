#include "integrator/render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "integrator/camera.h"
#include "integrator/thread_arena.h"
#include "integrator/tile_renderer.h"

namespace quiver {

std::vector<PixelTile> pixel_tiles(int width, int height, int side) {
  if (side < 1) throw std::invalid_argument("tile side must be at least 1");
  std::vector<PixelTile> tiles;
  for (int y = 0; y < height; y += side) {
    for (int x = 0; x < width; x += side) {
      tiles.push_back({x, y, std::min(side, width - x), std::min(side, height - y)});
    }
  }
  return tiles;
}

struct FrameRenderer::State {
  const Scene& scene;
  RenderSettings settings;
  Camera camera;
  std::vector<PixelTile> tiles;
  SceneIntersector intersector;
  tbb::enumerable_thread_specific<TileWorker> workers;
  ThreadArena arena;

  State(const Scene& s, const RenderSettings& rs)
      : scene(s),
        settings(rs),
        camera(s.camera, rs.width, rs.height),
        tiles(pixel_tiles(rs.width, rs.height, rs.tile_size)),
        intersector(kernel_unit_for(rs.isa), choose_sphere_method(s, rs.methods)),
        workers([this] { return TileWorker(scene, intersector, settings.trace); }),
        arena(rs.threads) {}

  bool corners_mode() const { return settings.aa.mode == AntiAliasing::Mode::corners; }

  // The corners a tile owns: its top-left corners, plus the image's right
  // and bottom edges (render_corners).
  PixelTile owned_corners(const PixelTile& tile) const {
    return {tile.x0, tile.y0, tile.width + (tile.x0 + tile.width == settings.width ? 1 : 0),
            tile.height + (tile.y0 + tile.height == settings.height ? 1 : 0)};
  }

  // Visits each of a tile's parts of the film as (pointer to its first
  // element in a row, bytes per row) for every row of the tile, in the
  // order pack_tile lays them out.
  template <class FilmRef, class Visit>
  void for_each_tile_row(FilmRef& film, const PixelTile& tile, Visit&& visit) const {
    const auto rows = [&](const PixelTile& r, std::size_t row_width, auto* base, std::size_t per_element) {
      if (base == nullptr) return;
      for (int y = r.y0; y < r.y0 + r.height; ++y) {
        const std::size_t first = (std::size_t(y) * row_width + std::size_t(r.x0)) * per_element;
        visit(reinterpret_cast<std::conditional_t<std::is_const_v<FilmRef>, const std::byte*, std::byte*>>(base + first),
              std::size_t(r.width) * per_element * sizeof(*base));
      }
    };
    const std::size_t w = std::size_t(settings.width);
    if (corners_mode()) {
      rows(owned_corners(tile), w + 1, film.corners.data(), 1);
    } else {
      rows(tile, w, film.image.rgb.data(), 3);
    }
    if (settings.aov_depth) rows(tile, w, film.image.depth.data(), 1);
    if (settings.aov_normal) rows(tile, w, film.image.normal.data(), 3);
    if (settings.aov_id) {
      rows(tile, w, film.image.kind.data(), 1);
      rows(tile, w, film.image.id.data(), 1);
    }
  }
};

FrameRenderer::FrameRenderer(const Scene& scene, const RenderSettings& settings) {
  if (settings.tile_size < 1) throw std::invalid_argument("tile size must be at least 1");
  state_ = std::make_unique<State>(scene, settings);
}

FrameRenderer::~FrameRenderer() = default;

const std::vector<PixelTile>& FrameRenderer::tiles() const { return state_->tiles; }

Film FrameRenderer::make_film() const {
  const RenderSettings& settings = state_->settings;
  Film film;
  Framebuffer& image = film.image;
  image = Framebuffer(settings.width, settings.height);
  const std::size_t pixels = image.pixel_count();
  if (settings.aov_depth) image.depth.assign(pixels, 0.f);
  if (settings.aov_normal) image.normal.assign(3 * pixels, 0.f);
  if (settings.aov_id) {
    image.kind.assign(pixels, kNoKind);
    image.id.assign(pixels, -1);
  }
  if (state_->corners_mode()) {
    film.corners.resize((std::size_t(settings.width) + 1) * (std::size_t(settings.height) + 1));
  }
  return film;
}

std::size_t FrameRenderer::render_tiles(Film& film, const TileSource& next, const TileDone& done,
                                        const std::atomic<bool>* stop) {
  State& s = *state_;
  const TileTarget target{s.camera, s.settings, film.image, rays_carry_differentials(s.scene, s.settings.trace)};
  const TileRenderer tile_renderer(target, &film.corners);
  std::atomic<std::size_t> rendered{0};
  s.arena.execute([&] {
    // Each iteration renders at most one tile, whichever next() gives.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, s.tiles.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          TileWorker& w = s.workers.local();
          for (std::size_t k = range.begin(); k != range.end(); ++k) {
            if (stop != nullptr && stop->load(std::memory_order_relaxed)) return;
            const std::optional<std::size_t> t = next();
            if (!t) return;
            // camera_and_film: the tile's time less what the tracer charged to its phases.
            const std::uint64_t traced_before = w.batch.stats.phases.total();
            PhaseClock clock(true);
            std::uint64_t tile_time = 0;
            tile_renderer.render(s.tiles.at(*t), w);
            clock.charge(tile_time);
            const std::uint64_t traced = w.batch.stats.phases.total() - traced_before;
            if (s.settings.trace.time_phases) {
              w.batch.stats.phases.camera_and_film += tile_time > traced ? tile_time - traced : 0;
            }
            ++rendered;
            if (done) done(*t, double(tile_time) / 1e6);
          }
        },
        tbb::simple_partitioner());
  });
  return rendered.load();
}

std::vector<double> FrameRenderer::estimate_costs(std::span<const std::size_t> tiles, int stride) const {
  State& s = *state_;
  stride = std::max(stride, 1);
  std::vector<double> costs(tiles.size(), 0.0);
  s.arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles.size(), 16), [&](const tbb::blocked_range<std::size_t>& range) {
      SampleBatch& w = s.workers.local().batch;
      TraceStats scratch;
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const PixelTile& tile = s.tiles.at(tiles[k]);
        w.film.clear(false);
        for (int y = tile.y0 + stride / 2; y < tile.y0 + tile.height; y += stride) {
          for (int x = tile.x0 + stride / 2; x < tile.x0 + tile.width; x += stride) w.film.push(x + 0.5, y + 0.5, 0, 0, 0);
        }
        w.colors.resize(w.film.size());
        const auto start = std::chrono::steady_clock::now();
        w.tracer.trace(s.camera, w.film, w.colors, scratch);
        costs[k] = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
      }
    });
  });
  return costs;
}

std::size_t FrameRenderer::tile_bytes(std::size_t tile) const {
  std::size_t bytes = 0;
  const PixelTile& t = state_->tiles.at(tile);
  const RenderSettings& settings = state_->settings;
  const PixelTile c = state_->corners_mode() ? state_->owned_corners(t) : t;
  bytes += std::size_t(c.width) * std::size_t(c.height) * 3 * sizeof(float);
  const std::size_t pixels = std::size_t(t.width) * std::size_t(t.height);
  if (settings.aov_depth) bytes += pixels * sizeof(float);
  if (settings.aov_normal) bytes += pixels * 3 * sizeof(float);
  if (settings.aov_id) bytes += pixels * 2 * sizeof(std::int32_t);
  return bytes;
}

void FrameRenderer::pack_tile(const Film& film, std::size_t tile, std::vector<std::byte>& out) const {
  state_->for_each_tile_row(film, state_->tiles.at(tile), [&](const std::byte* row, std::size_t bytes) {
    out.insert(out.end(), row, row + bytes);
  });
}

void FrameRenderer::unpack_tile(Film& film, std::size_t tile, std::span<const std::byte> bytes) const {
  if (bytes.size() != tile_bytes(tile)) {
    throw std::invalid_argument("tile " + std::to_string(tile) + ": expected " + std::to_string(tile_bytes(tile)) +
                                " bytes, found " + std::to_string(bytes.size()));
  }
  std::size_t at = 0;
  state_->for_each_tile_row(film, state_->tiles.at(tile), [&](std::byte* row, std::size_t n) {
    std::memcpy(row, bytes.data() + at, n);
    at += n;
  });
}

void FrameRenderer::finish(Film& film) const {
  if (state_->corners_mode()) average_corners(film.corners, film.image);
}

TraceStats FrameRenderer::stats() const {
  TraceStats total;
  for (const TileWorker& w : state_->workers) total.add(w.batch.stats);
  return total;
}

int FrameRenderer::threads() const { return state_->arena.threads(); }

SphereMethod FrameRenderer::sphere_method() const { return state_->intersector.sphere_method(); }

RenderResult render(const Scene& scene, const RenderSettings& settings, const RenderProgress& progress,
                    const std::atomic<bool>* stop) {
  FrameRenderer renderer(scene, settings);
  Film film = renderer.make_film();
  const std::size_t total = renderer.tiles().size();
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex progress_mutex;
  RenderResult result;
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> weights;
  WorkDone work;
  if (progress) {
    std::vector<std::size_t> all(total);
    std::iota(all.begin(), all.end(), std::size_t(0));
    weights = renderer.estimate_costs(all, kTileCostStride);
    for (double& w : weights) work.add_to_total(w = WorkDone::weight(w));
  }
  const auto tiles_start = std::chrono::steady_clock::now();
  renderer.render_tiles(
      film,
      [&]() -> std::optional<std::size_t> {
        const std::size_t t = next++;
        if (t < total) return t;
        return std::nullopt;
      },
      [&](std::size_t tile, double) {
        const std::size_t finished = ++done;
        if (progress) {
          std::lock_guard lock(progress_mutex);
          work.add_done(weights[tile]);
          progress({finished, total, work.share(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - tiles_start).count()});
        }
      },
      stop);
  result.tiles_total = total;
  result.tiles_done = done.load();
  if (!result.stopped()) renderer.finish(film);
  result.render_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.image = std::move(film.image);
  result.stats = renderer.stats();
  result.threads = renderer.threads();
  result.sphere_method = renderer.sphere_method();
  return result;
}

}  // namespace quiver
