// Anti-aliasing: RMSE of each mode's image against a high-sample reference
// (jitter:16, 256 stratified rays per pixel, another seed, with the same
// texture filter), against render time, with textures point-sampled and, in
// scenes with textures, box-filtered (--texture-filter box), on the built-in scene and io/examples/adaptive_aa.toml (thin wires
// and a fine checkerboard) at its own 640x360 (the built-in scene at a
// quarter of its 640x480, to keep the run short), and from the shared data
// ($QUIVER_SHARED_DIR, else ../shared; each skipped with a note when absent)
// SPD balls-s2 and gears-s1 and the spot mesh with its texture at 320x240. RMSE is over linear RGB clamped to [0, 1] (what
// an 8-bit output shows), every pixel and channel. One thread, the widest
// ISA, so the times compare within the run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <utility>

#include "bench/accuracy/studies.h"
#include "scene/default_scene.h"
#include "integrator/render.h"
#include "io/scene_loader.h"
#include "io/texture_image.h"
#include "scene/auto_view.h"

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

std::filesystem::path shared_dir() {
  if (const char* env = std::getenv("QUIVER_SHARED_DIR")) return env;
  return QUIVER_SHARED_DIR;
}

// A scene of the shared data, or nothing (with a note) when its files are absent.
std::optional<SceneDesc> shared_scene(const std::filesystem::path& file, const std::filesystem::path& texture = {}) {
  for (const std::filesystem::path& needed : {file, texture}) {
    if (!needed.empty() && !std::filesystem::exists(needed)) {
      std::fprintf(stderr, "anti-aliasing study: skipping %s: %s not found (set QUIVER_SHARED_DIR)\n",
                   file.filename().c_str(), needed.c_str());
      return std::nullopt;
    }
  }
  SceneDesc desc = load_scene(file);
  add_default_view(desc, 320, 240);  // a mesh brings no camera or light
  if (!texture.empty()) {  // every material of the mesh takes the image
    TextureDesc image;
    image.kind = TextureDesc::Kind::image;
    image.path = texture.string();
    desc.textures.push_back(image);
    for (MaterialDesc& m : desc.materials) m.texture = desc.textures.size() - 1;
    read_texture_images(desc);
  }
  return desc;
}

}  // namespace

void anti_aliasing_study(const StudyOptions& options) {
  const double shrink = options.quick ? 0.25 : 1.0;
  std::vector<SceneCase> scenes;
  scenes.push_back({"default_scene", default_scene(), int(160 * shrink), int(120 * shrink)});
  scenes.push_back({"adaptive_aa", load_scene(std::filesystem::path(QUIVER_SOURCE_DIR) / "io/examples/adaptive_aa.toml"),
                    int(640 * shrink), int(360 * shrink)});
  const std::filesystem::path shared = shared_dir();
  const std::pair<const char*, std::optional<SceneDesc>> extra[] = {
      {"balls-s2", shared_scene(shared / "scenes/spd/balls-s2.nff")},
      {"gears-s1", shared_scene(shared / "scenes/spd/gears-s1.nff")},
      {"spot", shared_scene(shared / "meshes/spot.obj", shared / "meshes/spot_texture.png")}};
  for (const auto& [name, desc] : extra) {
    if (desc) scenes.push_back({name, *desc, int(320 * shrink), int(240 * shrink)});
  }
  const std::vector<std::string> default_modes = {"none",          "grid:2",         "grid:3",          "grid:4",
                         "jitter:2",      "jitter:3",       "jitter:4",        "adaptive:0.3:3",
                         "adaptive:0.1:3", "adaptive:0.03:3", "adaptive:0.01:3", "corners",
                         "refine:0.1:4",   "refine:0.05:4",   "refine:0.03:4",   "refine:0.02:4",
                         "refine:0.08:8",  "refine:0.04:8",   "refine:0.02:8",   "refine:0.01:8"};
  const std::vector<std::string>& modes = options.aa_modes.empty() ? default_modes : options.aa_modes;
  std::FILE* f = open_csv(options.out / "anti_aliasing.csv",
                          "scene,width,height,mode,texture_filter,render_ms,camera_rays,rmse,reference_mode,reference_ms");
  for (const SceneCase& sc : scenes) {
    const Scene scene = build_scene(sc.desc, SceneBuildOptions{});
    for (const bool filter : {false, true}) {
      if (filter && sc.desc.textures.empty()) continue;  // the same image
      const char* filter_name = filter ? "box" : "none";
      RenderSettings settings;
      settings.width = sc.width;
      settings.height = sc.height;
      settings.threads = 1;
      settings.isa = best_supported_isa();
      settings.trace.filter_textures = filter;
      settings.trace.seed = 12345;
      settings.aa = parse_anti_aliasing("jitter:16");
      const RenderResult reference = render(scene, settings);
      settings.trace.seed = 0;
      for (const std::string& mode_text : modes) {
        const char* mode = mode_text.c_str();
        settings.aa = parse_anti_aliasing(mode);
        const RenderResult r = render(scene, settings);
        const double error = rmse(r.image, reference.image);
        std::fprintf(f, "%s,%d,%d,%s,%s,%.3f,%llu,%.9g,jitter:16,%.3f\n", sc.name, sc.width, sc.height, mode,
                     filter_name, r.render_ms, static_cast<unsigned long long>(r.stats.rays.primary), error,
                     reference.render_ms);
        std::printf("%-14s %-16s %-4s %8.1f ms  RMSE %.5f\n", sc.name, mode, filter_name, r.render_ms, error);
        std::fflush(f);
      }
    }
  }
  std::fclose(f);
}

}  // namespace quiver::accuracy
