#include "app/render_job.h"

#include <chrono>
#include <exception>
#include <new>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/scene_build.h"
#include "app/stage_status.h"
#include "app/stats_json.h"
#include "io/image_output.h"
#include "io/scene_loader.h"
#include "scene/auto_view.h"
#include "scene/default_scene.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

std::pair<int, std::string> describe_current_exception() {
  try {
    throw;
  } catch (const UsageError& error) {
    return {kExitUsage, error.what()};
  } catch (const std::bad_alloc&) {
    return {kExitFailure, "out of memory"};
  } catch (const std::exception& error) {
    return {kExitFailure, error.what()};
  }
}

fs::path default_output(const std::string& scene) {
  if (scene.empty()) return "quiver.png";
  return fs::path(scene).stem().string() + ".png";
}

CheckedRenderArgs check_render_args(const RenderArgs& args, const char* simd_environment,
                                    const std::vector<RoleFile>& extra_outputs) {
  CheckedRenderArgs checked;
  checked.output = args.output.empty() ? default_output(args.scene) : fs::path(args.output);
  checked.outputs.push_back({"--output", checked.output});
  if (!args.stats.empty()) checked.outputs.push_back({"--stats", args.stats});
  checked.outputs.insert(checked.outputs.end(), extra_outputs.begin(), extra_outputs.end());
  check_render_options(args.options);
  check_outputs_are_regular_files(checked.outputs);
  checked.isa = choose_isa(args.options.simd, simd_environment);
  const bool has_aovs = args.options.aov && args.options.aov->any();
  check_output_path(checked.output, has_aovs);
  if (!args.stats.empty()) check_stats_path(args.stats);
  std::vector<RoleFile> scene_file;
  if (!args.scene.empty()) scene_file.push_back({"the scene file", args.scene});
  check_outputs_spare_inputs(checked.outputs, scene_file);
  return checked;
}

namespace {

// How the steps name the scene.
std::string scene_name(const std::string& scene) { return scene.empty() ? "the built-in scene" : scene; }

}  // namespace

SceneDesc load_scene_timed(const std::string& scene, const SceneLoadOptions& options, double& load_ms,
                           ProgressStyle status) {
  StageStatus shown(stderr, status);
  shown.begin("reading " + scene_name(scene));
  const Clock::time_point start = Clock::now();
  SceneDesc desc = scene.empty() ? default_scene() : load_scene(scene, options);
  load_ms = ms_since(start);
  return desc;
}

void print_scene_warnings(const SceneDesc& desc) {
  for (const std::string& warning : desc.warnings) std::fprintf(stderr, "quiver: %s\n", warning.c_str());
}

Scene build_scene_timed(SceneDesc& desc, const SceneBuildOptions& options, const std::string& scene,
                        double& build_ms, ProgressStyle status) {
  StageStatus shown(stderr, status);
  shown.begin("building " + scene_name(scene));
  const Clock::time_point start = Clock::now();
  Scene built = build_named_scene_releasing_triangles(desc, options, scene);
  build_ms = ms_since(start);
  return built;
}

PreparedRender prepare_render(const RenderArgs& args, const CheckedRenderArgs& checked, ProgressStyle status) {
  PreparedRender p;
  p.desc = load_scene_timed(
      args.scene, {args.options.crease_angle, args.options.strict, args.options.allow_outside_paths}, p.load_ms,
      status);
  p.inputs = files_read(p.desc, !args.scene.empty());
  check_outputs_spare_inputs(checked.outputs, p.inputs);
  p.plan = plan_render(args.options, p.desc, checked.isa);
  p.plan.settings.trace.time_phases = !args.stats.empty();  // reported only there
  set_view(p.desc, args.options.camera, p.plan.settings.width, p.plan.settings.height);
  p.scene = build_scene_timed(p.desc, p.plan.build, args.scene, p.build_ms, status);
  return p;
}

nlohmann::json render_stats(const RenderArgs& args, const CheckedRenderArgs& checked, const PreparedRender& prepared,
                            const RenderResult& result) {
  RenderStatsContext context;
  context.version = QUIVER_VERSION;
  context.scene = args.scene.empty() ? "built-in" : args.scene;
  context.output = checked.output.string();
  context.load_ms = prepared.load_ms;
  context.build_ms = prepared.build_ms;
  context.scene_memory_bytes = prepared.scene.memory_bytes();
  context.acceleration_memory_bytes = prepared.scene.acceleration_bytes();
  return render_stats_json(result, prepared.plan.settings, context);
}

void print_render_summary(std::FILE* out, const RenderResult& result, const RenderSettings& settings, double load_ms,
                          double build_ms, const fs::path& output, std::string_view threads) {
  const double seconds = result.render_ms / 1000.0;
  const double mrays = seconds > 0.0 ? double(result.stats.rays.total()) / seconds / 1e6 : 0.0;
  std::fprintf(out,
               "rendered %dx%d (aa %s, %s x%d lanes, %s) in %.3f s: %llu rays, %.2f Mrays/s "
               "(load %.1f ms, build %.1f ms) -> %s\n",
               settings.width, settings.height, to_string(settings.aa).c_str(),
               std::string(isa_name(settings.isa)).c_str(), lane_width(settings.isa), std::string(threads).c_str(),
               seconds, static_cast<unsigned long long>(result.stats.rays.total()), mrays, load_ms, build_ms,
               output.string().c_str());
}

}  // namespace quiver
