#pragma once
// Running the rockdd command line (or any shell command) from a test.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace rockdd::test {

/// What a command printed (stdout and stderr together) and its exit status.
struct Invocation {
  int exit_code = -1;
  std::string output;
};

/// Runs a shell command line, stdout and stderr together.
inline Invocation run_shell(const std::string& command) {
  Invocation inv;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) inv.output += buffer.data();
  const int status = pclose(pipe);
  inv.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return inv;
}

/// Runs `rockdd ARGS` in `cwd`; with `timeout_s` > 0 it is killed after that many seconds
/// (exit status 124), so that a hang fails the test instead of stalling the suite.
inline Invocation rockdd_cli(const std::string& args, const std::filesystem::path& cwd,
                             int timeout_s = 0) {
  const std::string limit =
      timeout_s > 0 ? "timeout -k 5 " + std::to_string(timeout_s) + " " : std::string();
  return run_shell("cd '" + cwd.string() + "' && " + limit + "'" + ROCKDD_BINARY + "' " + args +
                   " 2>&1");
}

}  // namespace rockdd::test
