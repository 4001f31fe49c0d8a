#pragma once
// Runs a command line through the shell for the apps' end-to-end tests (player, editor): its
// exit code and everything it wrote (stdout and stderr together). Header-only; POSIX.

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace sylva::test {

struct RunResult {
  int exit_code = -1;   // -1 when the command could not be started or did not exit normally
  std::string output;   // stdout and stderr together
};

inline RunResult run_command(const std::string& executable, const std::string& args) {
  const std::string command = executable + " " + args + " 2>&1";
  RunResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe)) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace sylva::test
