#pragma once
// Collects per-frame statistics during a run and writes the --stats JSON:
//   {"frames", "size", "cpu_ms": {...}, "gpu_ms": {...}, "passes": {...}, "modules": {...}}
// where the timing objects are core SampleSummary records (count, mean, p50, p99, ...).

#include <sylva/core/result.hpp>
#include <sylva/render/queries.hpp>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace sylva::player {

class FrameRecorder {
 public:
  // One frame's CPU time [ms] measured by the caller.
  void add_cpu_ms(double ms) { cpu_ms_.push_back(ms); }
  // A completed GPU frame record from the profiler (arrives a few frames late).
  void add_gpu_frame(const render::FrameStats& frame);
  // Module-level facts (for example the ground's triangle count), copied into "modules".
  void set_module_info(const std::string& module, nlohmann::json info) { modules_[module] = std::move(info); }

  nlohmann::json to_json(int frames, glm::ivec2 size) const;
  // Writes atomically (core write_file_atomic).
  Status write(const std::filesystem::path& path, int frames, glm::ivec2 size) const;

 private:
  std::vector<double> cpu_ms_;
  std::vector<double> gpu_ms_;
  std::map<std::string, std::vector<double>> pass_gpu_ms_;
  std::map<std::string, render::PassStats> pass_last_;
  std::uint64_t last_gpu_frame_ = 0;
  bool any_gpu_frame_ = false;
  std::map<std::string, nlohmann::json> modules_;
};

}  // namespace sylva::player
