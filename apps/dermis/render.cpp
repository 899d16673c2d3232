// dermis render SCENE
#include "commands.h"

namespace dermis::app {

void register_render(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("render", "Render a pbrt-v4 scene");
  cmd->callback([&exit_code] { exit_code = 2; });
}

}  // namespace dermis::app
