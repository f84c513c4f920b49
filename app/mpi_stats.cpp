#include "app/mpi_stats.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace quiver {

namespace {

constexpr std::uint64_t kReportVersion = 3;

void put(std::vector<std::uint64_t>& out, const WaveLanes& lanes) {
  out.insert(out.end(), {lanes.active, lanes.issued_compacted, lanes.issued_uncompacted});
}

std::uint64_t double_bits(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

double bits_double(std::uint64_t bits) {
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace

std::vector<std::byte> encode_rank_report(const RankReport& r) {
  const TraceStats& s = r.stats;
  std::vector<std::uint64_t> words{kReportVersion,
                                   std::uint64_t(r.threads),
                                   r.tiles,
                                   r.tiles_repeated,
                                   double_bits(r.render_ms),
                                   double_bits(r.busy_ms),
                                   double_bits(r.start_ms),
                                   s.rays.primary,
                                   s.rays.primary_hits,
                                   s.rays.shadow,
                                   s.rays.reflection,
                                   s.rays.refraction,
                                   s.phases.camera_and_film,
                                   s.phases.intersection,
                                   s.phases.shading,
                                   s.phases.shadows,
                                   s.phases.shadow_walks,
                                   s.shading_active,
                                   s.light_sample_active,
                                   s.light_sample_issued};
  put(words, s.shadow);
  words.push_back(s.waves.size());
  for (const WaveLanes& wave : s.waves) put(words, wave);
  std::vector<std::byte> bytes(words.size() * sizeof(std::uint64_t));
  std::memcpy(bytes.data(), words.data(), bytes.size());
  return bytes;
}

RankReport decode_rank_report(std::span<const std::byte> bytes) {
  constexpr std::size_t kFixed = 24;
  if (bytes.size() % sizeof(std::uint64_t) != 0 || bytes.size() / sizeof(std::uint64_t) < kFixed) {
    throw std::invalid_argument("rank report: wrong size");
  }
  std::vector<std::uint64_t> w(bytes.size() / sizeof(std::uint64_t));
  std::memcpy(w.data(), bytes.data(), bytes.size());
  if (w[0] != kReportVersion) throw std::invalid_argument("rank report: unknown version");
  RankReport r;
  r.threads = int(w[1]);
  r.tiles = w[2];
  r.tiles_repeated = w[3];
  r.render_ms = bits_double(w[4]);
  r.busy_ms = bits_double(w[5]);
  r.start_ms = bits_double(w[6]);
  TraceStats& s = r.stats;
  s.rays = {w[7], w[8], w[9], w[10], w[11]};
  s.phases = {w[12], w[13], w[14], w[15], w[16]};
  s.shading_active = w[17];
  s.light_sample_active = w[18];
  s.light_sample_issued = w[19];
  s.shadow = {w[20], w[21], w[22]};
  const std::uint64_t waves = w[23];
  if (waves > (w.size() - kFixed) / 3 || w.size() != kFixed + 3 * waves) {
    throw std::invalid_argument("rank report: wrong wave count");
  }
  for (std::size_t i = 0; i < waves; ++i) s.waves.push_back({w[kFixed + 3 * i], w[kFixed + 3 * i + 1], w[kFixed + 3 * i + 2]});
  return r;
}

TraceStats merged_trace_stats(const std::vector<RankReport>& ranks) {
  TraceStats total;
  for (const RankReport& r : ranks) total.add(r.stats);
  return total;
}

nlohmann::json mpi_stats_json(const MpiJobSummary& job) {
  using nlohmann::json;
  json per_rank = json::array();
  double busy = 0.0, capacity = 0.0;
  std::uint64_t rendered = 0, repeated = 0;
  for (std::size_t i = 0; i < job.ranks.size(); ++i) {
    const RankReport& r = job.ranks[i];
    const double available = double(r.threads) * job.render_ms;
    busy += r.busy_ms;
    capacity += available;
    rendered += r.tiles;
    repeated += r.tiles_repeated;
    const RayCounts& rays = r.stats.rays;
    per_rank.push_back({{"rank", i},
                        {"threads", r.threads},
                        {"tiles", r.tiles},
                        {"tiles_repeated", r.tiles_repeated},
                        {"start_ms", r.start_ms},
                        {"render_ms", r.render_ms},
                        {"busy_ms", r.busy_ms},
                        {"idle_ms", std::max(0.0, available - r.busy_ms)},
                        {"rays",
                         {{"primary", rays.primary},
                          {"shadow", rays.shadow},
                          {"reflection", rays.reflection},
                          {"refraction", rays.refraction},
                          {"total", rays.total()}}}});
  }
  return {{"ranks", job.ranks.size()},
          {"tiles", job.tiles},
          {"tiles_resumed", job.tiles_resumed},
          {"tiles_rendered", rendered},
          {"tiles_repeated", repeated},
          {"render_ms", job.render_ms},
          {"estimate_ms", job.estimate_ms},
          {"checkpoint_ms", job.checkpoint_ms},
          {"checkpoints", job.checkpoints},
          {"efficiency", capacity > 0.0 ? json(busy / capacity) : json(nullptr)},
          {"per_rank", std::move(per_rank)}};
}

}  // namespace quiver
