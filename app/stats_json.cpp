#include "app/stats_json.h"

#include "io/output_file.h"

#include <charconv>
#include <stdexcept>
#include <system_error>

#include <nlohmann/json.hpp>

namespace quiver {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

[[noreturn]] void fail(const fs::path& path, const std::string& message) {
  throw std::runtime_error(path.string() + ": " + message);
}

// active / issued; null when nothing was issued.
json ratio(std::uint64_t active, std::uint64_t issued) {
  if (issued == 0) return nullptr;
  return double(active) / double(issued);
}

json lane_entry(const WaveLanes& lanes) {
  return {{"active", lanes.active},
          {"issued_compacted", lanes.issued_compacted},
          {"issued_uncompacted", lanes.issued_uncompacted},
          {"utilization_compacted", ratio(lanes.active, lanes.issued_compacted)},
          {"utilization_uncompacted", ratio(lanes.active, lanes.issued_uncompacted)}};
}

std::size_t framebuffer_bytes(const Framebuffer& image) {
  return bytes_of(image.rgb) + bytes_of(image.depth) + bytes_of(image.normal) + bytes_of(image.kind) +
         bytes_of(image.id);
}

json aov_names(const RenderSettings& settings) {
  json names = json::array();
  if (settings.aov_depth) names.push_back("depth");
  if (settings.aov_normal) names.push_back("normal");
  if (settings.aov_id) names.push_back("id");
  return names;
}

double phase_ms(std::uint64_t nanoseconds) { return double(nanoseconds) / 1e6; }

}  // namespace

json render_stats_json(const RenderResult& result, const RenderSettings& settings, const RenderStatsContext& context) {
  const TraceStats& stats = result.stats;
  const RayCounts& rays = stats.rays;

  json waves = json::array();
  WaveLanes every_wave;
  for (std::size_t depth = 0; depth < stats.waves.size(); ++depth) {
    const WaveLanes& wave = stats.waves[depth];
    json entry = lane_entry(wave);
    entry["depth"] = depth;
    waves.push_back(std::move(entry));
    every_wave.active += wave.active;
    every_wave.issued_compacted += wave.issued_compacted;
    every_wave.issued_uncompacted += wave.issued_uncompacted;
  }
  // The shading packets are the waves' packets; their active lanes are the hits.
  const WaveLanes shading{stats.shading_active, every_wave.issued_compacted, every_wave.issued_uncompacted};
  WaveLanes overall = every_wave;
  overall.active += stats.shadow.active;
  overall.issued_compacted += stats.shadow.issued_compacted;
  overall.issued_uncompacted += stats.shadow.issued_uncompacted;

  const double render_seconds = result.render_ms / 1000.0;
  return {
      {"version", context.version},
      {"scene", context.scene},
      {"output", context.output},
      {"load_ms", context.load_ms},
      {"build_ms", context.build_ms},
      {"render_ms", result.render_ms},
      {"threads", result.threads},
      {"simd", std::string(isa_name(settings.isa))},
      {"kernel_unit", std::string(kernel_unit_name(kernel_unit_for(settings.isa)))},
      {"sphere_method", result.sphere_method == SphereMethod::algebraic ? "algebraic" : "robust"},
      {"lanes", lane_width(settings.isa)},
      {"width", settings.width},
      {"height", settings.height},
      {"aa", to_string(settings.aa)},
      {"max_depth", settings.trace.max_depth},
      {"min_weight", json_float(settings.trace.min_weight)},
      {"seed", settings.trace.seed},
      {"aovs", aov_names(settings)},
      {"rays",
       {{"primary", rays.primary},
        {"eye_hit", rays.primary_hits},
        {"shadow", rays.shadow},
        {"reflection", rays.reflection},
        {"refraction", rays.refraction},
        {"total", rays.total()}}},
      {"phases_ms",
       {{"camera_and_film", phase_ms(stats.phases.camera_and_film)},
        {"intersection", phase_ms(stats.phases.intersection)},
        {"shading", phase_ms(stats.phases.shading)},
        {"shadows", phase_ms(stats.phases.shadows)}}},
      {"traversal_ms", phase_ms(stats.phases.walks())},
      // Wall time is render_ms; these add up every thread's time (about threads x render_ms).
      {"thread_time_keys", {"phases_ms", "traversal_ms"}},
      {"mrays_per_s", render_seconds > 0.0 ? json(double(rays.total()) / render_seconds / 1e6) : json(nullptr)},
      {"lane_utilization",
       {{"waves", std::move(waves)},
        {"shadow", lane_entry(stats.shadow)},
        {"shading", lane_entry(shading)},
        {"light_samples",
         {{"active", stats.light_sample_active},
          {"issued", stats.light_sample_issued},
          {"utilization", ratio(stats.light_sample_active, stats.light_sample_issued)}}},
        {"overall",
         {{"active", overall.active},
          {"issued_compacted", overall.issued_compacted},
          {"issued_uncompacted", overall.issued_uncompacted},
          {"compacted", ratio(overall.active, overall.issued_compacted)},
          {"uncompacted", ratio(overall.active, overall.issued_uncompacted)}}}}},
      {"memory_bytes",
       {{"scene", context.scene_memory_bytes},
        {"acceleration", context.acceleration_memory_bytes},
        {"framebuffer", framebuffer_bytes(result.image)}}},
  };
}

void check_stats_path(const fs::path& path) {
  if (path.empty()) fail(path, "empty file name");
  check_output_directory(path);
}

void stage_json_file(StagedOutputs& outputs, const fs::path& path, const json& value) {
  check_stats_path(path);
  outputs.stage_bytes(path, value.dump(2) + "\n");
}

double json_float(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  double nearest = 0.0;
  std::from_chars(text, end, nearest);
  return nearest;
}

}  // namespace quiver
