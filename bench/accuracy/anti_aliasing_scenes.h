// The scenes and settings of the anti-aliasing studies (anti_aliasing.csv,
// aa_oracle.csv): the built-in scene at 160x120 (a quarter of its size),
// io/examples/adaptive_aa.toml (thin wires, a fine checkerboard) at its own
// 640x360, io/examples/mirror_checker.toml (a checkered floor to the horizon
// in a mirror sphere, thin rods, hard shadows) at its own 400x300, and from the shared data ($QUIVER_SHARED_DIR, else ../shared;
// each skipped with a note when absent) SPD balls-s2 and gears-s1 and the
// spot mesh with its texture at 320x240; --quick shrinks each side 4x.
// Images compare by RMSE over linear RGB clamped to [0, 1] (what an 8-bit
// output shows), every pixel and channel.
#pragma once

#include <string>
#include <vector>

#include "bench/accuracy/studies.h"
#include "integrator/render.h"
#include "scene/scene_desc.h"

namespace quiver::accuracy {

struct SceneCase {
  std::string name;
  SceneDesc desc;
  int width, height;
};

std::vector<SceneCase> anti_aliasing_scenes(const StudyOptions& options);

// One thread, the widest ISA, the case's size, the texture filter on or off.
RenderSettings anti_aliasing_settings(const SceneCase& scene, bool filter_textures);

// A pixel's squared error summed over its channels, both clamped to [0, 1].
double pixel_squared_error(const Framebuffer& a, const Framebuffer& b, std::size_t pixel);

double rmse(const Framebuffer& a, const Framebuffer& b);

}  // namespace quiver::accuracy
