// dermis: a renderer for translucent materials. See README.md.
#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"Dermis: a path tracer for translucent materials (subsurface scattering)"};
  app.set_version_flag("--version", std::string("dermis ") + DERMIS_VERSION);
  app.require_subcommand(1);
  int exit_code = 0;
  dermis::app::register_render(app, exit_code);
  dermis::app::register_compare(app, exit_code);
  dermis::app::register_halfspace(app, exit_code);
  dermis::app::register_profile(app, exit_code);
  dermis::app::register_study(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    // Usage errors exit with status 2, like every other bad input.
    return rc == 0 ? 0 : 2;
  }
  return exit_code;
}
