// Runs every hostile case (cases_*.cpp) through the shipped executables: each gets a fresh
// folder with its generated files, and must exit with its code (never a signal, never a hang),
// say the words its row names, leave the user's input files byte for byte as they were and
// leave no temporary files behind; a run that exits 0 with a screenshot must have drawn a picture.

#include "hostile_case.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>

#include <gtest/gtest.h>

#include "run_command.hpp"

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

namespace sylva::hostile {

// ctest shows the case's name, not a dump of its bytes (found by argument-dependent lookup).
void PrintTo(const HostileCase& c, std::ostream* os);
void PrintTo(const HostileCase& c, std::ostream* os) { *os << c.name; }

namespace {

namespace fs = std::filesystem;

// A run longer than this is a hang (the slowest case, a 16384^2 map, takes a few seconds).
constexpr int kTimeoutSeconds = 90;

std::string executable(Tool tool) {
  switch (tool) {
    case Tool::kPlayer: return SYLVA_PLAYER_EXE;
    case Tool::kEditor: return SYLVA_EDITOR_EXE;
    case Tool::kBench: return SYLVA_BENCH_EXE;
  }
  return "";
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) text.replace(at, from.size(), to);
  return text;
}

// The content modules this player was built with (the `lean` preset leaves some out).
const std::set<std::string>& player_modules() {
  static const std::set<std::string> modules = [] {
    std::set<std::string> names;
    const auto listed = test::run_command(SYLVA_PLAYER_EXE, "--list-modules");
    std::istringstream lines(listed.output);
    for (std::string line; std::getline(lines, line);) names.insert(line.substr(0, line.find(' ')));
    return names;
  }();
  return modules;
}

fs::path case_folder(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sylva_hostile_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(f.good()) << path;
}

std::string clipped(const std::string& output) {
  constexpr std::size_t kMax = 3000;
  return output.size() <= kMax ? output : output.substr(0, kMax) + "\n[... " + std::to_string(output.size() - kMax) + " more bytes]";
}

std::string describe_exit(int code) {
  if (code == -1) return "killed by a signal (crash)";
  if (code == 124 || code == 137) return "did not finish within " + std::to_string(kTimeoutSeconds) + " s (hang)";
  return "exit code " + std::to_string(code);
}

// Temporary files a writer forgot (atomic writes name them ".<stem>.<pid>-<n>.tmp<ext>").
std::vector<std::string> leftover_temporaries(const fs::path& folder) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (name.rfind('.', 0) == 0 && name.find(".tmp") != std::string::npos) found.push_back(e.path().string());
  }
  return found;
}

void expect_picture(const fs::path& file) {
  auto image = read_image(file);
  ASSERT_TRUE(image.ok()) << "the run exited 0 but its screenshot does not read back: " << image.error().message;
  float lo = image->at(0, 0), hi = lo;
  for (int y = 0; y < image->height(); ++y)
    for (int x = 0; x < image->width(); ++x)
      for (int c = 0; c < std::min(image->channels(), 3); ++c) {
        lo = std::min(lo, image->at(x, y, c));
        hi = std::max(hi, image->at(x, y, c));
      }
  EXPECT_GT(hi - lo, 0.02f) << file << " is one flat colour (" << lo << "): exit 0 with a broken picture";
}

class HostileRun : public ::testing::TestWithParam<HostileCase> {};

TEST_P(HostileRun, FailsCleanly) {
  const HostileCase& c = GetParam();
  const std::string exe = executable(c.tool);
  if (exe.empty()) GTEST_SKIP() << "this build has no such executable";
  if (!c.needs_module.empty() && player_modules().count(c.needs_module) == 0) {
    GTEST_SKIP() << "built without the " << c.needs_module << " module";
  }
  const fs::path dir = case_folder(c.name);
  std::map<fs::path, std::string> inputs;
  std::map<fs::path, std::pair<std::uintmax_t, fs::file_time_type>> sparse;  // size and time
  for (const InputFile& f : c.files) {
    const fs::path path = dir / f.name;
    if (f.name.ends_with('/')) {
      fs::create_directories(path);
      continue;
    }
    if (f.sparse_size > 0) {
      ASSERT_NO_FATAL_FAILURE(write_bytes(path, f.bytes()));
      fs::resize_file(path, f.sparse_size);
      sparse[path] = {fs::file_size(path), fs::last_write_time(path)};
      continue;
    }
    inputs[path] = f.bytes();
    ASSERT_NO_FATAL_FAILURE(write_bytes(path, inputs[path]));
  }

  const std::string headless = c.tool == Tool::kBench ? "" : " --headless";
  const std::string args = replace_all(c.args, "{scenes}", SYLVA_SCENES_DIR);
  const std::string command = "cd '" + dir.string() + "' && timeout -k 5 " + std::to_string(kTimeoutSeconds) + " " + exe;
  const auto run = test::run_command(command, args + headless);
  const std::string where = "$ " + exe + " " + args + headless + "\n" + clipped(run.output);

  EXPECT_EQ(describe_exit(run.exit_code), describe_exit(c.exit_code)) << where;
  for (const std::string& word : c.words) {
    EXPECT_NE(run.output.find(word), std::string::npos) << "the message must contain \"" << word << "\"\n" << where;
  }
  for (const std::string& word : c.absent) {
    EXPECT_EQ(run.output.find(word), std::string::npos) << "the message must not contain \"" << word << "\"\n" << where;
  }
  // A user's file given as input is never modified.
  for (const auto& [path, bytes] : inputs) {
    auto now = read_file(path);
    ASSERT_TRUE(now.ok()) << path << " is gone after the run\n" << where;
    EXPECT_TRUE(*now == bytes) << path << " was modified by the run\n" << where;
  }
  for (const auto& [path, before] : sparse) {
    std::error_code ec;
    EXPECT_EQ(fs::file_size(path, ec), before.first) << path << " changed size in the run\n" << where;
    EXPECT_TRUE(fs::last_write_time(path, ec) == before.second) << path << " was written by the run\n" << where;
  }
  EXPECT_EQ(leftover_temporaries(dir), std::vector<std::string>{}) << where;
  if (run.exit_code == 0 && !c.picture.empty()) expect_picture(dir / c.picture);
  if (!HasFailure()) fs::remove_all(dir);
}

std::vector<HostileCase> all_cases() {
  std::vector<HostileCase> all;
  for (auto table : {scene_file_cases, map_image_cases, elevation_raster_cases, player_command_line_cases, output_path_cases,
                     editor_script_cases, bench_cases, species_file_cases, plant_file_cases}) {
    for (HostileCase& c : table()) all.push_back(std::move(c));
  }
  return all;
}

INSTANTIATE_TEST_SUITE_P(Inputs, HostileRun, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<HostileCase>& info) { return info.param.name; });

}  // namespace
}  // namespace sylva::hostile
