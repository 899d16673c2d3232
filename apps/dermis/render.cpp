// dermis render SCENE [--spp N] [--threads N] [--seed S] [--sampler sobol|independent] [-o OUT] [--res WxH]
// [--time-limit SEC] The body is render_job.cpp, shared with dermis-mpi.
#include "commands.h"
#include "render_job.h"

namespace dermis::app {

void register_render(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand("render", "Render a pbrt-v4 scene to EXR (and a PNG preview)");
  add_render_options(*cmd, *args);
  cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}

}  // namespace dermis::app
