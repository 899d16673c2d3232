// The render command's body, shared by `dermis render` (one process) and
// `dermis-mpi render` (a group of MPI ranks): the same options, the same steps, the
// same messages. With a group, rank 0 alone prints and writes; the others compute
// their shares silently and report only errors that rank 0 did not have.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "dermis/render/process_group.h"
#include "dermis/render/renderer.h"
#include "dermis/scene/file_access.h"

namespace dermis::app {

struct RenderArgs {
  std::string scene;
  int spp = 0, threads = 0;
  int64_t seed = -1;
  std::string sampler;  // empty: the scene's Sampler
  std::string output, res;
  double time_limit = 0;
  double noise_threshold = -1;  // negative: the scene's Sampler "noisethreshold" (0: off)
  int min_spp = 0;              // 0: the scene's, else the default
  // Parameters given to every `subsurface` material, as pbrt-v4 parameter text, or
  // "pbrt-v4" (kPbrtV4Subsurface): the file's own method otherwise.
  std::string subsurface;
  bool error_map = false;  // write the samples and error channels (implied by adaptive sampling)
  bool quiet = false, no_png = false;
  bool spectral = false;  // --spectral
  int64_t points = 0;
  std::string save_pointcloud, load_pointcloud;
  std::string checkpoint, resume;  // film state files (render/checkpoint.h)
  double checkpoint_interval = 60;
  FileAccessOptions file_access;  // --confine, --allow-path (scene/file_access.h)
  // The live preview (preview/preview_server.h): its port (0: a free one; negative: none)
  // and address; --watch: render again when a file the scene read changes.
  int preview_port = -1;
  std::string preview_bind = "127.0.0.1";
  bool watch = false;
};

// `--subsurface pbrt-v4`: the model pbrt-v4 renders a `subsurface` material with, its
// tabulated photon-beam-diffusion profile sampled by disk projection (docs/materials.md).
inline constexpr const char* kPbrtV4Subsurface = "\"string method\" \"disk\" \"string profile\" \"photonbeam\"";

// Adds the options of `render` to a subcommand.
void add_render_options(CLI::App& cmd, RenderArgs& args);

// Thrown by run_render when this process failed where the others of its group may be
// inside a collective step: the caller must stop the whole job (dermis-mpi: MPI_Abort).
struct RankCannotContinue : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RenderJob {
  std::string program = "dermis render";  // the prefix of error messages
  ProcessGroup* group = nullptr;          // null: this process alone
  TileAssignment tile_assignment = TileAssignment::Interleaved;
  // Signals that stop the render (first one: stop and write; again: default action).
  std::vector<int> stop_signals;  // empty: SIGINT
};

// Renders; returns the exit status: 0, 2 (bad input, nothing written) or 130
// (interrupted). Every process of the group calls it with the same arguments.
int run_render(const RenderArgs& args, const RenderJob& job = {});

}  // namespace dermis::app
