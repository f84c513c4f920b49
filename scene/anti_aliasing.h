// Anti-aliasing modes (the CLI's --aa):
//   none                 one ray through each pixel centre;
//   grid:N               N x N rays at the centres of a uniform sub-grid;
//   jitter:N             N x N stratified rays, one uniformly placed per cell;
//   adaptive:T:D         rays at pixel corners (shared with neighbours); a
//                        square whose corner colours differ by more than T in
//                        some channel is split into four, down to D levels
//                        (Whitted 1980; POV-Ray's method 2); a pixel is the
//                        average of its squares;
//   corners              the SPD rule: (W+1) x (H+1) rays at pixel corners,
//                        each pixel the average of its four;
//   refine:T:N           2 x 2 stratified jittered rays per pixel; a pixel
//                        whose mean's standard error exceeds T in some
//                        channel (clamped to [0, 1]), or, after the first
//                        pass, whose mean differs from a neighbour's by more
//                        than 4 T, or whose first-pass rays, or its and a
//                        neighbour's, met different surfaces (another
//                        material, nothing, or a depth jump of kDepthJump), doubles
//                        its strata per side (each stratum's ray kept, its
//                        three sibling sub-strata sampled), up to N x N (N a
//                        power of two, 2..16); later passes go on where the
//                        error still exceeds T.
//   refine:T:N:STRATA    where a pixel's rays lie in its strata: jitter (the
//                        default: anywhere in each, hashed per stratum) or
//                        grid (at the strata's centres, as grid:N; a refined
//                        pixel is sampled afresh at the finer centres, its
//                        coarser rays dropped, as the finer centres miss them).
#pragma once

#include <string>
#include <string_view>

namespace quiver {

struct AntiAliasing {
  enum class Mode { none, grid, jitter, adaptive, corners, refine };
  enum class Strata { jitter, grid };
  Mode mode = Mode::none;
  Strata strata = Strata::jitter;  // refine
  int n = 1;               // grid, jitter: rays per side; refine: at most
  float threshold = 0.1f;  // adaptive, refine
  int depth = 2;           // adaptive: levels of subdivision

  static constexpr int kMaxRaysPerSide = 64;
  static constexpr int kMaxDepth = 6;
  static constexpr int kMaxRefineSide = 16;
  // refine: a neighbour's mean this many thresholds away refines a pixel.
  static constexpr float kNeighbourContrast = 4.f;
  // refine: first-pass distances this fraction apart are different surfaces.
  static constexpr float kDepthJump = 0.05f;
};

// The programs' default when neither --aa nor the scene names a mode: nine
// rays per pixel at fixed positions, so its cost is bounded on every scene
// and every run renders the same image; among modes of bounded cost it gives
// the least error for its time (RMSE^2 x time).
inline constexpr std::string_view kDefaultAntiAliasing = "grid:3";

// Throws std::invalid_argument naming what was expected.
AntiAliasing parse_anti_aliasing(std::string_view text);
std::string to_string(const AntiAliasing& aa);

}  // namespace quiver
