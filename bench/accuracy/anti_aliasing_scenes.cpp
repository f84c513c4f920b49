#include "bench/accuracy/anti_aliasing_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <utility>

#include "scene/auto_view.h"
#include "scene/default_scene.h"
#include "io/scene_loader.h"
#include "io/texture_image.h"

namespace quiver::accuracy {
namespace {

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

double clamped(float v) { return std::clamp(double(v), 0.0, 1.0); }

}  // namespace

std::vector<SceneCase> anti_aliasing_scenes(const StudyOptions& options) {
  const double shrink = options.quick ? 0.25 : 1.0;
  std::vector<SceneCase> scenes;
  scenes.push_back({"default_scene", default_scene(), int(160 * shrink), int(120 * shrink)});
  scenes.push_back({"adaptive_aa", load_scene(std::filesystem::path(QUIVER_SOURCE_DIR) / "io/examples/adaptive_aa.toml"),
                    int(640 * shrink), int(360 * shrink)});
  scenes.push_back({"mirror_checker",
                    load_scene(std::filesystem::path(QUIVER_SOURCE_DIR) / "io/examples/mirror_checker.toml"),
                    int(400 * shrink), int(300 * shrink)});
  const std::filesystem::path shared = shared_dir();
  const std::pair<const char*, std::optional<SceneDesc>> extra[] = {
      {"balls-s2", shared_scene(shared / "scenes/spd/balls-s2.nff")},
      {"gears-s1", shared_scene(shared / "scenes/spd/gears-s1.nff")},
      {"spot", shared_scene(shared / "meshes/spot.obj", shared / "meshes/spot_texture.png")}};
  for (const auto& [name, desc] : extra) {
    if (desc) scenes.push_back({name, *desc, int(320 * shrink), int(240 * shrink)});
  }
  return scenes;
}

RenderSettings anti_aliasing_settings(const SceneCase& scene, bool filter_textures) {
  RenderSettings settings;
  settings.width = scene.width;
  settings.height = scene.height;
  settings.threads = 1;
  settings.isa = best_supported_isa();
  settings.trace.filter_textures = filter_textures;
  return settings;
}

double pixel_squared_error(const Framebuffer& a, const Framebuffer& b, std::size_t pixel) {
  double sum = 0.0;
  for (std::size_t c = 3 * pixel; c < 3 * pixel + 3; ++c) {
    const double d = clamped(a.rgb[c]) - clamped(b.rgb[c]);
    sum += d * d;
  }
  return sum;
}

double rmse(const Framebuffer& a, const Framebuffer& b) {
  double sum = 0.0;
  const std::size_t pixels = a.rgb.size() / 3;
  for (std::size_t p = 0; p < pixels; ++p) sum += pixel_squared_error(a, b, p);
  return std::sqrt(sum / double(a.rgb.size()));
}

}  // namespace quiver::accuracy
