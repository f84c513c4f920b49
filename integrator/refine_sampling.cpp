#include "integrator/refine_sampling.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "integrator/sample_hash.h"

namespace quiver {

namespace {

double largest_channel(const Vec3<double>& a) { return std::max(a.x, std::max(a.y, a.z)); }

// A pixel's samples meet different surfaces: more than one material
// (nothing counting as one), or distances a depth jump apart.
bool meets_several_surfaces(const RefinedPixel& p) {
  return p.mixed_materials || p.farthest > p.nearest * (1.f + AntiAliasing::kDepthJump);
}

// Two pixels' samples meet different surfaces: either meets several, their
// materials differ, or their distances lie a jump apart.
bool surfaces_differ(const RefinedPixel& a, const RefinedPixel& b) {
  return meets_several_surfaces(a) || meets_several_surfaces(b) || a.material != b.material ||
         std::max(a.nearest, b.nearest) > std::min(a.farthest, b.farthest) * (1.f + AntiAliasing::kDepthJump);
}

Vec3<double> mean_clamped(const RefinedPixel& px) { return px.clamped_sum * (1.0 / px.count); }

// One tile's refinement: the tile and a one-pixel apron around it (so every
// pixel's neighbours are known whatever the tiles), pass by pass.
class RefineTile {
 public:
  RefineTile(const TileTarget& target, const PixelTile& tile, SampleBatch& batch, RefineBuffers& buffers)
      : target_(target),
        batch_(batch),
        b_(buffers),
        x0_(tile.x0),
        y0_(tile.y0),
        x1_(tile.x0 + tile.width),
        y1_(tile.y0 + tile.height),
        ex0_(std::max(0, tile.x0 - 1)),
        ey0_(std::max(0, tile.y0 - 1)),
        ex1_(std::min(target.image.width, x1_ + 1)),
        ey1_(std::min(target.image.height, y1_ + 1)),
        seed_(target.settings.trace.seed),
        threshold_(target.settings.aa.threshold) {}

  void render() {
    first_pass();
    judge_first_pass();
    // Refinement passes: side s -> 2s for the pixels still uncertain.
    for (int side = 2; side < target_.settings.aa.n; side *= 2) {
      if (!refine_pass(side)) break;
    }
    for (int y = y0_; y < y1_; ++y) {
      for (int x = x0_; x < x1_; ++x) {
        const RefinedPixel& px = b_.pixels[local(x, y)];
        target_.set_pixel(x, y, px.sum * (1.f / float(px.count)));
      }
    }
  }

 private:
  std::size_t local(int x, int y) const {
    return std::size_t(y - ey0_) * std::size_t(ex1_ - ex0_) + std::size_t(x - ex0_);
  }
  std::uint64_t pixel_number(int x, int y) const {
    return std::uint64_t(y) * std::uint64_t(target_.image.width) + std::uint64_t(x);
  }

  StratumSample stratum(std::uint64_t pixel, int side, int i, int j) const {
    return refine_stratum(seed_, pixel, side, i, j, target_.settings.aa.strata);
  }

  // 2 x 2 strata for every pixel of the tile and its apron, traced.
  void first_pass() {
    b_.pixels.assign(std::size_t(ex1_ - ex0_) * std::size_t(ey1_ - ey0_), RefinedPixel{});
    b_.strata.clear();
    target_.start_batch(batch_);
    b_.owner.clear();
    for_each_pixel_in_groups(ex0_, ey0_, ex1_, ey1_, [&](int x, int y) {
      RefinedPixel& px = b_.pixels[local(x, y)];
      px.side = 2;
      px.first = static_cast<std::uint32_t>(b_.strata.size());
      for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) b_.strata.push_back(stratum(pixel_number(x, y), 2, i, j));
      }
    });
    for_each_pixel_in_groups(ex0_, ey0_, ex1_, ey1_, [&](int x, int y) {
      const RefinedPixel& px = b_.pixels[local(x, y)];
      for (int k = 0; k < 4; ++k) {
        const StratumSample& st = b_.strata[px.first + k];
        batch_.film.push(x + st.x, y + st.y, x + (st.i + 0.5) / 2, y + (st.j + 0.5) / 2, 0.5);
        b_.owner.push_back(static_cast<std::uint32_t>(local(x, y)));
      }
    });
    trace_new(true);
  }

  // Traces the batch and adds each sample to its pixel (on the first pass
  // also what it met); starts the next batch.
  void trace_new(bool first_pass) {
    b_.surfaces.resize(first_pass ? batch_.film.size() : 0);
    target_.trace(batch_, b_.surfaces);
    for (std::size_t k = 0; k < batch_.film.size(); ++k) {
      RefinedPixel& px = b_.pixels[b_.owner[k]];
      if (first_pass) {
        const FirstSurface& met = b_.surfaces[k];
        const float distance = met.depth;  // infinity where nothing was met
        if (px.count == 0) px.material = met.material;
        px.mixed_materials = px.mixed_materials || met.material != px.material;
        px.nearest = std::min(px.nearest, distance);
        px.farthest = std::max(px.farthest, distance);
      }
      const Vec3<float>& c = batch_.colors[k];
      px.sum = px.sum + c;
      const Vec3<double> clamped{std::clamp(double(c.x), 0.0, 1.0), std::clamp(double(c.y), 0.0, 1.0),
                                 std::clamp(double(c.z), 0.0, 1.0)};
      px.clamped_sum = px.clamped_sum + clamped;
      px.clamped_squares = px.clamped_squares + mul(clamped, clamped);
      ++px.count;
    }
    target_.start_batch(batch_);
    b_.owner.clear();
  }

  // The first pass's verdict: the pixel's own error, its samples meeting
  // different surfaces, or a neighbour's mean or surfaces.
  void judge_first_pass() {
    b_.uncertain.assign(b_.pixels.size(), 0);
    for (int y = y0_; y < y1_; ++y) {
      for (int x = x0_; x < x1_; ++x) {
        const RefinedPixel& px = b_.pixels[local(x, y)];
        bool more = too_uncertain(px, threshold_) || meets_several_surfaces(px);
        const Vec3<double> mean = mean_clamped(px);
        const auto differs = [&](int nx, int ny) {
          if (nx < ex0_ || nx >= ex1_ || ny < ey0_ || ny >= ey1_) return false;
          const RefinedPixel& neighbour = b_.pixels[local(nx, ny)];
          const Vec3<double> d = mean - mean_clamped(neighbour);
          const double contrast = largest_channel(Vec3<double>{std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
          return contrast > double(AntiAliasing::kNeighbourContrast) * double(threshold_) ||
                 surfaces_differ(px, neighbour);
        };
        more = more || differs(x - 1, y) || differs(x + 1, y) || differs(x, y - 1) || differs(x, y + 1);
        b_.uncertain[local(x, y)] = more;
      }
    }
  }

  // Strata of side `side` -> 2 side for the uncertain pixels (each
  // stratum's sample kept in its sub-stratum, the three siblings sampled),
  // traced; false when no pixel was uncertain.
  bool refine_pass(int side) {
    b_.next_strata.clear();
    bool any = false;
    for_each_pixel_in_groups(x0_, y0_, x1_, y1_, [&](int x, int y) {
      RefinedPixel& px = b_.pixels[local(x, y)];
      const std::uint32_t first = static_cast<std::uint32_t>(b_.next_strata.size());
      const int count = px.side * px.side;
      if (!b_.uncertain[local(x, y)]) {
        b_.next_strata.insert(b_.next_strata.end(), b_.strata.begin() + px.first, b_.strata.begin() + px.first + count);
        px.first = first;
        return;
      }
      any = true;
      split_strata(x, y, px, 2 * side);
      px.first = first;
      px.side = 2 * side;
    });
    std::swap(b_.strata, b_.next_strata);
    if (!any) return false;
    trace_new(false);
    for (std::size_t k = 0; k < b_.pixels.size(); ++k) {
      b_.uncertain[k] = b_.uncertain[k] && b_.pixels[k].side == 2 * side && too_uncertain(b_.pixels[k], threshold_);
    }
    return true;
  }

  // The pixel's strata split into `child` per side, appended to next_strata;
  // the new ones' samples to the batch. Centred strata keep no coarser ray:
  // the pixel starts again from the finer centres.
  void split_strata(int x, int y, RefinedPixel& px, int child) {
    const int count = px.side * px.side;
    const bool afresh = target_.settings.aa.strata == AntiAliasing::Strata::grid;
    if (afresh) {
      px.sum = Vec3<float>(0.f, 0.f, 0.f);
      px.clamped_sum = px.clamped_squares = Vec3<double>(0.0, 0.0, 0.0);
      px.count = 0;
    }
    for (int k = 0; k < count; ++k) {
      const StratumSample& st = b_.strata[px.first + k];
      const auto [ci, cj] = sub_stratum_holding(st, child);
      for (int b = 0; b < 2; ++b) {
        for (int a = 0; a < 2; ++a) {
          const int i = 2 * st.i + a, j = 2 * st.j + b;
          if (i == ci && j == cj && !afresh) {
            b_.next_strata.push_back({i, j, st.x, st.y});
            continue;
          }
          const StratumSample fresh = stratum(pixel_number(x, y), child, i, j);
          b_.next_strata.push_back(fresh);
          batch_.film.push(x + fresh.x, y + fresh.y, x + (i + 0.5) / child, y + (j + 0.5) / child, 1.0 / child);
          b_.owner.push_back(static_cast<std::uint32_t>(local(x, y)));
        }
      }
    }
  }

  const TileTarget& target_;
  SampleBatch& batch_;
  RefineBuffers& b_;
  int x0_, y0_, x1_, y1_;      // the tile
  int ex0_, ey0_, ex1_, ey1_;  // the tile and its apron
  std::uint64_t seed_;
  float threshold_;
};

}  // namespace

StratumSample refine_stratum(std::uint64_t seed, std::uint64_t pixel, int side, int i, int j,
                             AntiAliasing::Strata strata) {
  if (strata == AntiAliasing::Strata::grid) return StratumSample{i, j, (i + 0.5) / side, (j + 0.5) / side};
  std::uint64_t number = 0;  // strata of sides 2, 4, ... before this side
  for (int s = 2; s < side; s *= 2) number += std::uint64_t(s) * std::uint64_t(s);
  number += std::uint64_t(j) * std::uint64_t(side) + std::uint64_t(i);
  return StratumSample{i, j, (i + double(hash_uniform(seed, pixel, 2 * number))) / side,
                       (j + double(hash_uniform(seed, pixel, 2 * number + 1))) / side};
}

std::array<int, 2> sub_stratum_holding(const StratumSample& st, int child) {
  // Clamped: a sample that rounds onto the next stratum's edge stays in st.
  return {std::clamp(int(st.x * child), 2 * st.i, 2 * st.i + 1), std::clamp(int(st.y * child), 2 * st.j, 2 * st.j + 1)};
}

bool too_uncertain(const RefinedPixel& px, float threshold) {
  const Vec3<double> mean = mean_clamped(px);
  const Vec3<double> variance = (px.clamped_squares - mul(mean, px.clamped_sum)) * (1.0 / (px.count - 1));
  const double largest = largest_channel(variance);
  return largest > 0.0 && largest / px.count > double(threshold) * double(threshold);
}

void render_refined(const TileTarget& target, const PixelTile& tile, SampleBatch& batch, RefineBuffers& buffers) {
  RefineTile(target, tile, batch, buffers).render();
}

}  // namespace quiver
