#include "app/render_options.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <system_error>
#include <tuple>

#include "geometry/vertex_normals.h"
#include "scene/auto_view.h"
#include "scene/camera_frame.h"

namespace quiver {

namespace {

std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

// A flag's number as the user would write it (200, not 200.000000).
std::string format_flag_number(double value) {
  std::ostringstream shown;
  shown << value;
  return shown.str();
}

void check_side(int side, const char* flag) {
  if (side < 1 || side > kMaxImageSide) {
    throw UsageError(std::string(flag) + ": expected an integer in [1, " + std::to_string(kMaxImageSide) +
                     "], found " + std::to_string(side));
  }
}

void check_size(int width, int height) {
  check_side(width, "--width");
  check_side(height, "--height");
  if (std::int64_t(width) * std::int64_t(height) > kMaxImagePixels) {
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": expected at most 2^28 (268435456) pixels");
  }
}


// The other side for one given side, keeping aspect = other / given.
int scaled_side(int given, double aspect) {
  const double other = std::round(double(given) * aspect);
  if (other < 1.0) return 1;
  if (other > double(kMaxImageSide) + 1.0) return kMaxImageSide + 1;  // reported by check_size
  return int(other);
}

}  // namespace

AntiAliasing parse_aa_flag(std::string_view text) {
  try {
    return parse_anti_aliasing(text);
  } catch (const std::invalid_argument& error) {
    throw UsageError(std::string("--aa: ") + error.what());
  }
}

std::uint64_t parse_seed(std::string_view text) {
  std::uint64_t seed = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    throw UsageError("--seed: expected an integer in [0, 18446744073709551615], found " + quoted(text));
  }
  return seed;
}

void check_preset(std::string_view name) {
  if (name != "spd") throw UsageError("--preset: expected spd, found '" + std::string(name) + "'");
}

AovSelection parse_aov_list(std::string_view list) {
  AovSelection aovs;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string_view item = list.substr(start, comma == std::string_view::npos ? comma : comma - start);
    bool* slot = item == "depth" ? &aovs.depth : item == "normal" ? &aovs.normal : item == "id" ? &aovs.id : nullptr;
    if (!slot) {
      throw UsageError("--aov: expected a comma-separated list of depth, normal and id, found " + quoted(item));
    }
    if (*slot) throw UsageError("--aov: " + quoted(item) + " is listed twice");
    *slot = true;
    if (comma == std::string_view::npos) return aovs;
    start = comma + 1;
  }
}

Isa choose_isa(const std::optional<std::string>& flag, const char* environment_value) {
  const std::string_view requested = flag ? std::string_view(*flag)
                                          : environment_value ? std::string_view(environment_value)
                                                              : std::string_view("auto");
  try {
    return resolve_isa(requested);
  } catch (const std::runtime_error& error) {
    throw UsageError(std::string(flag ? "--simd: " : "QUIVER_SIMD: ") + error.what());
  }
}

bool parse_texture_filter(std::string_view name) {
  if (name == "box") return true;
  if (name == "none") return false;
  throw UsageError("--texture-filter: expected box or none, found '" + std::string(name) + "'");
}

void check_render_options(const RenderOptions& options) {
  if (options.width) check_side(*options.width, "--width");
  if (options.height) check_side(*options.height, "--height");
  if (options.width && options.height) check_size(*options.width, *options.height);
  if (options.max_depth && !valid_max_depth(*options.max_depth)) {
    throw UsageError("--max-depth: expected an integer in [0, " + std::to_string(kMaxMaxDepth) + "], found " +
                     std::to_string(*options.max_depth));
  }
  if (options.min_weight && !valid_min_weight(*options.min_weight)) {
    throw UsageError("--min-weight: expected a number from 0 to 1, found " + format_flag_number(*options.min_weight));
  }
  if (options.threads < 0 || options.threads > kMaxThreads) {
    throw UsageError("--threads: expected an integer in [0, " + std::to_string(kMaxThreads) + "], found " +
                     std::to_string(options.threads));
  }
  check_crease_angle(options.crease_angle);
  check_camera_flags(options.camera);
  if (!options.preset_spd) return;
  if (options.aa && options.aa->mode != AntiAliasing::Mode::corners) {
    throw UsageError("--preset spd samples pixel corners (--aa corners); it contradicts --aa " + to_string(*options.aa));
  }
  if (options.max_depth && *options.max_depth != kSpdMaxDepth) {
    throw UsageError("--preset spd sets --max-depth " + std::to_string(kSpdMaxDepth) + "; it contradicts --max-depth " +
                     std::to_string(*options.max_depth));
  }
  if (options.min_weight && *options.min_weight != 0.0) {
    throw UsageError("--preset spd sets --min-weight 0; it contradicts --min-weight " +
                     std::to_string(*options.min_weight));
  }
}

void check_crease_angle(const std::optional<double>& degrees) {
  if (degrees && !valid_crease_angle(*degrees)) {
    throw UsageError("--crease-angle: expected degrees in [0, 180], found " + format_flag_number(*degrees));
  }
}

Vec3<float> parse_vector_flag(std::string_view flag, std::string_view text) {
  float xyz[3];
  std::size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t comma = k < 2 ? text.find(',', start) : text.size();
    const std::string_view part = comma == std::string_view::npos ? std::string_view{} : text.substr(start, comma - start);
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), xyz[k]);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size() || !std::isfinite(xyz[k])) {
      throw UsageError(std::string(flag) + ": expected three finite numbers x,y,z, found " + quoted(text));
    }
    start = comma + 1;
  }
  return {xyz[0], xyz[1], xyz[2]};
}

void check_camera_flags(const CameraFlags& flags) {
  if (flags.fov && !(*flags.fov > 0.0 && *flags.fov < 180.0)) {
    throw UsageError("--fov: expected degrees in (0, 180), found " + format_flag_number(*flags.fov));
  }
}

void apply_camera_flags(const CameraFlags& flags, CameraDesc& camera) {
  if (flags.look_from) camera.from = *flags.look_from;
  if (flags.look_at) camera.at = *flags.look_at;
  if (flags.up) camera.up = *flags.up;
  if (flags.fov) camera.angle_degrees = static_cast<float>(*flags.fov);
  try {
    camera_frame(camera);
  } catch (const std::invalid_argument& error) {
    throw UsageError(std::string("--look-from, --look-at, --up: ") + error.what());
  }
}

std::optional<DefaultView> set_view(SceneDesc& desc, const CameraFlags& flags, int width, int height) {
  std::optional<DefaultView> view;
  if (!desc.camera) {
    std::optional<Vec3<double>> up;
    if (flags.up) {
      up = Vec3<double>{double(flags.up->x), double(flags.up->y), double(flags.up->z)};
      if (!(dot(*up, *up) > 0.0)) throw UsageError("--up: expected a direction, found 0,0,0");
    }
    const float angle = flags.fov ? static_cast<float>(*flags.fov) : kDefaultViewAngleDegrees;
    view = add_default_camera(desc, width, height, up, angle);
  }
  apply_camera_flags(flags, *desc.camera);
  add_default_lights(desc);
  return view;
}

std::pair<int, int> image_size(const RenderOptions& options, const std::optional<CameraDesc>& camera) {
  const int camera_width = camera ? camera->width : kDefaultImageSide;
  const int camera_height = camera ? camera->height : kDefaultImageSide;
  int width = camera_width, height = camera_height;
  if (options.width && options.height) {
    width = *options.width;
    height = *options.height;
  } else if (options.width) {
    width = *options.width;
    height = scaled_side(width, double(camera_height) / double(camera_width));
  } else if (options.height) {
    height = *options.height;
    width = scaled_side(height, double(camera_width) / double(camera_height));
  }
  check_size(width, height);
  return {width, height};
}

RenderPlan plan_render(const RenderOptions& options, const SceneDesc& scene, Isa isa) {
  check_render_options(options);
  RenderPlan plan;
  RenderSettings& s = plan.settings;
  std::tie(s.width, s.height) = image_size(options, scene.camera);

  if (options.preset_spd) {
    s.aa.mode = AntiAliasing::Mode::corners;
  } else if (options.aa) {
    s.aa = *options.aa;
  } else if (scene.render.aa) {
    s.aa = *scene.render.aa;
  } else {
    s.aa = parse_anti_aliasing(kDefaultAntiAliasing);
  }

  if (options.preset_spd) {
    s.trace.max_depth = kSpdMaxDepth;
  } else if (options.max_depth) {
    s.trace.max_depth = *options.max_depth;
  } else if (scene.render.max_depth) {
    if (!valid_max_depth(*scene.render.max_depth)) {
      throw std::runtime_error("the scene's render settings: max depth " + std::to_string(*scene.render.max_depth) +
                               " is outside [0, " + std::to_string(kMaxMaxDepth) + "]");
    }
    s.trace.max_depth = *scene.render.max_depth;
  } else {
    s.trace.max_depth = kDefaultMaxDepth;
  }

  if (options.preset_spd) {
    s.trace.min_weight = 0.f;
    s.trace.spawn_every_ray = true;
  } else if (options.min_weight) {
    s.trace.min_weight = float(*options.min_weight);
  } else if (scene.render.min_weight) {
    const float weight = *scene.render.min_weight;
    if (!valid_min_weight(weight)) {
      throw std::runtime_error("the scene's render settings: min weight " + format_flag_number(weight) +
                               " is not a number from 0 to 1");
    }
    s.trace.min_weight = weight;
  } else {
    s.trace.min_weight = kDefaultMinWeight;
  }

  s.trace.seed = options.seed;
  if (options.filter_textures) s.trace.filter_textures = *options.filter_textures;
  s.threads = options.threads;
  s.isa = isa;
  if (options.aov) {
    s.aov_depth = options.aov->depth;
    s.aov_normal = options.aov->normal;
    s.aov_id = options.aov->id;
  }
  plan.build.all_two_sided = options.preset_spd || options.two_sided;
  s.methods = options.robust_methods ? MethodChoice::most_robust : MethodChoice::per_scene;
  return plan;
}

}  // namespace quiver
