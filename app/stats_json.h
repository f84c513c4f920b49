// The statistics of one render as JSON (`quiver render --stats FILE`):
// timings, settings, ray counts by kind, lane utilisation per wave and the
// memory of each structure. Written atomically (a temporary file beside the
// target, renamed over it after a successful close), so a failure leaves no
// file behind and an existing file as it was.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "integrator/render.h"
#include "io/output_file.h"

namespace quiver {

// What the render result does not know about itself.
struct RenderStatsContext {
  std::string version;  // of quiver
  std::string scene;   // the scene file, or "built-in"
  std::string output;  // the image file
  double load_ms = 0.0;
  double build_ms = 0.0;
  std::size_t scene_memory_bytes = 0;         // Scene::memory_bytes()
  std::size_t acceleration_memory_bytes = 0;  // Scene::acceleration_bytes()
};

// Keys: version, scene, output, load_ms, build_ms, render_ms, threads, simd,
// kernel_unit, sphere_method (algebraic or robust, chosen per scene), lanes, width, height, aa, max_depth, min_weight, seed,
// aovs; rays {primary, eye_hit, shadow, reflection, refraction, total};
// phases_ms {camera_and_film, intersection, shading, shadows} (thread
// time summed over threads, integrator/trace_stats.h); traversal_ms (the
// part of intersection and shadows inside the BVH walks and kernels, same
// thread time);
// mrays_per_s (total rays / render seconds / 1e6; null for a zero time);
// lane_utilization {waves: [{depth, active, issued_compacted,
// issued_uncompacted, utilization_compacted, utilization_uncompacted}],
// shadow: {the same without depth}, shading: {the same, for the packets
// that shade the hits: active = lanes with a hit}, light_samples: {active,
// issued, utilization} (lanes casting a shadow ray per light sample
// iteration), overall: {active, issued_compacted, issued_uncompacted,
// compacted, uncompacted}} where utilisation is active / issued (null when
// nothing was issued) and overall sums every wave and the shadow rays;
// memory_bytes {scene, acceleration (the BVHs),
// framebuffer}.
nlohmann::json render_stats_json(const RenderResult& result, const RenderSettings& settings,
                                 const RenderStatsContext& context);

// A float for JSON: the double nearest its shortest round-trip decimal, so
// 0.02f prints as 0.02, not 0.019999999552965164, and reads back the same.
double json_float(float value);

// Checks, before rendering, that path can be written: an existing parent
// directory and not a directory itself. Throws std::runtime_error("<path>: ...").
void check_stats_path(const std::filesystem::path& path);

// Writes json (indented) to a temporary staged in outputs for path.
// Throws std::runtime_error ("<path>: <message>") on failure.
void stage_json_file(StagedOutputs& outputs, const std::filesystem::path& path, const nlohmann::json& json);

}  // namespace quiver
