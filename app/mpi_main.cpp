// quiver-mpi, the MPI program: `mpirun -np N quiver-mpi [SCENE] [render
// options]` renders one image over N processes (docs/MPI.md), the same bits
// as `quiver render` with the same options. Its own flags: --checkpoint,
// --checkpoint-interval, --resume, --tile-times. Exit codes as quiver's, the
// same on every rank; errors are printed once, by rank 0.
#include "app/render_flags_cli.h"

#include <mpi.h>

#include <cstdio>
#include <iostream>
#include <string>

#include "app/mpi_render.h"

namespace {

// MPI_Finalize on every way out of main.
struct MpiSession {
  MpiSession(int& argc, char**& argv) {
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  }
  ~MpiSession() { MPI_Finalize(); }
  int provided = 0, rank = 0;
};

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  if (mpi.provided < MPI_THREAD_FUNNELED) {
    return quiver::agree_on(quiver::kExitFailure, "this MPI library cannot run threads beside MPI (MPI_THREAD_FUNNELED)");
  }

  CLI::App app{"quiver-mpi: render one image over the ranks of an MPI job (mpirun -np N quiver-mpi ...), the same "
               "image as 'quiver render' with the same options. Rank 0 alone reads and builds the scene and sends "
               "it to the other ranks; it hands out tiles, renders too, checkpoints the finished tiles and writes "
               "the outputs. Run it with --threads "
               "set to the cores each rank may use.\nExit codes: 0 success, 1 failure (bad scene, render or write "
               "error), 2 usage error, 130/143 interrupted by SIGINT/SIGTERM (the finished tiles stay in the "
               "checkpoint; --resume continues).",
               "quiver-mpi"};
  app.set_version_flag("--version", std::string("quiver-mpi ") + QUIVER_VERSION, "Print the version and exit");
  quiver::MpiRenderArgs args;
  quiver::cli::RawRenderFlags raw;
  quiver::cli::add_render_flags(app, args.render, raw);
  app.add_option("--checkpoint", args.checkpoint,
                 "The side file rank 0 keeps the finished tiles in, every --checkpoint-interval seconds; removed "
                 "once the outputs are written; a regular file, never a file the render reads or another output. "
                 "Default: <output>.checkpoint")
      ->type_name("FILE")
      ->check(quiver::cli::kNonEmptyFileName);
  app.add_option("--checkpoint-interval", args.checkpoint_interval_s,
                 "Seconds between checkpoints, (0, 86400]; a killed job loses at most the tiles of the last "
                 "interval. Default: 5")
      ->type_name("SECONDS");
  app.add_flag("--resume", args.resume,
               "Read the checkpoint and render only the tiles it lacks; it must be from the same scene files, "
               "settings and version, else it is refused");
  app.add_flag("--tile-times", args.tile_times,
               "The stats JSON also lists each tile's render time (tile_ms, in tile order, row by row; null for "
               "tiles resumed from the checkpoint) and the estimated cost the queue was ordered by "
               "(tile_cost_estimate, rays)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) {  // --help, --version
      if (mpi.rank == 0) app.exit(error);
      return 0;
    }
    return quiver::agree_on(quiver::kExitUsage,
                            std::string(error.what()) + "\nRun 'quiver-mpi --help' for usage.");
  }
  int code = 0;
  std::string message;
  try {
    quiver::cli::collect_render_flags(raw, args.render.options);
  } catch (const quiver::UsageError& error) {
    code = quiver::kExitUsage;
    message = error.what();
  }
  if ((code = quiver::agree_on(code, message)) != 0) return code;
  return quiver::run_mpi_render(args);
}
