// The subcommands of the `dermis` command line, one file each. Each registers
// itself on the app and writes its exit status to `exit_code` when it runs.
#pragma once

#include <CLI/CLI.hpp>

namespace dermis::app {

void register_render(CLI::App& app, int& exit_code);
void register_compare(CLI::App& app, int& exit_code);
void register_halfspace(CLI::App& app, int& exit_code);
void register_profile(CLI::App& app, int& exit_code);
void register_study(CLI::App& app, int& exit_code);

}  // namespace dermis::app
