// quiver, the command-line program: `quiver render [SCENE]` renders a scene
// file (or the built-in scene) to an image, `quiver info SCENE` reports what
// a scene holds, `quiver trace SCENE` times the primary rays' closest hits
// and prints one JSON line (app/trace_command.h). Exit codes: 0 success,
// 1 failure (unreadable or invalid scene, render or write error), 2 usage
// error (bad flag or value, an output naming an input or another output),
// 130 / 143 interrupted by SIGINT / SIGTERM (app/interrupt.h). Errors go to
// stderr as "quiver: <message>". A render's outputs are staged and renamed
// over their targets together once all were written: on any failure or
// interruption no output file is created or changed.
// The only translation unit that includes CLI11 (it is slow to compile).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/vertex_normals.h"
#include "scene/default_scene.h"
#include "integrator/render.h"
#include "scene/scene.h"
#include "scene/auto_view.h"
#include "io/image_output.h"
#include "io/output_file.h"
#include "io/parse_error.h"
#include "app/interrupt.h"
#include "app/progress_bar.h"
#include "app/render_outputs.h"
#include "app/render_options.h"
#include "app/scene_build.h"
#include "app/scene_info.h"
#include "io/scene_loader.h"
#include "app/stats_json.h"
#include "app/trace_command.h"

namespace {

namespace fs = std::filesystem;
using quiver::RenderOptions;
using quiver::UsageError;
using Clock = std::chrono::steady_clock;

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// A file option given an empty value is a mistake, not a request for the default.
const CLI::Validator kNonEmptyFileName(
    [](std::string& value) { return value.empty() ? std::string("an empty file name") : std::string(); }, "");

// What `quiver render` was given, as parsed.
struct RenderArgs {
  std::string scene;   // empty: the built-in scene
  std::string output;  // empty: the default name
  std::string stats;   // empty: no stats file
  bool quiet = false;
  RenderOptions options;
};

// What `quiver trace` was given, as parsed.
struct TraceArgs {
  std::string scene;
  quiver::TraceOptions options;
};

// The camera flags of render and trace, before we know which were given.
struct RawCameraFlags {
  std::string look_from, look_at, up;
  double fov = 0.0;
  CLI::Option *look_from_option, *look_at_option, *up_option, *fov_option;
};

// The parsed values of `quiver trace`, before we know which were given.
struct RawTraceFlags {
  int width = 0, height = 0;
  double crease_angle = 0.0;
  std::string simd;
  CLI::Option *width_option, *height_option, *simd_option, *crease_angle_option;
  RawCameraFlags camera;
};

// The parsed values, before we know which optional flags were given.
struct RawRenderFlags {
  int width = 0, height = 0, max_depth = 0;
  double min_weight = 0.0, crease_angle = 0.0;
  std::string aa, simd, aov, preset, seed;
  CLI::Option *width_option, *height_option, *max_depth_option, *min_weight_option, *crease_angle_option;
  CLI::Option *aa_option, *simd_option, *aov_option, *preset_option, *seed_option;
  RawCameraFlags camera;
};

int report(std::string_view message, int exit_code) {
  std::cerr << "quiver: " << message << "\n";
  return exit_code;
}

// Reports the exception being handled: a UsageError exits 2, anything else 1.
int report_exception() {
  try {
    throw;
  } catch (const UsageError& error) {
    return report(error.what(), kExitUsage);
  } catch (const std::bad_alloc&) {
    return report("out of memory", kExitFailure);
  } catch (const std::exception& error) {
    return report(error.what(), kExitFailure);
  }
}

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

fs::path default_output(const std::string& scene) {
  if (scene.empty()) return "quiver.png";
  return fs::path(scene).stem().string() + ".png";
}

// The scene, as read, with the time it took.
quiver::SceneDesc load(const std::string& scene, const std::optional<double>& crease_angle, double& load_ms) {
  const Clock::time_point start = Clock::now();
  quiver::SceneDesc desc = scene.empty() ? quiver::default_scene() : quiver::load_scene(scene, {crease_angle});
  load_ms = ms_since(start);
  return desc;
}

// build_named_scene, timed.
quiver::Scene build(const quiver::SceneDesc& desc, const quiver::SceneBuildOptions& options, const std::string& scene,
                    double& build_ms) {
  const Clock::time_point start = Clock::now();
  quiver::Scene built = quiver::build_named_scene(desc, options, scene);
  build_ms = ms_since(start);
  return built;
}

void print_summary(const quiver::RenderResult& result, const quiver::RenderSettings& settings, double load_ms,
                   double build_ms, const fs::path& output) {
  const double seconds = result.render_ms / 1000.0;
  const double mrays = seconds > 0.0 ? double(result.stats.rays.total()) / seconds / 1e6 : 0.0;
  std::fprintf(stderr,
               "rendered %dx%d (aa %s, %s x%d lanes, %d threads) in %.3f s: %llu rays, %.2f Mrays/s "
               "(load %.1f ms, build %.1f ms) -> %s\n",
               settings.width, settings.height, quiver::to_string(settings.aa).c_str(),
               std::string(quiver::isa_name(settings.isa)).c_str(), quiver::lane_width(settings.isa), result.threads,
               seconds, static_cast<unsigned long long>(result.stats.rays.total()), mrays, load_ms, build_ms,
               output.string().c_str());
}

// "interrupted by SIGINT <when>; nothing written", exit 130 (143 for SIGTERM).
int report_interrupted(std::string_view when) {
  const int signal = quiver::interrupting_signal();
  return report("interrupted by " + quiver::signal_name(signal) + " " + std::string(when) +
                    "; nothing written, existing files unchanged",
                quiver::interrupted_exit_code(signal));
}

int run_render(const RenderArgs& args) {
  // Everything the flags alone decide, before the scene is read.
  quiver::Isa isa;
  const fs::path output = args.output.empty() ? default_output(args.scene) : fs::path(args.output);
  std::vector<quiver::RoleFile> outputs{{"--output", output}};
  if (!args.stats.empty()) outputs.push_back({"--stats", args.stats});
  try {
    quiver::check_render_options(args.options);
    isa = quiver::choose_isa(args.options.simd, std::getenv("QUIVER_SIMD"));
    const bool has_aovs = args.options.aov && quiver::parse_aov_list(*args.options.aov).any();
    quiver::check_output_path(output, has_aovs);
    if (!args.stats.empty()) quiver::check_stats_path(args.stats);
    std::vector<quiver::RoleFile> scene_file;
    if (!args.scene.empty()) scene_file.push_back({"the scene file", args.scene});
    quiver::check_outputs_spare_inputs(outputs, scene_file);
  } catch (const std::exception& error) {
    return report(error.what(), kExitUsage);
  }

  quiver::install_interrupt_handlers();
  try {
    double load_ms = 0.0;
    quiver::SceneDesc desc = load(args.scene, args.options.crease_angle, load_ms);
    // UsageError from here on exits 2 through report_exception.
    quiver::check_outputs_spare_inputs(outputs, quiver::files_read(desc, !args.scene.empty()));
    const quiver::RenderPlan plan = quiver::plan_render(args.options, desc, isa);
    quiver::set_view(desc, args.options.camera, plan.settings.width, plan.settings.height);

    double build_ms = 0.0;
    const quiver::Scene scene = build(desc, plan.build, args.scene, build_ms);

    quiver::set_interrupt_phase(quiver::InterruptPhase::rendering);
    quiver::ProgressBar progress(stderr, !args.quiet && quiver::is_terminal(stderr));
    const quiver::RenderResult result = quiver::render(
        scene, plan.settings, [&](std::size_t done, std::size_t total) { progress.update(done, total); },
        &quiver::stop_requested());
    progress.finish();
    if (result.stopped()) {
      return report_interrupted("during the render, after " + std::to_string(result.tiles_done) + " of " +
                                std::to_string(result.tiles_total) + " tiles");
    }

    quiver::StagedOutputs staged;
    quiver::stage_image(staged, output, result.image);
    if (!args.stats.empty()) {
      quiver::RenderStatsContext context;
      context.version = QUIVER_VERSION;
      context.scene = args.scene.empty() ? "built-in" : args.scene;
      context.output = output.string();
      context.load_ms = load_ms;
      context.build_ms = build_ms;
      context.scene_memory_bytes = scene.memory_bytes();
      context.acceleration_memory_bytes = scene.acceleration_bytes();
      quiver::stage_json_file(staged, args.stats, quiver::render_stats_json(result, plan.settings, context));
    }
    if (quiver::stop_requested()) return report_interrupted("while writing the outputs");
    staged.commit();
    if (!args.quiet) print_summary(result, plan.settings, load_ms, build_ms, output);
    return 0;
  } catch (...) {
    return report_exception();
  }
}

int run_info(const std::string& scene_path, const std::optional<double>& crease_angle) {
  try {
    quiver::check_crease_angle(crease_angle);
  } catch (const UsageError& error) {
    return report(error.what(), kExitUsage);
  }
  try {
    double load_ms = 0.0;
    const quiver::SceneDesc as_read = load(scene_path, crease_angle, load_ms);
    quiver::SceneDesc desc = as_read;
    const bool default_view = !desc.camera;
    if (default_view) quiver::add_default_view(desc, quiver::kDefaultImageSide, quiver::kDefaultImageSide);
    double build_ms = 0.0;
    const quiver::Scene scene = build(desc, {}, scene_path, build_ms);
    quiver::SceneInfoContext context;
    context.scene = scene_path;
    context.load_ms = load_ms;
    context.build_ms = build_ms;
    context.default_view_added = default_view;
    quiver::write_scene_info(std::cout, as_read, scene, context);
    std::cout.flush();
    if (!std::cout) return report("cannot write to standard output", kExitFailure);
    return 0;
  } catch (const std::bad_alloc&) {
    return report("out of memory", kExitFailure);
  } catch (const std::exception& error) {
    return report(error.what(), kExitFailure);
  }
}

int run_trace(const TraceArgs& args) {
  quiver::Isa isa;
  try {
    quiver::check_trace_options(args.options);
    isa = quiver::choose_isa(args.options.simd, std::getenv("QUIVER_SIMD"));
  } catch (const std::exception& error) {
    return report(error.what(), kExitUsage);
  }

  try {
    double load_ms = 0.0;
    quiver::SceneDesc desc = load(args.scene, args.options.crease_angle, load_ms);
    const auto [width, height] = quiver::set_trace_view(args.options, desc);
    double build_ms = 0.0;
    const quiver::Scene scene = build(desc, {}, args.scene, build_ms);
    const quiver::PrimaryTraceResult result =
        quiver::trace_primary(scene, width, height, isa, args.options.threads, args.options.repeat);
    std::cout << quiver::trace_json_line(result, scene, width, height, build_ms) << "\n";
    std::cout.flush();
    if (!std::cout) return report("cannot write to standard output", kExitFailure);
    return 0;
  } catch (...) {
    return report_exception();
  }
}

// --crease-angle, the same for render, info and trace; the caller copies
// the value when the option's count() is non-zero.
CLI::Option* add_crease_angle_flag(CLI::App& command, double& degrees) {
  return command
      .add_option("--crease-angle", degrees,
                  "Smooth normals for OBJ meshes without normals: faces meeting at a vertex at an angle up to this "
                  "many degrees, 0..180, are shaded smooth there (angle-weighted); sharper edges stay hard; 0: "
                  "faceted. Meshes with normals keep theirs. Default: a TOML mesh's crease_angle, else " +
                      std::to_string(int(quiver::kDefaultCreaseAngleDegrees)))
      ->type_name("DEGREES");
}

// --look-from, --look-at, --up, --fov, the same for render and trace.
void add_camera_flags(CLI::App& command, RawCameraFlags& raw) {
  raw.look_from_option = command.add_option("--look-from", raw.look_from,
                                            "Camera position x,y,z, over the scene's camera (or the default view "
                                            "of a scene without one)")
                             ->type_name("X,Y,Z");
  raw.look_at_option = command.add_option("--look-at", raw.look_at, "The point the camera looks at, x,y,z")
                           ->type_name("X,Y,Z");
  raw.up_option = command.add_option("--up", raw.up, "The camera's up direction x,y,z (its part across the view "
                                                     "is used)")
                      ->type_name("X,Y,Z");
  raw.fov_option = command.add_option("--fov", raw.fov, "Field of view in degrees, (0, 180), as the scene's camera "
                                                        "angle")
                       ->type_name("DEGREES");
}

// The camera flags that were given.
quiver::CameraFlags given_camera_flags(const RawCameraFlags& raw) {
  quiver::CameraFlags flags;
  if (raw.look_from_option->count()) flags.look_from = raw.look_from;
  if (raw.look_at_option->count()) flags.look_at = raw.look_at;
  if (raw.up_option->count()) flags.up = raw.up;
  if (raw.fov_option->count()) flags.fov = raw.fov;
  return flags;
}

void add_trace_flags(CLI::App& trace, TraceArgs& args, RawTraceFlags& raw) {
  trace.add_option("scene", args.scene,
                   "Scene file: .nff, .toml or .obj (any case). A scene without a camera (OBJ) gets the default "
                   "view framing it, as in 'quiver render'")
      ->required()
      ->type_name("SCENE");
  raw.width_option = trace.add_option("--width", raw.width,
                                      "Image width in pixels, 1..65536 (at most 2^24 pixels in all: every ray is "
                                      "held at once). Default: the scene camera's; with --height alone, the "
                                      "camera's aspect is kept; 512 without a camera")
                         ->type_name("PIXELS");
  raw.height_option = trace.add_option("--height", raw.height, "Image height in pixels, 1..65536. Default as for "
                                                               "--width")
                          ->type_name("PIXELS");
  trace.add_option("--threads", args.options.threads, "Worker threads, 0..1024; 0: one per core. Default: 0")
      ->type_name("N");
  trace.add_option("--repeat", args.options.repeat,
                   "Timed passes over every ray, 1..10000; the times reported are medians over them. Default: " +
                       std::to_string(quiver::kDefaultTraceRepeat))
      ->type_name("R");
  raw.simd_option = trace.add_option("--simd", raw.simd,
                                     "Lane width: auto (the widest this CPU supports), scalar (1), sse4 (4), avx2 "
                                     "(8) or avx512 (16); every choice finds the same hits. Default: $QUIVER_SIMD, "
                                     "else auto. A choice this CPU lacks is an error")
                        ->type_name("ISA");
  raw.crease_angle_option = add_crease_angle_flag(trace, raw.crease_angle);
  add_camera_flags(trace, raw.camera);
}

void add_render_flags(CLI::App& render, RenderArgs& args, RawRenderFlags& raw) {
  render.add_option("scene", args.scene,
                    "Scene file: .nff, .toml or .obj (any case). Absent: the built-in scene. A scene without a "
                    "camera (OBJ) gets a default view framing it (and, if it has no lights, a white point light "
                    "above and to the right of that view)")
      ->type_name("SCENE");
  render.add_option("-o,--output", args.output,
                    "Image file: .png/.jpg/.jpeg (8-bit sRGB) or .exr/.hdr/.tif/.tiff (32-bit float linear). "
                    "Default: <scene name>.png in the current directory, quiver.png for the built-in scene. "
                    "Checked before the scene is read; written only when everything succeeds")
      ->type_name("FILE")
      ->check(kNonEmptyFileName);
  raw.width_option = render.add_option("--width", raw.width,
                                       "Image width in pixels, 1..65536 (at most 2^28 pixels in all). Default: the "
                                       "scene camera's; with --height alone, the camera's aspect is kept; 512 "
                                       "without a camera")
                         ->type_name("PIXELS");
  raw.height_option = render.add_option("--height", raw.height,
                                        "Image height in pixels, 1..65536. Default as for --width")
                          ->type_name("PIXELS");
  raw.aa_option = render.add_option("--aa", raw.aa,
                                    "Anti-aliasing: none (one ray per pixel centre) | grid:N (NxN rays at sub-pixel "
                                    "centres, N 1..64) | jitter:N (NxN stratified random rays, N 1..64) | "
                                    "adaptive:THRESHOLD:DEPTH (rays at square corners, a square split while its "
                                    "corner colours differ by more than THRESHOLD, up to DEPTH levels, 0..6) | "
                                    "corners (SPD rule: (W+1)x(H+1) corner rays, pixel = mean of its 4) | "
                                    "refine:THRESHOLD:N (2x2 stratified random rays, a pixel's strata doubled per "
                                    "side while its mean's standard error exceeds THRESHOLD or, after the first "
                                    "pass, a neighbour's mean differs by more than 4 THRESHOLD; up to NxN, N 2, 4, 8 "
                                    "or 16). "
                                    "Default: the scene file's setting, else none")
                      ->type_name("MODE");
  raw.max_depth_option = render.add_option("--max-depth", raw.max_depth,
                                           "Bounces after the primary ray, 0..64 (0: ray casting, no reflection or "
                                           "refraction). Default: the scene file's setting, else 5")
                             ->type_name("BOUNCES");
  raw.min_weight_option = render.add_option("--min-weight", raw.min_weight,
                                            "A reflection or refraction ray whose largest RGB weight is below this "
                                            "is not cast; finite, >= 0; 0 disables the cut-off. Default: the scene "
                                            "file's setting, else 0.001")
                              ->type_name("WEIGHT");
  render.add_option("--threads", args.options.threads, "Worker threads, 0..1024; 0: one per core. Default: 0")
      ->type_name("N");
  raw.simd_option = render.add_option("--simd", raw.simd,
                                      "Lane width: auto (the widest this CPU supports), scalar (1), sse4 (4), "
                                      "avx2 (8) or avx512 (16); every choice gives the same image. Default: "
                                      "$QUIVER_SIMD, else auto. A choice this CPU lacks is an error")
                        ->type_name("ISA");
  raw.seed_option = render.add_option("--seed", raw.seed,
                    "Seed (unsigned 64-bit) for jittered anti-aliasing and area-light samples. Default: 0")
      ->type_name("UINT64");
  render.add_option("--stats", args.stats,
                    "Also write render statistics as JSON: timings (ms), settings, ray counts by kind, Mrays/s, "
                    "lane utilisation per wave, memory (bytes). Written only when everything succeeds")
      ->type_name("FILE.json")
      ->check(kNonEmptyFileName);
  raw.aov_option = render.add_option("--aov", raw.aov,
                                     "Extra channels through each pixel centre, a comma list of depth (Z: distance, "
                                     "inf on a miss), normal (N.X N.Y N.Z), id (kind and id: primitive kind and "
                                     "index in the scene file, -1 on a miss); each at most once; needs an .exr "
                                     "output")
                       ->type_name("LIST");
  render.add_flag("-q,--quiet", args.quiet, "No progress bar and no summary line (errors are still reported)");
  raw.preset_option = render.add_option("--preset", raw.preset,
                                        "spd: the Standard Procedural Databases procedure: --aa corners, "
                                        "--max-depth 4 (5 levels counting the eye ray), --min-weight 0, every "
                                        "surface two-sided; a flag contradicting it is an error")
                          ->type_name("NAME");
  render.add_flag("--two-sided", args.options.two_sided,
                  "Make every surface two-sided (a one-sided surface seen from behind gets only ambient light)");
  render.add_flag("--robust-methods", args.options.robust_methods,
                  "Use the robust sphere test in every scene. Default: the seed's algebraic test where no ray can "
                  "start more than 10 radii from a sphere (bench/ACCURACY.md), the robust one elsewhere");
  raw.crease_angle_option = add_crease_angle_flag(render, raw.crease_angle);
  add_camera_flags(render, raw.camera);
}

// Copies the flags that were given into the optional fields.
void collect_render_flags(const RawRenderFlags& raw, RenderOptions& options) {
  if (raw.width_option->count()) options.width = raw.width;
  if (raw.height_option->count()) options.height = raw.height;
  if (raw.max_depth_option->count()) options.max_depth = raw.max_depth;
  if (raw.min_weight_option->count()) options.min_weight = raw.min_weight;
  if (raw.crease_angle_option->count()) options.crease_angle = raw.crease_angle;
  options.camera = given_camera_flags(raw.camera);
  if (raw.aa_option->count()) options.aa = raw.aa;
  if (raw.simd_option->count()) options.simd = raw.simd;
  if (raw.aov_option->count()) options.aov = raw.aov;
  if (raw.preset_option->count()) quiver::check_preset(raw.preset);
  options.preset_spd = raw.preset_option->count() > 0;
  if (raw.seed_option->count()) options.seed = quiver::parse_seed(raw.seed);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"quiver: a data-oriented SIMD packet ray tracer (Whitted: Phong shading, shadows, reflection, "
               "refraction, textures, anti-aliasing).\nExit codes: 0 success, 1 failure (bad scene, render or "
               "write error), 2 usage error (also: an output naming a file the render reads or another output), "
               "130/143 interrupted by SIGINT/SIGTERM (the render stops at its next tile; no output is written "
               "or changed).",
               "quiver"};
  app.footer("Run 'quiver render --help', 'quiver info --help' or 'quiver trace --help' for the options of each "
             "command.");
  app.set_version_flag("--version", std::string("quiver ") + QUIVER_VERSION, "Print the version and exit");
  app.require_subcommand(1, 1);

  RenderArgs render_args;
  RawRenderFlags raw;
  CLI::App* render = app.add_subcommand("render", "Render a scene file (or the built-in scene) to an image");
  add_render_flags(*render, render_args, raw);

  std::string info_scene;
  CLI::App* info = app.add_subcommand(
      "info", "Report a scene: primitives as read and as built (kept, dropped), opaque and transmissive, bounds, "
              "camera, lights, materials, textures, memory (bytes) per structure, load and build times (ms)");
  info->add_option("scene", info_scene, "Scene file: .nff, .toml or .obj")->required()->type_name("SCENE");
  double info_crease_angle = 0.0;
  CLI::Option* info_crease_angle_option = add_crease_angle_flag(*info, info_crease_angle);

  TraceArgs trace_args;
  RawTraceFlags raw_trace;
  CLI::App* trace = app.add_subcommand(
      "trace",
      "Time the closest hits of the primary rays alone (one through each pixel centre, as --aa none; no shading, no "
      "secondary rays) and print one JSON line: mrays_per_s (median over the repeats), hits (rays that hit), t_sum "
      "(their hit distances added in double), rays, ms_median, threads, simd, lanes, build_ms, width, height, "
      "repeat, primitives, acceleration_bytes (the BVH's). Rays are generated before timing; hits and t_sum are "
      "the same for every --threads and --simd");
  add_trace_flags(*trace, trace_args, raw_trace);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);  // --help, --version
    std::cerr << "quiver: " << error.what() << "\nRun 'quiver --help' (or 'quiver render --help') for usage.\n";
    return kExitUsage;
  }

  if (render->parsed()) {
    try {
      collect_render_flags(raw, render_args.options);
    } catch (const UsageError& error) {
      return report(error.what(), kExitUsage);
    }
    return run_render(render_args);
  }
  if (trace->parsed()) {
    if (raw_trace.width_option->count()) trace_args.options.width = raw_trace.width;
    if (raw_trace.height_option->count()) trace_args.options.height = raw_trace.height;
    if (raw_trace.simd_option->count()) trace_args.options.simd = raw_trace.simd;
    if (raw_trace.crease_angle_option->count()) trace_args.options.crease_angle = raw_trace.crease_angle;
    trace_args.options.camera = given_camera_flags(raw_trace.camera);
    return run_trace(trace_args);
  }
  std::optional<double> crease_angle;
  if (info_crease_angle_option->count()) crease_angle = info_crease_angle;
  return run_info(info_scene, crease_angle);
}
