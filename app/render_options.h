// The `quiver render` options as the command line gave them, and how they
// become RenderSettings and SceneBuildOptions together with the scene's own
// camera and RenderDesc. A flag that was not given is an empty optional, so
// the scene's value (or the default below) applies. No CLI11 here: the
// command-line parser fills RenderOptions, everything else is testable alone.
// Problems with a flag throw UsageError (the CLI exits 2); problems with a
// value the scene file carries throw std::runtime_error (the CLI exits 1).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "integrator/render.h"
#include "scene/auto_view.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"
#include "simd/isa.h"

namespace quiver {

// A bad flag or flag value (exit code 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Image size bounds: kMaxImageSide, kMaxImagePixels; kDefaultImageSide; the
// render settings' bounds and defaults: kMaxMaxDepth, valid_min_weight, ...
// (all in scene/scene_desc.h). The defaults of the rest:
inline constexpr int kMaxThreads = 1024;
// --preset spd: corner sampling, 4 bounces (5 levels with the eye ray), no
// weight cut-off, every surface two-sided.
inline constexpr int kSpdMaxDepth = 4;

// --look-from, --look-at, --up, --fov (render and trace): each field over
// the scene's camera (or the default view's), parsed ("x,y,z":
// parse_vector_flag) where they are given; the field of view in degrees.
struct CameraFlags {
  std::optional<Vec3<float>> look_from, look_at, up;
  std::optional<double> fov;
};

struct AovSelection {
  bool depth = false, normal = false, id = false;
  bool any() const { return depth || normal || id; }
};

// Typed values, parsed once where they are given (the command line, the
// Python module); check_render_options checks their ranges and agreement.
struct RenderOptions {
  std::optional<int> width, height;
  std::optional<AntiAliasing> aa;
  std::optional<int> max_depth;
  std::optional<double> min_weight;
  int threads = 0;                  // 0: every core
  std::optional<std::string> simd;  // absent: QUIVER_SIMD, else auto
  std::uint64_t seed = 0;
  std::optional<AovSelection> aov;  // --aov: parse_aov_list
  bool preset_spd = false;
  bool two_sided = false;
  bool robust_methods = false;      // the robust sphere test even where the scene allows the cheaper one
  std::optional<bool> filter_textures;  // --texture-filter: parse_texture_filter
  std::optional<double> crease_angle;  // degrees, every OBJ mesh's (SceneLoadOptions)
  bool strict = false;                 // SceneLoadOptions::strict
  bool allow_outside_paths = false;    // SceneLoadOptions::allow_outside_paths
  CameraFlags camera;
};

// --texture-filter: "box" (true) or "none" (false); throws UsageError.
bool parse_texture_filter(std::string_view name);

// A decimal unsigned 64-bit integer (no sign, no spaces); throws UsageError.
std::uint64_t parse_seed(std::string_view text);

// --preset NAME: spd is the one preset; anything else throws UsageError.
void check_preset(std::string_view name);

// "depth,normal,id" in any order, each at most once, no empty items.
AovSelection parse_aov_list(std::string_view list);

// The ISA: the flag if given, else the environment value (QUIVER_SIMD; null
// when unset), else auto. Unknown or unsupported choices throw UsageError.
Isa choose_isa(const std::optional<std::string>& flag, const char* environment_value);

// --aa: parse_anti_aliasing's modes; throws UsageError naming the flag.
AntiAliasing parse_aa_flag(std::string_view text);

// Checks every flag's range and the flags against --preset spd, before any
// scene is read.
void check_render_options(const RenderOptions& options);

// --crease-angle (of render, info and trace): degrees in [0, 180].
void check_crease_angle(const std::optional<double>& degrees);

// "x,y,z": three finite numbers; throws UsageError naming the flag.
Vec3<float> parse_vector_flag(std::string_view flag, std::string_view text);

// The field of view in (0, 180); throws UsageError.
void check_camera_flags(const CameraFlags& flags);

// The camera flags over the camera; throws UsageError when the result has
// no view direction (from = at, or up along it).
void apply_camera_flags(const CameraFlags& flags, CameraDesc& camera);

// The view a command renders or traces desc with: the default camera of
// width x height (scene/auto_view.h) when desc has no camera, around --up as
// the model's up axis and framed for --fov when given, then the camera flags
// over its camera (apply_camera_flags), then the default lights around that
// final camera when desc has none. Returns the default view when one was
// chosen.
std::optional<DefaultView> set_view(SceneDesc& desc, const CameraFlags& flags, int width, int height);

// The image size: both flags as given; one flag and the other side from the
// camera's aspect (rounded, at least 1); neither: the camera's resolution,
// or kDefaultImageSide square without a camera.
std::pair<int, int> image_size(const RenderOptions& options, const std::optional<CameraDesc>& camera);

struct RenderPlan {
  RenderSettings settings;
  SceneBuildOptions build;
};

// The settings for this scene: flags first, then the scene's RenderDesc,
// then the defaults; --preset spd replaces the scene's values. The scene
// may lack a camera (the caller adds a view of plan.settings' size).
RenderPlan plan_render(const RenderOptions& options, const SceneDesc& scene, Isa isa);

}  // namespace quiver
