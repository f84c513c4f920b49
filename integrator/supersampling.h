// none, grid:N, jitter:N: N x N samples per pixel (one for none), at the
// centres of a uniform sub-grid (grid) or one uniformly placed in each cell
// (jitter, stratified: its offsets hashed from the seed, the pixel and the
// cell), averaged with equal weights.
#pragma once

#include <vector>

#include "integrator/tile_sampling.h"

namespace quiver {

class Supersampler {
 public:
  // aa: none, grid or jitter.
  explicit Supersampler(const AntiAliasing& aa);
  void render(const TileTarget& target, const PixelTile& tile, SampleBatch& batch) const;

 private:
  // A sub-pixel cell (column i, row j) of N x N and its centre.
  struct Cell {
    int i, j;
    double cx, cy;
  };
  bool jitter_;
  int cells_per_side_;       // grid, jitter: N; none: 1
  std::vector<Cell> cells_;  // a pixel's N x N cells
};

}  // namespace quiver
