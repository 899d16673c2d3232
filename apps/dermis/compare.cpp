// dermis compare A.exr B.exr [--diff OUT.exr]
#include "commands.h"

namespace dermis::app {

void register_compare(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("compare", "Compare two images: per-channel mean, RMSE, relative MSE");
  cmd->callback([&exit_code] { exit_code = 2; });
}

}  // namespace dermis::app
