#pragma once
// Running the shipped sylva-bake (SYLVA_BAKE_EXE, set by the test target) as a child process,
// for the tests that check it from the outside: exit status, output files and log text.

#include <sylva/core/atomic_file.hpp>

#include <fmt/format.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

extern char** environ;

namespace sylva::bake::testing {

namespace fs = std::filesystem;

// A folder of this process's own (ctest runs test cases side by side).
inline fs::path test_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / fmt::format("sylva_bake_{}_{}", ::getpid(), name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Starts sylva-bake with stdout and stderr into `log`; -1 when it cannot be started.
inline pid_t spawn_bake(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> all{SYLVA_BAKE_EXE};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

// Exit status, or 128 + signal; -1 when `pid` is not a child.
inline int wait_for(pid_t pid) {
  int status = 0;
  if (pid <= 0 || waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

inline std::string text_of(const fs::path& p) {
  Result<std::string> r = read_file(p);
  return r ? r.value() : std::string();
}

inline int run_bake(const std::vector<std::string>& args, const fs::path& log) { return wait_for(spawn_bake(args, log)); }

}  // namespace sylva::bake::testing
