#include "integrator/render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "integrator/camera.h"
#include "integrator/thread_arena.h"

namespace quiver {

namespace {

double largest_channel(const Vec3<double>& a) { return std::max(a.x, std::max(a.y, a.z)); }

float max_difference(const Vec3<float>& a, const Vec3<float>& b) {
  return std::max(std::fabs(a.x - b.x), std::max(std::fabs(a.y - b.y), std::fabs(a.z - b.z)));
}

// refine: a pixel's running sums (its samples, and their channels clamped to
// [0, 1] for the error estimate) and its strata per side.
struct RefinedPixel {
  Vec3<float> sum{0.f, 0.f, 0.f};
  Vec3<double> clamped_sum{0.0, 0.0, 0.0}, clamped_squares{0.0, 0.0, 0.0};
  int count = 0;
  int side = 0;
  std::uint32_t first = 0;  // its strata's start in Worker::strata
  // What its first-pass samples met: one material (-1: nothing), or mixed;
  // the nearest and farthest distance (a miss: infinity).
  std::int32_t material = -1;
  bool mixed_materials = false;
  float nearest = std::numeric_limits<float>::infinity(), farthest = 0.f;
};

// refine: a pixel's samples meet different surfaces: more than one
// material (nothing counting as one), or distances a depth jump apart.
bool meets_several_surfaces(const RefinedPixel& p) {
  return p.mixed_materials || p.farthest > p.nearest * (1.f + AntiAliasing::kDepthJump);
}

// refine: two pixels' samples meet different surfaces: either meets
// several, their materials differ, or their distances lie a jump apart.
bool surfaces_differ(const RefinedPixel& a, const RefinedPixel& b) {
  return meets_several_surfaces(a) || meets_several_surfaces(b) || a.material != b.material ||
         std::max(a.nearest, b.nearest) > std::min(a.farthest, b.farthest) * (1.f + AntiAliasing::kDepthJump);
}

// refine: one stratum of a pixel at the pixel's side, and its sample's
// offset in the pixel.
struct StratumSample {
  int i, j;
  double x, y;
};

// grid, jitter, none: a sub-pixel cell (column i, row j) of N x N and its centre.
struct SubPixelCell {
  int i, j;
  double cx, cy;
};

// Per-thread state: a tracer and its buffers, reused tile after tile.
struct Worker {
  Tracer tracer;
  TraceStats stats;
  FilmSamples film;  // the batch being traced
  std::vector<Vec3<float>> colors;
  std::vector<Ray<float>> centre_rays;
  std::vector<FirstHit> first;
  std::vector<std::int32_t> lattice;  // adaptive: sample index per lattice point, -1 unset
  std::vector<RefinedPixel> refined;  // refine: per pixel of the tile
  std::vector<StratumSample> strata, next_strata;  // refine: per pixel, side^2 strata at a time
  std::vector<std::uint32_t> owner;  // refine: the pixel of each traced sample
  std::vector<std::uint8_t> uncertain;  // refine: per pixel, refined in the next pass
  std::vector<SampleSurface> sample_surfaces;  // refine's first pass: per traced sample
  Worker(const Scene& scene, const SceneIntersector& intersector, const TraceSettings& settings)
      : tracer(scene, intersector, settings) {}
};

class TileRenderer {
 public:
  TileRenderer(const Camera& camera, const RenderSettings& settings, Framebuffer& image,
               std::vector<Vec3<float>>* corners, bool differentials)
      : camera_(camera), settings_(settings), image_(image), corners_(corners), differentials_(differentials) {
    // grid, jitter, none: each sub-pixel cell's column, row and centre, once.
    const AntiAliasing::Mode mode = settings.aa.mode;
    if (mode == AntiAliasing::Mode::none || mode == AntiAliasing::Mode::grid || mode == AntiAliasing::Mode::jitter) {
      cells_per_side_ = mode == AntiAliasing::Mode::none ? 1 : settings.aa.n;
      const int n = cells_per_side_;
      for (int j = 0; j < n * n; ++j) cells_.push_back({j % n, j / n, (j % n + 0.5) / n, (j / n + 0.5) / n});
    }
  }

  void render(const PixelTile& tile, Worker& w) const {
    switch (settings_.aa.mode) {
      case AntiAliasing::Mode::none:
      case AntiAliasing::Mode::grid:
      case AntiAliasing::Mode::jitter: render_supersampled(tile, w); break;
      case AntiAliasing::Mode::corners: render_corners(tile, w); break;
      case AntiAliasing::Mode::adaptive: render_adaptive(tile, w); break;
      case AntiAliasing::Mode::refine: render_refined(tile, w); break;
    }
    if (settings_.aov_depth || settings_.aov_normal || settings_.aov_id) render_aovs(tile, w);
  }

 private:
  // Starts a batch of camera samples; cells are kept when rays carry differentials.
  void start_batch(Worker& w) const { w.film.clear(differentials_); }

  void trace(Worker& w, std::span<SampleSurface> surfaces = {}) const {
    w.colors.resize(w.film.size());
    w.tracer.trace(camera_, w.film, w.colors, w.stats, surfaces);
  }

  void set_pixel(int x, int y, const Vec3<float>& c) const {
    float* p = &image_.rgb[(std::size_t(y) * std::size_t(image_.width) + std::size_t(x)) * 3];
    p[0] = c.x;
    p[1] = c.y;
    p[2] = c.z;
  }

  // none, grid:N, jitter:N: N x N samples per pixel, averaged.
  void render_supersampled(const PixelTile& tile, Worker& w) const {
    const bool jitter = settings_.aa.mode == AntiAliasing::Mode::jitter;
    const int n = cells_per_side_;
    const int x1 = tile.x0 + tile.width, y1 = tile.y0 + tile.height;
    const double spacing = 1.0 / n;
    start_batch(w);
    w.film.resize(std::size_t(tile.width) * std::size_t(tile.height) * std::size_t(n * n));
    std::size_t next = 0;
    for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) {
      const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(image_.width) + std::uint64_t(x);
      for (int j = 0; j < n * n; ++j) {
        const SubPixelCell& cell = cells_[std::size_t(j)];
        double ox = cell.cx, oy = cell.cy;
        if (jitter) {
          ox = (cell.i + hash_uniform(settings_.trace.seed, pixel, 2 * j)) / n;
          oy = (cell.j + hash_uniform(settings_.trace.seed, pixel, 2 * j + 1)) / n;
        }
        w.film.set(next++, x + ox, y + oy, x + cell.cx, y + cell.cy, spacing);
      }
    });
    trace(w);
    const float inv = 1.f / float(n * n);
    std::size_t k = 0;
    for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) {
      Vec3<float> sum{0.f, 0.f, 0.f};
      for (int j = 0; j < n * n; ++j) sum = sum + w.colors[k++];
      set_pixel(x, y, sum * inv);
    });
  }

  // The SPD rule, part one: the rays at the corners this tile owns (its
  // top-left corners, plus the image's right and bottom edges), each traced
  // once; render() averages them into pixels when every tile is done.
  void render_corners(const PixelTile& tile, Worker& w) const {
    const int x1 = tile.x0 + tile.width + (tile.x0 + tile.width == image_.width ? 1 : 0);
    const int y1 = tile.y0 + tile.height + (tile.y0 + tile.height == image_.height ? 1 : 0);
    start_batch(w);
    w.film.resize(std::size_t(x1 - tile.x0) * std::size_t(y1 - tile.y0));
    std::size_t next = 0;
    for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) { w.film.set(next++, x, y, x, y, 1.0); });
    trace(w);
    std::size_t k = 0;
    for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) {
      (*corners_)[std::size_t(y) * (image_.width + 1) + x] = w.colors[k++];
    });
  }

  // Adaptive: corners on a lattice of 2^depth points per pixel side; level by
  // level, every square whose corners differ by more than the threshold asks
  // for its centre and edge midpoints, all of a level traced as one batch.
  void render_adaptive(const PixelTile& tile, Worker& w) const {
    const int depth = settings_.aa.depth;
    const int scale = 1 << depth;
    const int lw = tile.width * scale + 1, lh = tile.height * scale + 1;
    w.lattice.assign(std::size_t(lw) * std::size_t(lh), -1);
    std::vector<Vec3<float>> values;
    // Lattice points of the current batch, each with its spacing (the size
    // of the squares it is a corner of, in pixels) for texture filtering.
    std::vector<std::pair<std::int32_t, double>> pending;

    auto request = [&](int X, int Y, int size) {
      std::int32_t& slot = w.lattice[std::size_t(Y) * lw + X];
      if (slot != -1) return;
      slot = -2;  // requested
      pending.push_back({Y * lw + X, double(size) / scale});
    };
    auto run_batch = [&]() {
      start_batch(w);
      for (const auto& [p, spacing] : pending) {
        const int X = p % lw, Y = p / lw;
        const double x = tile.x0 + double(X) / scale, y = tile.y0 + double(Y) / scale;
        w.film.push(x, y, x, y, spacing);
      }
      trace(w);
      for (std::size_t k = 0; k < pending.size(); ++k) {
        w.lattice[pending[k].first] = static_cast<std::int32_t>(values.size());
        values.push_back(w.colors[k]);
      }
      pending.clear();
    };
    auto at = [&](int X, int Y) { return values[w.lattice[std::size_t(Y) * lw + X]]; };
    auto splits = [&](int X, int Y, int size) {
      if (size <= 1) return false;
      const Vec3<float> c[4] = {at(X, Y), at(X + size, Y), at(X, Y + size), at(X + size, Y + size)};
      for (int a = 0; a < 4; ++a) {
        for (int b = a + 1; b < 4; ++b) {
          if (max_difference(c[a], c[b]) > settings_.aa.threshold) return true;
        }
      }
      return false;
    };

    for_each_pixel_in_groups(0, 0, tile.width + 1, tile.height + 1,
                             [&](int x, int y) { request(x * scale, y * scale, scale); });
    run_batch();
    struct Square {
      int X, Y, size;
    };
    std::vector<Square> level, next;
    for_each_pixel_in_groups(0, 0, tile.width, tile.height,
                             [&](int x, int y) { level.push_back({x * scale, y * scale, scale}); });
    while (!level.empty()) {
      next.clear();
      for (const Square& s : level) {
        if (!splits(s.X, s.Y, s.size)) continue;
        const int h = s.size / 2;
        request(s.X + h, s.Y, h);
        request(s.X, s.Y + h, h);
        request(s.X + h, s.Y + h, h);
        request(s.X + s.size, s.Y + h, h);
        request(s.X + h, s.Y + s.size, h);
        for (const Square& child : {Square{s.X, s.Y, h}, Square{s.X + h, s.Y, h}, Square{s.X, s.Y + h, h},
                                    Square{s.X + h, s.Y + h, h}}) {
          next.push_back(child);
        }
      }
      run_batch();
      std::swap(level, next);
    }
    // A square's colour: the mean of its four children if it split, else of its corners.
    std::vector<Square> stack;
    for (int y = 0; y < tile.height; ++y) {
      for (int x = 0; x < tile.width; ++x) {
        Vec3<float> sum{0.f, 0.f, 0.f};
        stack.assign(1, {x * scale, y * scale, scale});
        // Weighted by area: a square of size s counts (s / scale)^2.
        while (!stack.empty()) {
          const Square s = stack.back();
          stack.pop_back();
          if (splits(s.X, s.Y, s.size)) {
            const int h = s.size / 2;
            stack.push_back({s.X + h, s.Y + h, h});
            stack.push_back({s.X, s.Y + h, h});
            stack.push_back({s.X + h, s.Y, h});
            stack.push_back({s.X, s.Y, h});
            continue;
          }
          const float weight = float(s.size) * float(s.size) / (float(scale) * float(scale)) * 0.25f;
          sum = sum + (at(s.X, s.Y) + at(s.X + s.size, s.Y) + at(s.X, s.Y + s.size) + at(s.X + s.size, s.Y + s.size)) *
                          weight;
        }
        set_pixel(tile.x0 + x, tile.y0 + y, sum);
      }
    }
  }

  // refine:T:N (anti_aliasing.h). A stratum (i, j) at side s of pixel p has
  // its sample at ((i + u) / s, (j + v) / s), u and v hashed from the seed,
  // p and the stratum's number (strata of smaller sides first), so a pixel's
  // rays depend on it alone, not on the tile or the thread.
  void render_refined(const PixelTile& tile, Worker& w) const {
    const std::uint64_t seed = settings_.trace.seed;
    const auto stratum = [&](std::uint64_t pixel, int side, int i, int j) {
      std::uint64_t number = 0;  // strata of sides 2, 4, ... before this side
      for (int s = 2; s < side; s *= 2) number += std::uint64_t(s) * std::uint64_t(s);
      number += std::uint64_t(j) * std::uint64_t(side) + std::uint64_t(i);
      return StratumSample{i, j, (i + double(hash_uniform(seed, pixel, 2 * number))) / side,
                           (j + double(hash_uniform(seed, pixel, 2 * number + 1))) / side};
    };
    const int x1 = tile.x0 + tile.width, y1 = tile.y0 + tile.height;
    // The first pass also covers a one-pixel apron around the tile, so every
    // pixel's neighbours are known whatever the tiles.
    const int ex0 = std::max(0, tile.x0 - 1), ey0 = std::max(0, tile.y0 - 1);
    const int ex1 = std::min(image_.width, x1 + 1), ey1 = std::min(image_.height, y1 + 1);
    const auto local = [&](int x, int y) { return std::size_t(y - ey0) * std::size_t(ex1 - ex0) + std::size_t(x - ex0); };
    const auto pixel_number = [&](int x, int y) { return std::uint64_t(y) * std::uint64_t(image_.width) + std::uint64_t(x); };
    w.refined.assign(std::size_t(ex1 - ex0) * std::size_t(ey1 - ey0), RefinedPixel{});
    w.strata.clear();
    start_batch(w);
    w.owner.clear();
    // First pass: 2 x 2 strata for every pixel.
    for_each_pixel_in_groups(ex0, ey0, ex1, ey1, [&](int x, int y) {
      RefinedPixel& px = w.refined[local(x, y)];
      px.side = 2;
      px.first = static_cast<std::uint32_t>(w.strata.size());
      for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) w.strata.push_back(stratum(pixel_number(x, y), 2, i, j));
      }
    });
    const auto trace_new = [&](bool first_pass) {
      w.sample_surfaces.resize(first_pass ? w.film.size() : 0);
      trace(w, w.sample_surfaces);
      for (std::size_t k = 0; k < w.film.size(); ++k) {
        RefinedPixel& px = w.refined[w.owner[k]];
        if (first_pass) {
          const SampleSurface& met = w.sample_surfaces[k];
          const float distance = met.material < 0 ? std::numeric_limits<float>::infinity() : met.distance;
          if (px.count == 0) px.material = met.material;
          px.mixed_materials = px.mixed_materials || met.material != px.material;
          px.nearest = std::min(px.nearest, distance);
          px.farthest = std::max(px.farthest, distance);
        }
        const Vec3<float>& c = w.colors[k];
        px.sum = px.sum + c;
        const Vec3<double> clamped{std::clamp(double(c.x), 0.0, 1.0), std::clamp(double(c.y), 0.0, 1.0),
                                   std::clamp(double(c.z), 0.0, 1.0)};
        px.clamped_sum = px.clamped_sum + clamped;
        px.clamped_squares = px.clamped_squares + mul(clamped, clamped);
        ++px.count;
      }
      start_batch(w);
      w.owner.clear();
    };
    for_each_pixel_in_groups(ex0, ey0, ex1, ey1, [&](int x, int y) {
      const RefinedPixel& px = w.refined[local(x, y)];
      for (int k = 0; k < 4; ++k) {
        const StratumSample& st = w.strata[px.first + k];
        w.film.push(x + st.x, y + st.y, x + (st.i + 0.5) / 2, y + (st.j + 0.5) / 2, 0.5);
        w.owner.push_back(static_cast<std::uint32_t>(local(x, y)));
      }
    });
    trace_new(true);
    const float threshold = settings_.aa.threshold;
    const auto mean_clamped = [](const RefinedPixel& px) { return px.clamped_sum * (1.0 / px.count); };
    const auto too_uncertain = [&](const RefinedPixel& px) {
      const Vec3<double> mean = mean_clamped(px);
      const Vec3<double> variance = (px.clamped_squares - mul(mean, px.clamped_sum)) * (1.0 / (px.count - 1));
      const double largest = largest_channel(variance);
      return largest > 0.0 && largest / px.count > double(threshold) * double(threshold);
    };
    // The first pass's verdict: the pixel's own error, its samples meeting
    // different surfaces, or a neighbour's mean or surfaces.
    std::vector<std::uint8_t>& refine = w.uncertain;
    refine.assign(w.refined.size(), 0);
    for (int y = tile.y0; y < y1; ++y) {
      for (int x = tile.x0; x < x1; ++x) {
        const RefinedPixel& px = w.refined[local(x, y)];
        bool more = too_uncertain(px) || meets_several_surfaces(px);
        const Vec3<double> mean = mean_clamped(px);
        const auto differs = [&](int nx, int ny) {
          if (nx < ex0 || nx >= ex1 || ny < ey0 || ny >= ey1) return false;
          const RefinedPixel& neighbour = w.refined[local(nx, ny)];
          const Vec3<double> d = mean - mean_clamped(neighbour);
          const double contrast = largest_channel(Vec3<double>{std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
          return contrast > double(AntiAliasing::kNeighbourContrast) * double(threshold) ||
                 surfaces_differ(px, neighbour);
        };
        more = more || differs(x - 1, y) || differs(x + 1, y) || differs(x, y - 1) || differs(x, y + 1);
        refine[local(x, y)] = more;
      }
    }
    // Refinement passes: side s -> 2s for the pixels still uncertain.
    for (int side = 2; side < settings_.aa.n; side *= 2) {
      w.next_strata.clear();
      bool any = false;
      for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) {
        RefinedPixel& px = w.refined[local(x, y)];
        const std::uint32_t first = static_cast<std::uint32_t>(w.next_strata.size());
        const int count = px.side * px.side;
        if (!refine[local(x, y)]) {
          w.next_strata.insert(w.next_strata.end(), w.strata.begin() + px.first, w.strata.begin() + px.first + count);
          px.first = first;
          return;
        }
        any = true;
        const int child = 2 * side;
        for (int k = 0; k < count; ++k) {
          const StratumSample& st = w.strata[px.first + k];
          // The sub-stratum holding this stratum's sample (clamped against rounding).
          const int ci = std::clamp(int(st.x * child), 2 * st.i, 2 * st.i + 1);
          const int cj = std::clamp(int(st.y * child), 2 * st.j, 2 * st.j + 1);
          for (int b = 0; b < 2; ++b) {
            for (int a = 0; a < 2; ++a) {
              const int i = 2 * st.i + a, j = 2 * st.j + b;
              if (i == ci && j == cj) {
                w.next_strata.push_back({i, j, st.x, st.y});
                continue;
              }
              const StratumSample fresh = stratum(pixel_number(x, y), child, i, j);
              w.next_strata.push_back(fresh);
              w.film.push(x + fresh.x, y + fresh.y, x + (i + 0.5) / child, y + (j + 0.5) / child, 1.0 / child);
              w.owner.push_back(static_cast<std::uint32_t>(local(x, y)));
            }
          }
        }
        px.first = first;
        px.side = child;
      });
      std::swap(w.strata, w.next_strata);
      if (!any) break;
      trace_new(false);
      for (std::size_t k = 0; k < w.refined.size(); ++k) {
        refine[k] = refine[k] && w.refined[k].side == 2 * side && too_uncertain(w.refined[k]);
      }
    }
    for (int y = tile.y0; y < y1; ++y) {
      for (int x = tile.x0; x < x1; ++x) {
        const RefinedPixel& px = w.refined[local(x, y)];
        set_pixel(x, y, px.sum * (1.f / float(px.count)));
      }
    }
  }

  void render_aovs(const PixelTile& tile, Worker& w) const {
    w.centre_rays.clear();
    for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
      for (int x = tile.x0; x < tile.x0 + tile.width; ++x) w.centre_rays.push_back(camera_.ray(x + 0.5, y + 0.5));
    }
    w.first.resize(w.centre_rays.size());
    w.tracer.first_hits(w.centre_rays, w.first);
    std::size_t k = 0;
    for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
      for (int x = tile.x0; x < tile.x0 + tile.width; ++x, ++k) {
        const std::size_t p = std::size_t(y) * std::size_t(image_.width) + std::size_t(x);
        const FirstHit& f = w.first[k];
        if (settings_.aov_depth) image_.depth[p] = f.depth;
        if (settings_.aov_normal) {
          image_.normal[3 * p] = f.normal.x;
          image_.normal[3 * p + 1] = f.normal.y;
          image_.normal[3 * p + 2] = f.normal.z;
        }
        if (settings_.aov_id) {
          image_.kind[p] = f.kind;
          image_.id[p] = f.id;
        }
      }
    }
  }

  const Camera& camera_;
  const RenderSettings& settings_;
  Framebuffer& image_;
  std::vector<Vec3<float>>* corners_;  // corners mode: (W + 1) x (H + 1) colours
  bool differentials_;                 // rays_carry_differentials (tracer.h)
  int cells_per_side_ = 1;             // grid, jitter: N; none: 1
  std::vector<SubPixelCell> cells_;    // grid, jitter, none: a pixel's N x N cells
};

// The SPD rule, part two: each pixel the mean of its four corners.
void average_corners(const std::vector<Vec3<float>>& corners, Framebuffer& image) {
  const std::size_t cw = std::size_t(image.width) + 1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::size_t i = std::size_t(y) * cw + std::size_t(x);
      const Vec3<float> c = (corners[i] + corners[i + 1] + corners[i + cw] + corners[i + cw + 1]) * 0.25f;
      float* p = &image.rgb[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3];
      p[0] = c.x;
      p[1] = c.y;
      p[2] = c.z;
    }
  }
}

}  // namespace

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
  tbb::enumerable_thread_specific<Worker> workers;
  ThreadArena arena;

  State(const Scene& s, const RenderSettings& rs)
      : scene(s),
        settings(rs),
        camera(s.camera, rs.width, rs.height),
        tiles(pixel_tiles(rs.width, rs.height, rs.tile_size)),
        intersector(kernel_unit_for(rs.isa), choose_sphere_method(s, rs.methods)),
        workers([this] { return Worker(scene, intersector, settings.trace); }),
        arena(rs.threads) {}

  bool corners_mode() const { return settings.aa.mode == AntiAliasing::Mode::corners; }

  // The corners a tile owns: its top-left corners, plus the image's right
  // and bottom edges (TileRenderer::render_corners).
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
  const TileRenderer tile_renderer(s.camera, s.settings, film.image, &film.corners,
                                   rays_carry_differentials(s.scene, s.settings.trace));
  std::atomic<std::size_t> rendered{0};
  s.arena.execute([&] {
    // Each iteration renders at most one tile, whichever next() gives.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, s.tiles.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          Worker& w = s.workers.local();
          for (std::size_t k = range.begin(); k != range.end(); ++k) {
            if (stop != nullptr && stop->load(std::memory_order_relaxed)) return;
            const std::optional<std::size_t> t = next();
            if (!t) return;
            // camera_and_film: the tile's time less what the tracer charged to its phases.
            const std::uint64_t traced_before = w.stats.phases.total();
            PhaseClock clock;
            std::uint64_t tile_time = 0;
            tile_renderer.render(s.tiles.at(*t), w);
            clock.charge(tile_time);
            const std::uint64_t traced = w.stats.phases.total() - traced_before;
            w.stats.phases.camera_and_film += tile_time > traced ? tile_time - traced : 0;
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
      Worker& w = s.workers.local();
      TraceStats scratch;
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const PixelTile& tile = s.tiles.at(tiles[k]);
        w.film.clear(false);
        for (int y = tile.y0 + stride / 2; y < tile.y0 + tile.height; y += stride) {
          for (int x = tile.x0 + stride / 2; x < tile.x0 + tile.width; x += stride) w.film.push(x + 0.5, y + 0.5, 0, 0, 0);
        }
        const std::uint64_t before = scratch.rays.total();
        w.colors.resize(w.film.size());
        w.tracer.trace(s.camera, w.film, w.colors, scratch);
        costs[k] = double(scratch.rays.total() - before);
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
  for (const Worker& w : state_->workers) total.add(w.stats);
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
  renderer.render_tiles(
      film,
      [&]() -> std::optional<std::size_t> {
        const std::size_t t = next++;
        if (t < total) return t;
        return std::nullopt;
      },
      [&](std::size_t, double) {
        const std::size_t finished = ++done;
        if (progress) {
          std::lock_guard lock(progress_mutex);
          progress(finished, total);
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
