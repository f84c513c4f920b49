// What each quiver-mpi rank reports to rank 0 at the end of a render, as
// bytes for one MPI message, and the "mpi" part of the stats JSON merged
// from every rank's report. No MPI here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "integrator/trace_stats.h"

namespace quiver {

struct RankReport {
  int threads = 0;
  std::uint64_t tiles = 0;           // first results rank 0 placed (rank 0: counted by rank 0)
  std::uint64_t tiles_repeated = 0;  // tiles rendered again after another rank's result won
  double render_ms = 0.0;            // the rank's wall time from its first tile request to its last tile
  double busy_ms = 0.0;              // its threads' time in tiles, summed
  // Its wall time from its start to its first tile request: the scene read
  // and built (rank 0) or received from rank 0, and the cost estimate.
  double start_ms = 0.0;
  TraceStats stats;                  // every tile it rendered
};

std::vector<std::byte> encode_rank_report(const RankReport& report);
// Throws std::invalid_argument for bytes encode_rank_report did not make.
RankReport decode_rank_report(std::span<const std::byte> bytes);

// What rank 0 knows of the whole job.
struct MpiJobSummary {
  std::size_t tiles = 0, tiles_resumed = 0;
  double render_ms = 0.0;      // rank 0's wall time from the first tile to the last
  double estimate_ms = 0.0;    // the cost estimate before the tiles go out
  double checkpoint_ms = 0.0;  // writing checkpoints
  std::size_t checkpoints = 0; // batches appended
  std::vector<RankReport> ranks;
};

// idle_ms of a rank: threads x job render_ms - busy_ms (at least 0).
// efficiency: every rank's busy_ms over (every rank's threads x the job's render_ms).
// Keys: ranks, tiles, tiles_resumed, tiles_rendered, tiles_repeated,
// render_ms, estimate_ms, checkpoint_ms, checkpoints, efficiency,
// per_rank [{rank, threads, tiles, tiles_repeated, start_ms, render_ms,
// busy_ms, idle_ms, rays {primary, shadow, reflection, refraction, total}}].
nlohmann::json mpi_stats_json(const MpiJobSummary& job);

// Every rank's stats summed.
TraceStats merged_trace_stats(const std::vector<RankReport>& ranks);

}  // namespace quiver
