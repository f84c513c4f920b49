// quiver, the command-line program: `quiver render [SCENE]` renders a scene
// file (or the built-in scene) to an image, `quiver info SCENE` reports what
// a scene holds, `quiver trace SCENE` times the primary rays' closest hits
// and prints one JSON line (app/trace_command.h), `quiver view [SCENE]`
// serves a page to look around the scene in a browser (app/view_server.h).
// Exit codes: 0 success, 1 failure (unreadable or invalid scene, render or
// write error), 2 usage error (bad flag or value, an output naming an input
// or another output), 130 / 143 interrupted by SIGINT / SIGTERM
// (app/interrupt.h; for view, the way it stops). Errors go to
// stderr as "quiver: <message>". A render's outputs are staged and renamed
// over their targets together once all were written: on any failure or
// interruption no output file is created or changed.
// CLI11 is slow to compile: only the program mains include it (here
// through app/render_flags_cli.h, which quiver-mpi's main shares).
#include "app/render_flags_cli.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "integrator/render.h"
#include "scene/scene.h"
#include "scene/auto_view.h"
#include "io/image_output.h"
#include "io/output_file.h"
#include "app/interrupt.h"
#include "app/progress_bar.h"
#include "app/render_job.h"
#include "app/render_options.h"
#include "app/scene_build.h"
#include "app/scene_info.h"
#include "app/suggestions.h"
#include "app/stats_json.h"
#include "app/trace_command.h"
#include "app/view_server.h"
#include "app/view_session.h"

namespace {

namespace fs = std::filesystem;
using quiver::kExitFailure;
using quiver::kExitUsage;
using quiver::RenderArgs;
using quiver::UsageError;
using quiver::cli::RawCameraFlags;
using quiver::cli::RawRenderFlags;

// What `quiver trace` was given, as parsed.
struct TraceArgs {
  std::string scene;
  quiver::TraceOptions options;
};

// The parsed values of `quiver trace`, before we know which were given.
struct RawTraceFlags {
  int width = 0, height = 0;
  double crease_angle = 0.0;
  std::string simd;
  CLI::Option *width_option, *height_option, *simd_option, *crease_angle_option;
  RawCameraFlags camera;
};

// What `quiver info` was given, as parsed, before we know which optional flags were.
struct InfoArgs {
  std::string scene;
  quiver::SceneLoadOptions load_options;
  double crease_angle = 0.0;
  CLI::Option* crease_angle_option;
  RawCameraFlags camera;
};

int report(std::string_view message, int exit_code) {
  std::cerr << "quiver: " << message << "\n";
  return exit_code;
}

// Reports the exception being handled: a UsageError exits 2, anything else 1.
int report_exception() {
  const auto [exit_code, message] = quiver::describe_current_exception();
  return report(message, exit_code);
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
  quiver::CheckedRenderArgs checked;
  try {
    checked = quiver::check_render_args(args, std::getenv("QUIVER_SIMD"));
  } catch (const std::exception& error) {
    return report(error.what(), kExitUsage);
  }

  quiver::install_interrupt_handlers();
  try {
    const quiver::ProgressStyle style = quiver::progress_style_for(stderr, args.quiet);
    // UsageError from here on exits 2 through report_exception.
    const quiver::PreparedRender prepared = quiver::prepare_render(args, checked, style);
    quiver::print_scene_warnings(prepared.desc);
    const quiver::RenderSettings& settings = prepared.plan.settings;

    quiver::set_interrupt_phase(quiver::InterruptPhase::rendering);
    quiver::ProgressBar progress(stderr, style);
    // No progress shown, no callback: the render then skips estimating its tiles' costs.
    quiver::RenderProgress report_progress;
    if (style != quiver::ProgressStyle::off) {
      report_progress = [&](const quiver::RenderProgressState& p) {
        progress.update(p.tiles_done, p.tiles_total, p.work_done, p.tile_seconds);
      };
    }
    const quiver::RenderResult result =
        quiver::render(prepared.scene, settings, report_progress, &quiver::stop_requested());
    progress.finish();
    if (result.stopped()) {
      return report_interrupted("during the render, after " + std::to_string(result.tiles_done) + " of " +
                                std::to_string(result.tiles_total) + " tiles");
    }

    quiver::StagedOutputs staged;
    quiver::stage_image(staged, checked.output, result.image);
    if (!args.stats.empty()) {
      quiver::stage_json_file(staged, args.stats, quiver::render_stats(args, checked, prepared, result));
    }
    if (quiver::stop_requested()) return report_interrupted("while writing the outputs");
    staged.commit();
    if (!args.quiet) {
      quiver::print_render_summary(stderr, result, settings, prepared.load_ms, prepared.build_ms, checked.output,
                                   std::to_string(result.threads) + " threads");
    }
    return 0;
  } catch (...) {
    return report_exception();
  }
}

int run_view(const RenderArgs& args, const quiver::cli::ViewFlags& flags) {
  quiver::Isa isa;
  try {
    quiver::check_render_options(args.options);
    isa = quiver::choose_isa(args.options.simd, std::getenv("QUIVER_SIMD"));
  } catch (const std::exception& error) {
    return report(error.what(), kExitUsage);
  }
  quiver::install_interrupt_handlers();
  try {
    quiver::ViewSession session(args, isa);
    quiver::ViewServer server(session, {flags.bind, flags.port, ""});
    if (!quiver::is_loopback_address(flags.bind)) {
      std::cerr << "quiver: warning: --bind " << flags.bind
                << " lets other machines reach the viewer; anyone with the URL's token can render views of the "
                   "scene\n";
    }
    std::fprintf(stderr, "quiver view: %s (load %.1f ms, build %.1f ms) at\n  %s\nquiver view: open that URL in a "
                 "browser; Ctrl-C stops\n", args.scene.empty() ? "the built-in scene" : args.scene.c_str(),
                 session.load_ms(), session.build_ms(), server.url().c_str());
    // From here a signal only raises the stop flag; this thread turns it into the server's stop.
    quiver::set_interrupt_phase(quiver::InterruptPhase::rendering);
    std::atomic<bool> served{false};
    std::thread watcher([&] {
      while (!served.load() && !quiver::stop_requested().load()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      server.stop();
    });
    const bool listened = server.run();
    served.store(true);
    watcher.join();
    if (const int signal = quiver::interrupting_signal(); signal != 0) {
      std::cerr << "quiver view: stopped by " << quiver::signal_name(signal) << "\n";
      return quiver::interrupted_exit_code(signal);
    }
    if (!listened) return report("the viewer's server stopped listening", kExitFailure);
    return 0;
  } catch (...) {
    return report_exception();
  }
}

int run_info(const std::string& scene_path, const quiver::SceneLoadOptions& load_options,
             const quiver::CameraFlags& camera_flags) {
  try {
    quiver::check_crease_angle(load_options.crease_angle_degrees);
    quiver::check_camera_flags(camera_flags);
  } catch (const UsageError& error) {
    return report(error.what(), kExitUsage);
  }
  try {
    double load_ms = 0.0;
    const quiver::ProgressStyle style = quiver::progress_style_for(stderr, false);
    quiver::SceneDesc desc = quiver::load_scene_timed(scene_path, load_options, load_ms, style);
    quiver::print_scene_warnings(desc);
    // set_view sets only the camera, lights, ambient and background: the
    // report's are the file's, kept aside rather than in a copy of the whole
    // scene (its meshes may be large).
    const auto camera_as_read = desc.camera;
    const auto lights_as_read = desc.lights;
    const auto ambient_as_read = desc.ambient;
    const auto background_as_read = desc.background;
    const std::optional<quiver::DefaultView> default_view =
        quiver::set_view(desc, camera_flags, quiver::kDefaultImageSide, quiver::kDefaultImageSide);
    quiver::SceneInfoContext context;
    context.read = quiver::read_counts(desc);
    double build_ms = 0.0;
    const std::size_t load_peak = quiver::peak_resident_bytes();
    if (quiver::restart_resident_high_water()) {
      context.build_start_resident_bytes = quiver::process_status_bytes("VmRSS");
    }
    const quiver::Scene scene = quiver::build_scene_timed(desc, {}, scene_path, build_ms, style);
    if (context.build_start_resident_bytes) context.build_peak_resident_bytes = quiver::process_status_bytes("VmHWM");
    desc.camera = camera_as_read;
    desc.lights = lights_as_read;
    desc.ambient = ambient_as_read;
    desc.background = background_as_read;
    context.scene = scene_path;
    context.load_ms = load_ms;
    context.build_ms = build_ms;
    context.default_view = default_view;
    context.peak_resident_bytes = std::max(load_peak, quiver::peak_resident_bytes());
    quiver::write_scene_info(std::cout, desc, scene, context);
    std::cout.flush();
    if (!std::cout) return report("cannot write to standard output", kExitFailure);
    return 0;
  } catch (const UsageError& error) {
    return report(error.what(), kExitUsage);
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
    const quiver::ProgressStyle style = quiver::progress_style_for(stderr, false);
    quiver::SceneDesc desc = quiver::load_scene_timed(
        args.scene, {args.options.crease_angle, args.options.strict, args.options.allow_outside_paths}, load_ms,
        style);
    quiver::print_scene_warnings(desc);
    const auto [width, height] = quiver::set_trace_view(args.options, desc);
    double build_ms = 0.0;
    const quiver::Scene scene = quiver::build_scene_timed(desc, {}, args.scene, build_ms, style);
    const quiver::PrimaryTraceResult result =
        quiver::trace_primary(scene, width, height, isa, args.options.threads, args.options.repeat,
                              {args.options.occluded, args.options.shuffled});
    std::cout << quiver::trace_json_line(result, scene, width, height, build_ms,
                                         {args.options.occluded, args.options.shuffled})
              << "\n";
    std::cout.flush();
    if (!std::cout) return report("cannot write to standard output", kExitFailure);
    return 0;
  } catch (...) {
    return report_exception();
  }
}

void add_info_flags(CLI::App& info, InfoArgs& args) {
  info.add_option("scene", args.scene, "Scene file: .nff, .toml, .obj, .ply, .gltf, .glb or .stl")
      ->required()
      ->type_name("SCENE");
  args.crease_angle_option = quiver::cli::add_crease_angle_flag(info, args.crease_angle);
  quiver::cli::add_strict_flag(info, args.load_options.strict);
  quiver::cli::add_allow_outside_paths_flag(info, args.load_options.allow_outside_paths);
  quiver::cli::add_camera_flags(info, args.camera);
}

void add_trace_flags(CLI::App& trace, TraceArgs& args, RawTraceFlags& raw) {
  trace.add_option("scene", args.scene,
                   "Scene file: .nff, .toml, .obj, .ply, .gltf, .glb or .stl (any case). A scene without a camera "
                   "(a mesh) gets the default view framing it, as in 'quiver render'")
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
  raw.crease_angle_option = quiver::cli::add_crease_angle_flag(trace, raw.crease_angle);
  quiver::cli::add_strict_flag(trace, args.options.strict);
  quiver::cli::add_allow_outside_paths_flag(trace, args.options.allow_outside_paths);
  quiver::cli::add_camera_flags(trace, raw.camera);
  trace.add_flag("--occluded", args.options.occluded,
                 "Time any-hit (occlusion) queries instead of closest hits: hits counts the occluded rays, t_sum is 0");
  trace.add_flag("--shuffle", args.options.shuffled,
                 "Trace the same rays in a random order (one fixed permutation), in batches of 256 as the tiles: "
                 "incoherent rays. t_sum may differ from the tile order's in its last bits (another order of "
                 "additions)");
}

// The render flags that were given, into args.options, then run(args); a
// bad value exits 2.
template <class Run>
int with_collected_flags(const RawRenderFlags& raw, RenderArgs& args, const Run& run) {
  try {
    quiver::cli::collect_render_flags(raw, args.options);
  } catch (const UsageError& error) {
    return report(error.what(), kExitUsage);
  }
  return run(args);
}

// `quiver trace` with the optional flags that were given.
int run_trace_command(const RawTraceFlags& raw, TraceArgs args) {
  if (raw.width_option->count()) args.options.width = raw.width;
  if (raw.height_option->count()) args.options.height = raw.height;
  if (raw.simd_option->count()) args.options.simd = raw.simd;
  if (raw.crease_angle_option->count()) args.options.crease_angle = raw.crease_angle;
  try {
    args.options.camera = quiver::cli::given_camera_flags(raw.camera);
  } catch (const UsageError& error) {
    return report(error.what(), kExitUsage);
  }
  return run_trace(args);
}

// `quiver info` with the optional flags that were given.
int run_info_command(InfoArgs args) {
  if (args.crease_angle_option->count()) args.load_options.crease_angle_degrees = args.crease_angle;
  quiver::CameraFlags camera_flags;
  try {
    camera_flags = quiver::cli::given_camera_flags(args.camera);
  } catch (const UsageError& error) {
    return report(error.what(), kExitUsage);
  }
  return run_info(args.scene, args.load_options, camera_flags);
}

CLI::App* add_view_command(CLI::App& app, RenderArgs& args, RawRenderFlags& raw, quiver::cli::ViewFlags& flags) {
  CLI::App* view = app.add_subcommand(
      "view",
      "Look around a scene in a web browser: serves a page on this machine (the URL, with its access token, is "
      "printed) that shows the scene from any view, refined from a coarse image to the full render; drag to "
      "orbit, right- or shift-drag to pan, wheel to dolly, f frames the scene, r resets; 'Copy command' gives the "
      "'quiver render' command that writes the view shown, bit for bit. Takes the render flags (the view's "
      "camera, size and sampling start from them)");
  quiver::cli::add_view_flags(*view, args, raw, flags);
  return view;
}

}  // namespace

// The command names of app, in the order they were added.
std::vector<std::string> command_names(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    names.push_back(command->get_name());
  }
  return names;
}

// The first argument is a word that is neither a flag nor a command.
bool first_word_is_no_command(const std::vector<std::string>& args, const std::vector<std::string>& commands) {
  return args.size() >= 2 && !args[1].empty() && args[1][0] != '-' &&
         std::find(commands.begin(), commands.end(), args[1]) == commands.end();
}

// `quiver SCENE [options]` is `quiver render SCENE [options]`: when the
// first argument is no command but names a file, the arguments with
// "render" put before it.
std::vector<std::string> with_default_command(int argc, char** argv, const std::vector<std::string>& commands) {
  std::vector<std::string> args(argv, argv + argc);
  std::error_code error;
  if (first_word_is_no_command(args, commands) && fs::is_regular_file(args[1], error)) {
    args.insert(args.begin() + 1, "render");
  }
  return args;
}

// What to add to CLI11's message for a command line it refused: a first
// word that is no command (nor a file), or flags the command does not
// have, each with the nearest known spelling.
std::string usage_hint(CLI::App& app, const std::vector<std::string>& args, const std::vector<std::string>& commands) {
  if (first_word_is_no_command(args, commands)) {
    std::string listed;
    for (const std::string& name : commands) listed += (listed.empty() ? "" : ", ") + name;
    return "\n'" + args[1] + "' is neither a command (" + listed + ") nor an existing file" +
           quiver::did_you_mean(args[1], commands);
  }
  if (args.size() < 2) return "";
  CLI::App* command = app.get_subcommand_ptr(args[1]).get();
  if (command == nullptr) return "";
  std::vector<std::string> flags{"--help"};
  for (const CLI::Option* option : command->get_options()) {
    for (const std::string& name : option->get_lnames()) flags.push_back("--" + name);
  }
  std::string hint;
  for (std::size_t k = 2; k < args.size(); ++k) {
    if (args[k].rfind("--", 0) != 0 || args[k].size() == 2) continue;
    const std::string flag = args[k].substr(0, args[k].find('='));
    if (std::find(flags.begin(), flags.end(), flag) != flags.end()) continue;
    const std::string suggestion = quiver::did_you_mean(flag, flags);
    hint += "\n'" + flag + "' is not a flag of 'quiver " + args[1] + "'" + suggestion;
  }
  return hint;
}

int main(int argc, char** argv) {
  CLI::App app{"quiver: a data-oriented SIMD packet ray tracer (Whitted: Phong shading, shadows, reflection, "
               "refraction, textures, anti-aliasing).\nExit codes: 0 success, 1 failure (bad scene, render or "
               "write error), 2 usage error (also: an output naming a file the render reads or another output), "
               "130/143 interrupted by SIGINT/SIGTERM (the render stops at its next tile; no output is written "
               "or changed).",
               "quiver"};
  app.footer("'quiver SCENE [options]' is short for 'quiver render SCENE [options]'. Run 'quiver render --help', "
             "'quiver info --help', 'quiver trace --help' or 'quiver view --help' for the options of each command.");
  app.set_version_flag("--version", std::string("quiver ") + QUIVER_VERSION, "Print the version and exit");
  app.require_subcommand(1, 1);

  RenderArgs render_args;
  RawRenderFlags raw;
  CLI::App* render = app.add_subcommand("render", "Render a scene file (or the built-in scene) to an image");
  quiver::cli::add_render_flags(*render, render_args, raw);

  InfoArgs info_args;
  CLI::App* info = app.add_subcommand(
      "info", "Report a scene: primitives as read and as built (kept, dropped), opaque and transmissive, bounds, "
              "camera (the view the camera flags give), lights, materials, textures, memory (bytes) per "
              "structure against the process's peak resident memory and the build's own, load and build times (ms)");
  add_info_flags(*info, info_args);

  TraceArgs trace_args;
  RawTraceFlags raw_trace;
  CLI::App* trace = app.add_subcommand(
      "trace",
      "Time the closest hits of the primary rays alone (one through each pixel centre, as --aa none; no shading, no "
      "secondary rays) and print one JSON line: mrays_per_s (median over the repeats), hits (rays that hit), t_sum "
      "(their hit distances added in double), rays, ms_median, threads, simd, lanes, build_ms, width, height, "
      "repeat, primitives (an instanced mesh counted once), acceleration_bytes (the BVHs'), memory_bytes (the "
      "stored primitives and their tables), instances, instance_table_bytes (with the top-level BVH), query "
      "(closest or occluded) and order (tiles or shuffled). Rays are generated before timing; hits and t_sum are "
      "the same for every --threads and --simd");
  add_trace_flags(*trace, trace_args, raw_trace);

  RenderArgs view_args;
  RawRenderFlags view_raw;
  quiver::cli::ViewFlags view_flags;
  CLI::App* view = add_view_command(app, view_args, view_raw, view_flags);

  const std::vector<std::string> commands = command_names(app);
  std::vector<std::string> args = with_default_command(argc, argv, commands);
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend() - 1);  // CLI11 takes them last first, no program name
    app.parse(reversed);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);  // --help, --version
    std::cerr << "quiver: " << error.what() << usage_hint(app, args, commands)
              << "\nRun 'quiver --help' (or 'quiver render --help') for usage.\n";
    return kExitUsage;
  }

  if (render->parsed()) return with_collected_flags(raw, render_args, run_render);
  if (view->parsed()) {
    return with_collected_flags(view_raw, view_args, [&](const RenderArgs& a) { return run_view(a, view_flags); });
  }
  if (trace->parsed()) return run_trace_command(raw_trace, trace_args);
  return run_info_command(info_args);
}
