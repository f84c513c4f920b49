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
//                        each pixel the average of its four.
#pragma once

#include <string>
#include <string_view>

namespace quiver {

struct AntiAliasing {
  enum class Mode { none, grid, jitter, adaptive, corners };
  Mode mode = Mode::none;
  int n = 1;               // grid, jitter: rays per side
  float threshold = 0.1f;  // adaptive
  int depth = 2;           // adaptive: levels of subdivision

  static constexpr int kMaxRaysPerSide = 64;
  static constexpr int kMaxDepth = 6;
};

// Throws std::invalid_argument naming what was expected.
AntiAliasing parse_anti_aliasing(std::string_view text);
std::string to_string(const AntiAliasing& aa);

}  // namespace quiver
