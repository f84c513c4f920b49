// quiver-mpi: one image rendered by every rank of an MPI job
// (docs/MPI.md). Rank 0 reads and builds the scene and broadcasts it to the
// other ranks (app/scene_broadcast.h); it keeps the tile queue
// (app/tile_schedule.h), hands tiles out to the other ranks and renders some
// itself, places every tile as it arrives, checkpoints them
// (app/checkpoint.h) and writes the outputs as `quiver render` does. The
// image is the same bits as `quiver render`'s.
// Needs MPI initialised (MPI_THREAD_FUNNELED: only the calling thread makes
// MPI calls).
#pragma once

#include <string>

#include "app/render_job.h"

namespace quiver {

// The render flags plus quiver-mpi's own.
struct MpiRenderArgs {
  RenderArgs render;
  std::string checkpoint;             // empty: <output>.checkpoint
  double checkpoint_interval_s = 5.0;
  bool resume = false;
  bool tile_times = false;            // the stats JSON lists each tile's time
};

inline constexpr double kMaxCheckpointInterval = 86400.0;

// Every rank calls it with the same arguments; returns the exit code, the
// same on every rank. Errors are printed once, by rank 0.
int run_mpi_render(const MpiRenderArgs& args);

// Every rank's verdict on a step: the highest exit code of all ranks; when
// it is not 0, rank 0 prints the message of the lowest failing rank once
// ("quiver-mpi: <message>", with "rank N: " before another rank's). Collective.
int agree_on(int exit_code, const std::string& message);

}  // namespace quiver
