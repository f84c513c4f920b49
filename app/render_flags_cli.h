// The `render` flags on CLI11, shared by the programs `quiver render`
// (app/main.cpp) and `quiver-mpi` (app/mpi_main.cpp), with the crease-angle
// and camera flags `info` and `trace` share. CLI11 is slow to compile:
// include this header only from a program's main file.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "app/render_job.h"
#include "app/render_options.h"
#include "geometry/vertex_normals.h"

namespace quiver::cli {

// A file option given an empty value is a mistake, not a request for the default.
inline const CLI::Validator kNonEmptyFileName(
    [](std::string& value) { return value.empty() ? std::string("an empty file name") : std::string(); }, "");

// The camera flags of render and trace, before we know which were given.
struct RawCameraFlags {
  std::string look_from, look_at, up;
  double fov = 0.0;
  CLI::Option *look_from_option, *look_at_option, *up_option, *fov_option;
};

// The parsed values, before we know which optional flags were given.
struct RawRenderFlags {
  int width = 0, height = 0, max_depth = 0;
  double min_weight = 0.0, crease_angle = 0.0;
  std::string aa, simd, aov, preset, seed, texture_filter;
  CLI::Option *width_option, *height_option, *max_depth_option, *min_weight_option, *crease_angle_option;
  CLI::Option *aa_option, *simd_option, *preset_option, *seed_option, *texture_filter_option;
  CLI::Option* aov_option = nullptr;  // render's, not view's
  RawCameraFlags camera;
};

// --strict, the same for render, info and trace.
inline void add_strict_flag(CLI::App& command, bool& strict) {
  command.add_flag("--strict", strict,
                   "Refuse what the mesh readers otherwise forgive with a warning (a missing mtllib file or "
                   "map_Kd image, a usemtl of an undefined material, a trailing comment in OBJ; a missing glTF "
                   "texture file or one embedded as raw texels; points and lines in PLY, glTF or STL)");
}

// --allow-outside-paths, the same for render, info and trace.
inline void add_allow_outside_paths_flag(CLI::App& command, bool& allow) {
  command.add_flag("--allow-outside-paths", allow,
                   "Let the scene name files outside its own folder. Default: an OBJ's mtllib and map_Kd, a TOML "
                   "scene's meshes and images and a glTF's buffers and images must lie in the folder of the scene "
                   "file given (or below it, symlinks resolved); any other is an error");
}

// --crease-angle, the same for render, info and trace; the caller copies
// the value when the option's count() is non-zero.
inline CLI::Option* add_crease_angle_flag(CLI::App& command, double& degrees) {
  return command
      .add_option("--crease-angle", degrees,
                  "Smooth normals for OBJ, PLY and STL meshes without normals (STL's facet normals count as "
                  "none): faces meeting at a vertex at an angle up to this many degrees, 0..180, are shaded "
                  "smooth there (angle-weighted); sharper edges stay hard; 0: "
                  "faceted. Meshes with normals keep theirs. Default: a TOML mesh's crease_angle, else " +
                      std::to_string(int(quiver::kDefaultCreaseAngleDegrees)))
      ->type_name("DEGREES");
}

// --look-from, --look-at, --up, --fov, the same for render, info and trace.
inline void add_camera_flags(CLI::App& command, RawCameraFlags& raw) {
  raw.look_from_option = command.add_option("--look-from", raw.look_from,
                                            "Camera position x,y,z, over the scene's camera (or the default view "
                                            "of a scene without one)")
                             ->type_name("X,Y,Z");
  raw.look_at_option = command.add_option("--look-at", raw.look_at, "The point the camera looks at, x,y,z")
                           ->type_name("X,Y,Z");
  raw.up_option = command.add_option("--up", raw.up,
                                     "The camera's up direction x,y,z (its part across the view is used); for a "
                                     "scene without a camera, also the model's up axis the default view is "
                                     "placed around (else +z for STL, CAD's convention, and for PLY by Blender or "
                                     "OBJ by FreeCAD, which keep their +z up; else +y, or +z for a mesh standing "
                                     "on a flat base at its lowest z; `quiver info` says which)")
                      ->type_name("X,Y,Z");
  raw.fov_option = command.add_option("--fov", raw.fov, "Field of view in degrees, (0, 180), as the scene's camera "
                                                        "angle")
                       ->type_name("DEGREES");
}

// The camera flags that were given.
inline quiver::CameraFlags given_camera_flags(const RawCameraFlags& raw) {
  quiver::CameraFlags flags;
  if (raw.look_from_option->count()) flags.look_from = quiver::parse_vector_flag("--look-from", raw.look_from);
  if (raw.look_at_option->count()) flags.look_at = quiver::parse_vector_flag("--look-at", raw.look_at);
  if (raw.up_option->count()) flags.up = quiver::parse_vector_flag("--up", raw.up);
  if (raw.fov_option->count()) flags.fov = raw.fov;
  return flags;
}

// The scene file, for render and view.
inline void add_scene_argument(CLI::App& render, RenderArgs& args) {
  render.add_option("scene", args.scene,
                    "Scene file: .nff, .toml, .obj, .ply, .gltf, .glb or .stl (any case). Absent: the built-in "
                    "scene. A scene without a camera (a mesh) gets a default view framing it; a scene without "
                    "lights gets a rig that follows the final camera (after the camera flags): a key light above "
                    "and to the right of the eye, a fill at the eye, and a grey background if it has none")
      ->type_name("SCENE");
}

// The scene and the image file.
inline void add_file_flags(CLI::App& render, RenderArgs& args) {
  add_scene_argument(render, args);
  render.add_option("-o,--output", args.output,
                    "Image file: .png/.jpg/.jpeg (8-bit sRGB) or .exr/.hdr/.tif/.tiff (32-bit float linear). "
                    "Default: <scene name>.png in the current directory, quiver.png for the built-in scene. "
                    "Checked before the scene is read; written only when everything succeeds, by renaming a finished "
                    "file into place, so it must name a regular file (not a device such as /dev/null or a FIFO), and "
                    "never a file the render reads or another output")
      ->type_name("FILE")
      ->check(kNonEmptyFileName);
}

// The image: its size and how its pixels are sampled and traced.
inline void add_image_flags(CLI::App& render, RawRenderFlags& raw) {
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
                                    "pass, a neighbour's mean differs by more than 4 THRESHOLD or its first rays, or "
                                    "its and a neighbour's, met different surfaces (material, nothing, or a 5% depth "
                                    "jump); up to NxN, N 2, 4, 8 or 16; refine:THRESHOLD:N:grid puts the rays at "
                                    "the strata's centres, as grid:N, a refined pixel sampled afresh). "
                                    "Default: the scene file's setting, else " +
                                        std::string(quiver::kDefaultAntiAliasing) +
                                        " (the best quality for its cost in bench/ACCURACY.md's study)")
                      ->type_name("MODE");
  raw.max_depth_option = render.add_option("--max-depth", raw.max_depth,
                                           "Bounces after the primary ray, 0.." + std::to_string(quiver::kMaxMaxDepth) +
                                               " (0: ray casting, no reflection or refraction). Default: the scene "
                                               "file's setting, else " +
                                               std::to_string(quiver::kDefaultMaxDepth))
                             ->type_name("BOUNCES");
  raw.min_weight_option = render.add_option("--min-weight", raw.min_weight,
                                            "A reflection or refraction ray whose largest RGB weight is below this "
                                            "is not cast; 0..1; 0 disables the cut-off. Default: the scene "
                                            "file's setting, else 0.001")
                              ->type_name("WEIGHT");
}

// How the render runs: threads, lane width and seed.
inline void add_engine_flags(CLI::App& render, RenderArgs& args, RawRenderFlags& raw) {
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
}

// What else a render writes, and what it says as it goes.
inline void add_report_flags(CLI::App& render, RenderArgs& args, RawRenderFlags& raw) {
  render.add_option("--stats", args.stats,
                    "Also write render statistics as JSON: timings (ms: render_ms wall time, phases_ms and "
                    "traversal_ms thread time summed over the threads, listed in thread_time_keys), settings, ray "
                    "counts by kind, Mrays/s, lane utilisation per wave, memory (bytes). Written only when "
                    "everything succeeds, as --output (a regular file)")
      ->type_name("FILE.json")
      ->check(kNonEmptyFileName);
  raw.aov_option = render.add_option("--aov", raw.aov,
                                     "Extra channels through each pixel centre, a comma list of depth (Z: distance, "
                                     "inf on a miss), normal (N.X N.Y N.Z), id (id: the primitive's number in the "
                                     "whole scene, each kind's list in the file in the order spheres, planes, "
                                     "triangles, polygons, cones, then each instance's triangles; kind: its "
                                     "kind; -1 on a miss; exact in the EXR's float channels up to 2^24); each at "
                                     "most once; needs an .exr output")
                       ->type_name("LIST");
  render.add_flag("-q,--quiet", args.quiet,
                  "No progress (a bar with the time left on a terminal, else a line every 5 s; on a terminal, "
                  "reading or building the scene for over a second shows that step) and no summary line (errors "
                  "are still reported)");
}

// Procedures, surfaces, textures, meshes, paths and the view.
inline void add_procedure_flags(CLI::App& render, RenderArgs& args, RawRenderFlags& raw) {
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
  raw.texture_filter_option =
      render.add_option("--texture-filter", raw.texture_filter,
                        "box: textures filtered over each sample's footprint, from ray differentials carried "
                        "through reflection and refraction (checkers box-filtered, images MIP-mapped); none: point "
                        "sampling. Default: box")
          ->type_name("FILTER");
  raw.crease_angle_option = add_crease_angle_flag(render, raw.crease_angle);
  add_strict_flag(render, args.options.strict);
  add_allow_outside_paths_flag(render, args.options.allow_outside_paths);
  add_camera_flags(render, raw.camera);
}

inline void add_render_flags(CLI::App& render, RenderArgs& args, RawRenderFlags& raw) {
  add_file_flags(render, args);
  add_image_flags(render, raw);
  add_engine_flags(render, args, raw);
  add_report_flags(render, args, raw);
  add_procedure_flags(render, args, raw);
}

// What `quiver view` serves, as parsed.
struct ViewFlags {
  int port = 0;
  std::string bind = "127.0.0.1";
};

// The render flags but the outputs' (a view renders into the page; -o names
// the copied command's image), and where to listen.
inline void add_view_flags(CLI::App& view, RenderArgs& args, RawRenderFlags& raw, ViewFlags& flags) {
  add_scene_argument(view, args);
  view.add_option("-o,--output", args.output,
                  "The image file named in the copied 'quiver render' command (nothing is written by the viewer; "
                  "its Download button saves the same PNG). Default: <scene name>.png, quiver.png for the built-in "
                  "scene")
      ->type_name("FILE")
      ->check(kNonEmptyFileName);
  add_image_flags(view, raw);
  add_engine_flags(view, args, raw);
  add_procedure_flags(view, args, raw);
  view.add_option("--port", flags.port, "TCP port to listen on, 1..65535. Default: a free one")
      ->type_name("PORT")
      ->check(CLI::Range(1, 65535));
  view.add_option("--bind", flags.bind,
                  "Address to listen on. Default: 127.0.0.1 (this machine only); any other address lets other "
                  "machines reach the viewer (with the token), and is warned about")
      ->type_name("ADDRESS");
}

// The flags that were given, parsed into the optional fields (UsageError).
inline void collect_render_flags(const RawRenderFlags& raw, RenderOptions& options) {
  if (raw.width_option->count()) options.width = raw.width;
  if (raw.height_option->count()) options.height = raw.height;
  if (raw.max_depth_option->count()) options.max_depth = raw.max_depth;
  if (raw.min_weight_option->count()) options.min_weight = raw.min_weight;
  if (raw.crease_angle_option->count()) options.crease_angle = raw.crease_angle;
  options.camera = given_camera_flags(raw.camera);
  if (raw.aa_option->count()) options.aa = quiver::parse_aa_flag(raw.aa);
  if (raw.simd_option->count()) options.simd = raw.simd;
  if (raw.aov_option != nullptr && raw.aov_option->count()) options.aov = quiver::parse_aov_list(raw.aov);
  if (raw.texture_filter_option->count()) options.filter_textures = quiver::parse_texture_filter(raw.texture_filter);
  if (raw.preset_option->count() && raw.preset != "spd") {
    throw UsageError("--preset: expected spd, found '" + raw.preset + "'");
  }
  options.preset_spd = raw.preset_option->count() > 0;
  if (raw.seed_option->count()) options.seed = quiver::parse_seed(raw.seed);
}

}  // namespace quiver::cli
