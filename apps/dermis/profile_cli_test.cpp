// `dermis profile` rejects bad options with exit status 2 and a message (the real binary).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace {

std::pair<int, std::string> run_profile_command(const std::string& args) {
  const std::string cmd = std::string(DERMIS_BINARY) + " profile " + args + " 2>&1";
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {-1, out};
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

TEST(ProfileCli, RejectsBadOptionsWithExit2) {
  for (const char* args : {"", "--fit-error --albedos 0.5,1.2", "--fit-error --albedos 0", "--fit-error --eta 0",
                           "--fit-error --paths 5", "--fit-error --paths -3", "--fit-error --bins 1",
                           "--fit-error --seed -1", "--fit-error --albedos x", "--no-such-option"}) {
    const auto [status, output] = run_profile_command(args);
    EXPECT_EQ(status, 2) << args << ": " << output;
    EXPECT_FALSE(output.empty()) << args;
  }
}

}  // namespace
