#include "integrator/corner_sampling.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace quiver {

void render_corners(const TileTarget& target, const PixelTile& tile, SampleBatch& batch,
                    std::vector<Vec3<float>>& corners) {
  const Framebuffer& image = target.image;
  const int x1 = tile.x0 + tile.width + (tile.x0 + tile.width == image.width ? 1 : 0);
  const int y1 = tile.y0 + tile.height + (tile.y0 + tile.height == image.height ? 1 : 0);
  target.start_batch(batch);
  batch.film.resize(std::size_t(x1 - tile.x0) * std::size_t(y1 - tile.y0));
  std::size_t next = 0;
  for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) { batch.film.set(next++, x, y, x, y, 1.0); });
  target.trace(batch);
  std::size_t k = 0;
  for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) {
    corners[std::size_t(y) * (image.width + 1) + x] = batch.colors[k++];
  });
}

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

namespace {

// A square of the lattice: its top-left point and side, in lattice steps.
struct Square {
  int X, Y, size;
};

// One tile's lattice of 2^depth points per pixel side: points requested,
// traced a batch at a time, and the squares' verdicts.
class AdaptiveTile {
 public:
  AdaptiveTile(const TileTarget& target, const PixelTile& tile, SampleBatch& batch, AdaptiveLattice& lattice)
      : target_(target),
        tile_(tile),
        batch_(batch),
        sample_(lattice.sample),
        scale_(1 << target.settings.aa.depth),
        lw_(tile.width * scale_ + 1) {
    const int lh = tile.height * scale_ + 1;
    sample_.assign(std::size_t(lw_) * std::size_t(lh), -1);
  }

  int scale() const { return scale_; }

  // Asks for point (X, Y), a corner of squares of side `size`, once.
  void request(int X, int Y, int size) {
    std::int32_t& slot = sample_[std::size_t(Y) * lw_ + X];
    if (slot != -1) return;
    slot = -2;  // requested
    pending_.push_back({Y * lw_ + X, double(size) / scale_});
  }

  // Traces the points requested since the last batch.
  void run_batch() {
    target_.start_batch(batch_);
    for (const auto& [p, spacing] : pending_) {
      const int X = p % lw_, Y = p / lw_;
      const double x = tile_.x0 + double(X) / scale_, y = tile_.y0 + double(Y) / scale_;
      batch_.film.push(x, y, x, y, spacing);
    }
    target_.trace(batch_);
    for (std::size_t k = 0; k < pending_.size(); ++k) {
      sample_[pending_[k].first] = static_cast<std::int32_t>(values_.size());
      values_.push_back(batch_.colors[k]);
    }
    pending_.clear();
  }

  const Vec3<float>& at(int X, int Y) const { return values_[sample_[std::size_t(Y) * lw_ + X]]; }

  // Whether the square's corners differ by more than the threshold.
  bool splits(const Square& s) const {
    if (s.size <= 1) return false;
    return corners_differ({at(s.X, s.Y), at(s.X + s.size, s.Y), at(s.X, s.Y + s.size), at(s.X + s.size, s.Y + s.size)},
                          target_.settings.aa.threshold);
  }

 private:
  const TileTarget& target_;
  const PixelTile& tile_;
  SampleBatch& batch_;
  std::vector<std::int32_t>& sample_;
  int scale_, lw_;
  std::vector<Vec3<float>> values_;
  // Lattice points of the current batch, each with its spacing (the size
  // of the squares it is a corner of, in pixels) for texture filtering.
  std::vector<std::pair<std::int32_t, double>> pending_;
};

// The corners of every pixel, then level by level the centre and edge
// midpoints of every square that splits.
void sample_lattice(const PixelTile& tile, AdaptiveTile& lattice) {
  const int scale = lattice.scale();
  for_each_pixel_in_groups(0, 0, tile.width + 1, tile.height + 1,
                           [&](int x, int y) { lattice.request(x * scale, y * scale, scale); });
  lattice.run_batch();
  std::vector<Square> level, next;
  for_each_pixel_in_groups(0, 0, tile.width, tile.height,
                           [&](int x, int y) { level.push_back({x * scale, y * scale, scale}); });
  while (!level.empty()) {
    next.clear();
    for (const Square& s : level) {
      if (!lattice.splits(s)) continue;
      const int h = s.size / 2;
      lattice.request(s.X + h, s.Y, h);
      lattice.request(s.X, s.Y + h, h);
      lattice.request(s.X + h, s.Y + h, h);
      lattice.request(s.X + s.size, s.Y + h, h);
      lattice.request(s.X + h, s.Y + s.size, h);
      for (const Square& child : {Square{s.X, s.Y, h}, Square{s.X + h, s.Y, h}, Square{s.X, s.Y + h, h},
                                  Square{s.X + h, s.Y + h, h}}) {
        next.push_back(child);
      }
    }
    lattice.run_batch();
    std::swap(level, next);
  }
}

// A pixel's colour: a square's the mean of its four children if it split,
// else of its corners, weighted by area (a square of size s counts (s / scale)^2).
Vec3<float> pixel_colour(const AdaptiveTile& lattice, int x, int y, std::vector<Square>& stack) {
  const int scale = lattice.scale();
  Vec3<float> sum{0.f, 0.f, 0.f};
  stack.assign(1, {x * scale, y * scale, scale});
  while (!stack.empty()) {
    const Square s = stack.back();
    stack.pop_back();
    if (lattice.splits(s)) {
      const int h = s.size / 2;
      stack.push_back({s.X + h, s.Y + h, h});
      stack.push_back({s.X, s.Y + h, h});
      stack.push_back({s.X + h, s.Y, h});
      stack.push_back({s.X, s.Y, h});
      continue;
    }
    const float weight = float(s.size) * float(s.size) / (float(scale) * float(scale)) * 0.25f;
    sum = sum + (lattice.at(s.X, s.Y) + lattice.at(s.X + s.size, s.Y) + lattice.at(s.X, s.Y + s.size) +
                 lattice.at(s.X + s.size, s.Y + s.size)) *
                    weight;
  }
  return sum;
}

}  // namespace

void render_adaptive(const TileTarget& target, const PixelTile& tile, SampleBatch& batch, AdaptiveLattice& lattice) {
  AdaptiveTile points(target, tile, batch, lattice);
  sample_lattice(tile, points);
  std::vector<Square> stack;
  for (int y = 0; y < tile.height; ++y) {
    for (int x = 0; x < tile.width; ++x) target.set_pixel(tile.x0 + x, tile.y0 + y, pixel_colour(points, x, y, stack));
  }
}

}  // namespace quiver
