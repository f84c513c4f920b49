// Anti-aliasing: RMSE of each mode's image against a high-sample reference
// (jitter:16, 256 stratified rays per pixel, another seed), against render
// time, on the built-in scene and io/examples/adaptive_aa.toml (thin wires
// and a fine checkerboard) at its own 640x360 (the built-in scene at a
// quarter of its 640x480, to keep the run short). RMSE is over linear RGB clamped to [0, 1] (what
// an 8-bit output shows), every pixel and channel. One thread, the widest
// ISA, so the times compare within the run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bench/accuracy/studies.h"
#include "scene/default_scene.h"
#include "integrator/render.h"
#include "io/scene_loader.h"

namespace quiver::accuracy {
namespace {

double rmse(const Framebuffer& a, const Framebuffer& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    const double d = std::clamp(double(a.rgb[i]), 0.0, 1.0) - std::clamp(double(b.rgb[i]), 0.0, 1.0);
    sum += d * d;
  }
  return std::sqrt(sum / double(a.rgb.size()));
}

struct SceneCase {
  const char* name;
  SceneDesc desc;
  int width, height;
};

}  // namespace

void anti_aliasing_study(const StudyOptions& options) {
  const double shrink = options.quick ? 0.25 : 1.0;
  std::vector<SceneCase> scenes;
  scenes.push_back({"default_scene", default_scene(), int(160 * shrink), int(120 * shrink)});
  scenes.push_back({"adaptive_aa", load_scene(std::filesystem::path(QUIVER_SOURCE_DIR) / "io/examples/adaptive_aa.toml"),
                    int(640 * shrink), int(360 * shrink)});
  const char* modes[] = {"none",          "grid:2",         "grid:3",          "grid:4",
                         "jitter:2",      "jitter:3",       "jitter:4",        "adaptive:0.3:3",
                         "adaptive:0.1:3", "adaptive:0.03:3", "adaptive:0.01:3", "corners",
                         "refine:0.1:4",   "refine:0.05:4",   "refine:0.03:4",   "refine:0.02:4",
                         "refine:0.08:8",  "refine:0.04:8",   "refine:0.02:8",   "refine:0.01:8"};
  std::FILE* f = open_csv(options.out / "anti_aliasing.csv",
                          "scene,width,height,mode,render_ms,camera_rays,rmse,reference_mode,reference_ms");
  for (const SceneCase& sc : scenes) {
    const Scene scene = build_scene(sc.desc, SceneBuildOptions{});
    RenderSettings settings;
    settings.width = sc.width;
    settings.height = sc.height;
    settings.threads = 1;
    settings.isa = best_supported_isa();
    settings.trace.seed = 12345;
    settings.aa = parse_anti_aliasing("jitter:16");
    const RenderResult reference = render(scene, settings);
    settings.trace.seed = 0;
    for (const char* mode : modes) {
      settings.aa = parse_anti_aliasing(mode);
      const RenderResult r = render(scene, settings);
      std::fprintf(f, "%s,%d,%d,%s,%.3f,%llu,%.9g,jitter:16,%.3f\n", sc.name, sc.width, sc.height, mode, r.render_ms,
                   static_cast<unsigned long long>(r.stats.rays.primary), rmse(r.image, reference.image), reference.render_ms);
      std::printf("%-14s %-16s %8.1f ms  RMSE %.5f\n", sc.name, mode, r.render_ms, rmse(r.image, reference.image));
      std::fflush(f);
    }
  }
  std::fclose(f);
}

}  // namespace quiver::accuracy
