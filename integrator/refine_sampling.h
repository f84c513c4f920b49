// refine:T:N (anti_aliasing.h): 2 x 2 stratified jittered rays per pixel; a
// pixel whose mean's standard error exceeds T, or, after the first pass,
// whose mean differs from a neighbour's by more than 4 T, or whose samples
// (or its and a neighbour's) met different surfaces, doubles its strata per
// side, up to N x N. A stratum (i, j) at side s of pixel p has its sample
// at ((i + u) / s, (j + v) / s), u and v hashed from the seed, p and the
// stratum's number (strata of smaller sides first), so a pixel's rays
// depend on it alone, not on the tile or the thread; with grid strata u and
// v are 1/2, and a refined pixel's coarser rays are dropped.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "integrator/tile_sampling.h"
#include "scene/anti_aliasing.h"

namespace quiver {

// A pixel's running sums (its samples, and their channels clamped to [0, 1]
// for the error estimate) and its strata per side.
struct RefinedPixel {
  Vec3<float> sum{0.f, 0.f, 0.f};
  Vec3<double> clamped_sum{0.0, 0.0, 0.0}, clamped_squares{0.0, 0.0, 0.0};
  int count = 0;
  int side = 0;
  std::uint32_t first = 0;  // its strata's start in RefineBuffers::strata
  // What its first-pass samples met: one material (-1: nothing), or mixed;
  // the nearest and farthest distance (a miss: infinity).
  std::int32_t material = -1;
  bool mixed_materials = false;
  float nearest = std::numeric_limits<float>::infinity(), farthest = 0.f;
};

// One stratum of a pixel at the pixel's side, and its sample's offset in the pixel.
struct StratumSample {
  int i, j;
  double x, y;
};

// Stratum (i, j) at `side` of pixel number `pixel` and its sample (the
// strata rule above; grid strata: the centre).
StratumSample refine_stratum(std::uint64_t seed, std::uint64_t pixel, int side, int i, int j,
                             AntiAliasing::Strata strata);

// The stratum at side `child` (twice st's side) that holds st's sample, as
// {i, j}: one of st's four, whatever the sample's rounding.
std::array<int, 2> sub_stratum_holding(const StratumSample& st, int child);

// The pixel's mean's standard error exceeds `threshold` in some clamped
// channel (its count at least 2).
bool too_uncertain(const RefinedPixel& px, float threshold);

// A worker's buffers, reused tile after tile.
struct RefineBuffers {
  std::vector<RefinedPixel> pixels;                // per pixel of the tile and its apron
  std::vector<StratumSample> strata, next_strata;  // per pixel, side^2 strata at a time
  std::vector<std::uint32_t> owner;                // the pixel of each traced sample
  std::vector<std::uint8_t> uncertain;             // per pixel, refined in the next pass
  std::vector<FirstSurface> surfaces;             // the first pass's, per traced sample
};

void render_refined(const TileTarget& target, const PixelTile& tile, SampleBatch& batch, RefineBuffers& buffers);

}  // namespace quiver
