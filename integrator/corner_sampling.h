// Samples at pixel corners, shared with the neighbours:
//   corners: the SPD rule, (W+1) x (H+1) rays, each pixel the mean of its
//            four (render_corners traces a tile's corners, average_corners
//            makes the pixels once every tile is done);
//   adaptive:T:D: corners on a lattice of 2^D points per pixel side; a
//            square whose corner colours differ by more than T in some
//            channel asks for its centre and edge midpoints and splits into
//            four, down to D levels (Whitted 1980; POV-Ray's method 2); a
//            pixel is the area-weighted mean of its squares.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "integrator/tile_sampling.h"

namespace quiver {

// The rays at the corners this tile owns (its top-left corners, plus the
// image's right and bottom edges), each traced once, into corners
// ((W + 1) x (H + 1) colours).
void render_corners(const TileTarget& target, const PixelTile& tile, SampleBatch& batch,
                    std::vector<Vec3<float>>& corners);

// Each pixel of image the mean of its four corners.
void average_corners(const std::vector<Vec3<float>>& corners, Framebuffer& image);

// Whether an adaptive square splits: two of its corners' colours (any
// order) differ by more than threshold in some channel. Inline: the lattice
// asks it of every square, twice.
inline bool corners_differ(const std::array<Vec3<float>, 4>& c, float threshold) {
  const auto max_difference = [](const Vec3<float>& a, const Vec3<float>& b) {
    return std::max(std::fabs(a.x - b.x), std::max(std::fabs(a.y - b.y), std::fabs(a.z - b.z)));
  };
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) {
      if (max_difference(c[a], c[b]) > threshold) return true;
    }
  }
  return false;
}

// adaptive's per-worker buffer: the sample index per lattice point (-1 unset).
struct AdaptiveLattice {
  std::vector<std::int32_t> sample;
};

// Every level's new lattice points traced as one batch.
void render_adaptive(const TileTarget& target, const PixelTile& tile, SampleBatch& batch, AdaptiveLattice& lattice);

}  // namespace quiver
