// The steps of `quiver render` that quiver-mpi shares (app/main.cpp,
// app/mpi_main.cpp): the arguments as parsed, their checks before the scene
// is read, reading and building the scene with its settings, the stats JSON
// and the summary line. No CLI11 here (app/render_flags_cli.h registers
// the flags).
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "app/progress_bar.h"
#include "app/render_options.h"
#include "app/render_outputs.h"
#include "io/scene_loader.h"
#include "integrator/render.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"

namespace quiver {


// Exit codes of quiver and quiver-mpi.
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// What `render` was given, as parsed.
struct RenderArgs {
  std::string scene;   // empty: the built-in scene
  std::string output;  // empty: the default name
  std::string stats;   // empty: no stats file
  bool quiet = false;
  RenderOptions options;
};

// The exception being handled as an exit code and a message: UsageError 2
// (kExitUsage), out of memory and anything else 1.
std::pair<int, std::string> describe_current_exception();

// <scene name>.png, quiver.png for the built-in scene.
std::filesystem::path default_output(const std::string& scene);

// What the flags alone decide, checked before the scene is read.
struct CheckedRenderArgs {
  Isa isa = Isa::scalar;
  std::filesystem::path output;
  std::vector<RoleFile> outputs;  // --output, --stats if given, then extra_outputs
};

// Checks the options, the ISA, the output paths and that no output names
// the scene file or another output; throws UsageError (exit 2) or
// std::runtime_error (an output's directory, exit 2 as well).
CheckedRenderArgs check_render_args(const RenderArgs& args, const char* simd_environment,
                                    const std::vector<RoleFile>& extra_outputs = {});

// The scene as read (desc, with the default view and the camera flags
// applied), its settings, the built scene, the files it read and the times.
struct PreparedRender {
  SceneDesc desc;
  RenderPlan plan;
  Scene scene;
  std::vector<RoleFile> inputs;  // files_read(desc)
  double load_ms = 0.0, build_ms = 0.0;
};

// The scene file (or the built-in scene), read with the load options; throws.
// `status`: how a long read shows on stderr (app/stage_status.h: on a
// terminal, "reading <scene>: 2.4 s" once it lasts a second).
SceneDesc load_scene_timed(const std::string& scene, const SceneLoadOptions& options, double& load_ms,
                           ProgressStyle status = ProgressStyle::off);

// What the readers forgave (SceneDesc::warnings), one "quiver: " line each on stderr.
void print_scene_warnings(const SceneDesc& desc);

// build_scene, timed, its errors (bad material or texture indices) naming the
// scene; desc.triangles is released while building (empty afterwards: a
// command keeps the built scene, not a large mesh's description beside it).
// `status` as for load_scene_timed ("building <scene>").
Scene build_scene_timed(SceneDesc& desc, const SceneBuildOptions& options, const std::string& scene,
                        double& build_ms, ProgressStyle status = ProgressStyle::off);

// Reads and builds the scene for a checked render; throws UsageError when an
// output names a file the scene reads, std::runtime_error for a bad scene.
// `status` as for load_scene_timed, for the read and the build.
PreparedRender prepare_render(const RenderArgs& args, const CheckedRenderArgs& checked,
                              ProgressStyle status = ProgressStyle::off);

// The stats JSON of `quiver render --stats`.
nlohmann::json render_stats(const RenderArgs& args, const CheckedRenderArgs& checked, const PreparedRender& prepared,
                            const RenderResult& result);

// "rendered WxH (aa ..., unit xN lanes, T threads) in S s: R rays, M Mrays/s
// (load L ms, build B ms) -> OUTPUT"; `threads` as the line shows them.
void print_render_summary(std::FILE* out, const RenderResult& result, const RenderSettings& settings, double load_ms,
                          double build_ms, const std::filesystem::path& output, std::string_view threads);

}  // namespace quiver
