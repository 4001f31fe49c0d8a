#pragma once
// Collects per-frame statistics during a run and writes the --stats JSON:
//   {"frames", "size", "scene", "cpu_ms": {...}, "gpu_ms": {...}, "wall_ms": {...},
//    "longest_frame_ms", "timing": {"<figure>": "what it measures"},
//    "passes":  {"<pass>": {"gpu_ms": {...}, "primitives", "samples", "triangles", "draw_calls", "instances"}},
//    "modules": {"<module>": {"gpu_ms": {...}, "update_ms": {...},
//                             "passes": {"<pass>": {"gpu_ms": {...}, counters...}}, ...module facts}}}
// Three clocks, named in "timing": cpu_ms is the CPU time of update and draw submission; gpu_ms
// the GPU timer queries, which on a software rasteriser (llvmpipe) do not see the rasterisation;
// wall_ms the frame from its start to the buffer swap (window) or glFinish (headless), the figure
// to compare between machines and with other programs. Per frame, wall_ms >= cpu_ms.
// The timing objects are core SampleSummary records (count, mean, p50, p99, ...); counters are
// those of the newest complete frame. Passes and modules come from the scene's profiler scopes
// ("opaque", "opaque/grass": scene/frame_stats.hpp).

#include <sylva/core/result.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/scene/frame_stats.hpp>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace sylva::player {

class FrameRecorder {
 public:
  // One frame's CPU time of update + submission and its wall time to swap / glFinish [ms].
  void add_frame_ms(double cpu_ms, double wall_ms) {
    cpu_ms_.push_back(cpu_ms);
    wall_ms_.push_back(wall_ms);
  }
  // CPU time of each module's update() in one frame [ms].
  void add_update_ms(const std::map<std::string, double>& per_module);
  // A completed GPU frame record from the profiler (arrives a few frames late; repeats ignored).
  void add_gpu_frame(const render::FrameStats& frame);
  // Module-level facts (triangles, chunks, blades...), merged into "modules".
  void set_module_info(const std::string& module, nlohmann::json info) { modules_[module] = std::move(info); }
  void set_scene_name(std::string name) { scene_name_ = std::move(name); }
  // The scene's effective render settings ("render", "sun", "environment" sections with every
  // default filled in), so a figure can be read beside what produced it (make gallery).
  void set_settings(nlohmann::json settings) { settings_ = std::move(settings); }
  // Memory at the end of the run (scene::memory_report()).
  void set_memory(nlohmann::json memory) { memory_ = std::move(memory); }

  nlohmann::json to_json(int frames, glm::ivec2 size) const;
  // Writes atomically (core write_file_atomic).
  Status write(const std::filesystem::path& path, int frames, glm::ivec2 size) const;

 private:
  std::vector<double> cpu_ms_;
  std::vector<double> wall_ms_;
  std::vector<double> gpu_ms_;
  std::map<std::string, std::vector<double>> pass_gpu_ms_;
  std::map<std::string, render::PassStats> pass_last_;
  std::map<std::string, std::vector<double>> module_gpu_ms_;                      // module -> total per frame
  std::map<std::string, std::map<std::string, std::vector<double>>> module_pass_ms_;  // module -> pass -> ms
  std::map<std::string, std::map<std::string, render::PassStats>> module_pass_last_;
  std::map<std::string, std::vector<double>> update_ms_;
  std::uint64_t last_gpu_frame_ = 0;
  bool any_gpu_frame_ = false;
  std::map<std::string, nlohmann::json> modules_;
  std::string scene_name_;
  nlohmann::json settings_;
  nlohmann::json memory_;
};

}  // namespace sylva::player
