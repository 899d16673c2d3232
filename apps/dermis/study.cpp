// dermis study SCENE --methods a,b --time T [...]: the equal-time comparison of subsurface
// methods with its HTML report. The study is Python (python/dermis/study.py, on top of the
// `dermis` module: NumPy arrays, matplotlib plots); this subcommand replaces itself with
// `python3 -m dermis.study ARGS...` (exec: same process, so exit status and Ctrl-C are
// the study's), the build's python/ folder first on PYTHONPATH.
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.h"

// Set by python/CMakeLists.txt; the fallbacks serve a build without the Python module.
#ifndef DERMIS_PYTHON_EXECUTABLE
#define DERMIS_PYTHON_EXECUTABLE "/usr/bin/python3"
#endif
#ifndef DERMIS_PYTHON_DIR
#define DERMIS_PYTHON_DIR ""  // then: python/ beside this executable
#endif

namespace dermis::app {

namespace {

namespace fs = std::filesystem;

fs::path self_path() {
  std::error_code ec;
  fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path("dermis") : p;
}

fs::path python_dir() {
  const std::string configured = DERMIS_PYTHON_DIR;
  return configured.empty() ? self_path().parent_path() / "python" : fs::path(configured);
}

// The package is there and holds the compiled extension (_dermis*.so).
bool module_built(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir / "dermis" / "__init__.py", ec) || !fs::exists(dir / "dermis" / "study.py", ec)) return false;
  for (const auto& entry : fs::directory_iterator(dir / "dermis", ec))
    if (entry.path().filename().string().rfind("_dermis", 0) == 0 && entry.path().extension() == ".so") return true;
  return false;
}

int run_study(const std::vector<std::string>& args) {
  const fs::path dir = python_dir();
  const std::string python = DERMIS_PYTHON_EXECUTABLE;
  if (!module_built(dir)) {
    fmt::print(stderr,
               "dermis study: the Python module `dermis` was not built (no {}/dermis/_dermis*.so).\n"
               "Build it with the rest: cmake --build build (it needs pybind11-dev and python3-dev, "
               "installed by scripts/install-deps.sh).\n",
               dir.string());
    return 2;
  }
  const char* old = std::getenv("PYTHONPATH");
  const std::string path = dir.string() + (old && *old ? std::string(":") + old : std::string());
  setenv("PYTHONPATH", path.c_str(), 1);
  // How the study names itself in its usage and in the report's command line: as the
  // user types it, `dermis study`.
  setenv("DERMIS_STUDY_PROG", (self_path().filename().string() + " study").c_str(), 1);

  std::vector<std::string> words = {python, "-m", "dermis.study"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  execv(python.c_str(), argv.data());
  fmt::print(stderr, "dermis study: cannot run {}: {}\n", python, std::strerror(errno));
  return 2;
}

}  // namespace

void register_study(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("study",
                                 "Compare subsurface methods at equal time: an HTML report with images, error maps, "
                                 "tables and convergence plots (python3 -m dermis.study; `dermis study --help`)");
  cmd->prefix_command();  // every argument goes to the study as it is
  cmd->set_help_flag();   // --help too: the study's own parser answers it
  cmd->callback([cmd, &exit_code] { exit_code = run_study(cmd->remaining()); });
}

}  // namespace dermis::app
