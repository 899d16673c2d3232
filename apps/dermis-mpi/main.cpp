// dermis-mpi: `dermis render` on the ranks of an MPI job (docs/distributed.md).
//   mpirun -n N dermis-mpi render SCENE [the options of dermis render] [--tiles interleaved|blocks]
// Every rank reads the scene; they share the pre-passes and the tiles; rank 0 prints
// the progress and writes the image, bit-identical to `dermis render` with the same seed.
#include <fmt/format.h>
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <csignal>

#include "mpi_process_group.h"
#include "render_job.h"

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  dermis::app::MpiProcessGroup group;

  CLI::App app{"Dermis over MPI: `dermis render` shared by the ranks of an MPI job"};
  app.set_version_flag("--version", std::string("dermis-mpi ") + DERMIS_VERSION);
  app.require_subcommand(1);
  dermis::app::RenderArgs args;
  std::string tiles = "interleaved";
  auto* cmd = app.add_subcommand("render", "Render a pbrt-v4 scene to EXR (and a PNG preview) on all ranks");
  dermis::app::add_render_options(*cmd, args);
  cmd->add_option("--tiles", tiles,
                  "which rank renders which 16x16 tile: interleaved (tile i on rank i mod N, the "
                  "default) or blocks (contiguous runs of tiles)")
      ->check(CLI::IsMember({"interleaved", "blocks"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // The same on every rank: rank 0 says it.
    int rc = group.is_root() ? app.exit(e) : e.get_exit_code();
    MPI_Finalize();
    return rc == 0 ? 0 : 2;  // usage errors exit with status 2, like every other bad input
  }

  dermis::app::RenderJob job;
  job.program = "dermis-mpi render";
  job.group = &group;
  job.tile_assignment = tiles == "blocks" ? dermis::TileAssignment::Blocks : dermis::TileAssignment::Interleaved;
  // Ctrl-C on mpirun reaches the ranks as SIGTERM (Open MPI 4.1 sends SIGKILL a second
  // later); SIGUSR1, which mpirun forwards, stops without that deadline.
  job.stop_signals = {SIGINT, SIGTERM, SIGUSR1};
  int exit_code = 0;
  try {
    exit_code = dermis::app::run_render(args, job);
  } catch (const dermis::app::RankCannotContinue& e) {
    // The message names the program and the problem; the others may be inside a collective.
    fmt::print(stderr, "{} (rank {}); aborting the job\n", e.what(), group.rank());
    MPI_Abort(MPI_COMM_WORLD, 2);
  } catch (const std::exception& e) {
    // Only this rank knows: stop the whole job rather than leave the others waiting.
    fmt::print(stderr, "dermis-mpi render: rank {}: {}; aborting the job\n", group.rank(), e.what());
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  MPI_Finalize();
  return exit_code;
}
