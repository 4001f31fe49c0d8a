#pragma once
// End-to-end tests run the real sylva-bench executable (SYLVA_BENCH_EXE, set by CMakeLists.txt for
// every test in this folder) in a fresh folder per test and read what it printed.
#include <sylva/core/atomic_file.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

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

// Runs `sylva-bench --suite SUITE` at CI size (64x36, `frames` frames, no warm-up, no shadows)
// plus `extra` (already quoted), with its results in DIR/out and its output in DIR/log.txt.
inline int run_small_suite(const std::string& suite, int frames, const std::string& extra,
                           const std::filesystem::path& dir, std::string& output) {
  return run_bench("--suite " + suite + " --size 64x36 --frames " + std::to_string(frames) +
                       " --warmup 0 --set render.shadows.enabled=false " + extra + " --out '" + (dir / "out").string() + "'",
                   dir / "log.txt", output);
}

// An empty folder <temp>/<prefix>-<pid>/<name>, for one test's outputs.
inline std::filesystem::path fresh_test_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The lines of `output` starting with `prefix` (the row lines of a suite that prints rows).
inline std::vector<std::string> lines_of(const std::string& output, const std::string& prefix) {
  std::vector<std::string> found;
  std::size_t at = 0;
  while (at < output.size()) {
    const std::size_t end = output.find('\n', at);
    const std::string line = output.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (line.rfind(prefix, 0) == 0) found.push_back(line);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return found;
}

// The number after "key=" in a row line (NaN when absent).
inline double field(const std::string& line, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(line, m, std::regex(key + "=([-0-9.e+]+)"))) return std::nan("");
  return std::stod(m[1].str());
}

}  // namespace sylva::bench::testing
