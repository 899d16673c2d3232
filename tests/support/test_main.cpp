// The GoogleTest main of Dermis' test executables: each test process gets a cache folder
// of its own (core/cache_dir.h reads $XDG_CACHE_HOME), made empty here and removed at the
// end, so that no test reads or writes the user's ~/.cache/dermis and no verdict depends
// on what an earlier run left there. The folder lies under $DERMIS_TEST_CACHE_ROOT (ctest
// sets it to <build>/test-cache), else under the system's temporary folder. Tests of the
// cache itself choose their own folders.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace {

std::filesystem::path make_fresh_cache_dir() {
  const char* root_env = std::getenv("DERMIS_TEST_CACHE_ROOT");
  const std::filesystem::path root =
      root_env && *root_env ? std::filesystem::path(root_env) : std::filesystem::temp_directory_path();
  std::error_code ec;
  std::filesystem::create_directories(root, ec);
  std::string pattern = (root / "gtest-XXXXXX").string();
  if (!mkdtemp(pattern.data())) return {};
  return pattern;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  const std::filesystem::path cache = make_fresh_cache_dir();
  // No folder could be made: no cache at all (the renderer builds its tables), never the user's.
  setenv("XDG_CACHE_HOME", cache.empty() ? "/dev/null/no-cache" : cache.c_str(), 1);
  const int status = RUN_ALL_TESTS();
  std::error_code ec;
  if (!cache.empty()) std::filesystem::remove_all(cache, ec);
  return status;
}
