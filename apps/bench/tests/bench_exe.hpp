#pragma once
// End-to-end tests run the real sylva-bench executable (SYLVA_BENCH_EXE, set by CMakeLists.txt for
// every test in this folder) in a fresh folder per test and read what it printed.
#include <sylva/core/atomic_file.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace sylva::bench::testing {

struct RunResult {
  int exit_code = -1;  // -1 when the process did not exit normally
  std::string output;  // stdout and stderr
};

// Runs `sylva-bench ARGS` (ARGS already quoted for the shell) with its output in `log`.
inline RunResult run_bench(const std::string& args, const std::filesystem::path& log) {
  const std::string cmd = std::string(SYLVA_BENCH_EXE) + " " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto text = read_file(log);
  if (text.ok()) r.output = *text;
  return r;
}

// The same, as exit code with the output in `output`.
inline int run_bench(const std::string& args, const std::filesystem::path& log, std::string& output) {
  RunResult r = run_bench(args, log);
  output = std::move(r.output);
  return r.exit_code;
}

// An empty folder <temp>/<prefix>-<pid>/<name>, for one test's outputs.
inline std::filesystem::path fresh_test_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace sylva::bench::testing
