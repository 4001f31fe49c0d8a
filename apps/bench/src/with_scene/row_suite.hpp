#pragma once
// What the suites that print rows instead of a sweep report share (--suite species,
// species_suite.hpp; --suite stream, stream_suite.hpp): building one of their scenes with the
// user's --set assignments, and results.csv (kind,name,count,value,unit; one row per line,
// written atomically).

#include "bench_target.hpp"
#include "sweep.hpp"

#include <glm/glm.hpp>

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

namespace sylva::bench {

struct SuiteRow {
  std::string kind, name;
  double count = 0.0;
  double value = 0.0;
  std::string unit;
};

// The scene's target (scene JSON `scene`, named `source` in messages) with `settings` applied,
// not yet built. An unknown path or bad value: its error, naming "--set path=value".
Result<std::unique_ptr<BenchTarget>> make_scene_target(const std::string& scene, const std::string& source,
                                                       const std::vector<Assignment>& settings);

// A built scene and the wall time its build took [ms]: factory, --set, prepare (files,
// textures, bakes) and glFinish.
struct BuiltTarget {
  std::unique_ptr<BenchTarget> target;
  double build_ms = 0.0;
};
Result<BuiltTarget> build_scene_target(const std::string& scene, const std::string& source, glm::ivec2 size,
                                       const std::vector<Assignment>& settings);

// A temporary file or folder a suite writes (a bake, a cache), removed with everything under it
// when the suite ends, whatever way it ends.
class ScratchPath {
 public:
  explicit ScratchPath(std::filesystem::path path) : path_(std::move(path)) {}
  ~ScratchPath() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchPath(const ScratchPath&) = delete;
  ScratchPath& operator=(const ScratchPath&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Writes `rows` to `dir`/results.csv (the folder made if needed) and says so on `out`.
Status write_rows_csv(const std::vector<SuiteRow>& rows, const std::filesystem::path& dir, std::ostream& out);

}  // namespace sylva::bench
