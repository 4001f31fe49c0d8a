#include "frame_recorder.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/stats.hpp>

#include <algorithm>

namespace sylva::player {

void FrameRecorder::add_update_ms(const std::map<std::string, double>& per_module) {
  for (const auto& [module, ms] : per_module) update_ms_[module].push_back(ms);
}

void FrameRecorder::add_gpu_frame(const render::FrameStats& frame) {
  // The profiler reports its newest complete frame; the same one may be seen twice.
  if (any_gpu_frame_ && frame.frame <= last_gpu_frame_) return;
  any_gpu_frame_ = true;
  last_gpu_frame_ = frame.frame;
  gpu_ms_.push_back(frame.gpu_ms);
  const scene::SceneFrameStats split = scene::split_frame_stats(frame);
  for (const auto& [name, pass] : split.passes) {
    pass_gpu_ms_[name].push_back(pass.gpu_ms);
    pass_last_[name] = pass;
  }
  for (const auto& [module, passes] : split.modules) {
    double total = 0.0;
    for (const auto& [pass, stats] : passes) {
      module_pass_ms_[module][pass].push_back(stats.gpu_ms);
      module_pass_last_[module][pass] = stats;
      total += stats.gpu_ms;
    }
    module_gpu_ms_[module].push_back(total);
  }
}

nlohmann::json FrameRecorder::to_json(int frames, glm::ivec2 size) const {
  auto counters = [](const render::PassStats& s) {
    return nlohmann::json{{"primitives", s.primitives}, {"samples", s.samples},   {"triangles", s.triangles},
                          {"draw_calls", s.draw_calls}, {"instances", s.instances}};
  };
  nlohmann::json j;
  j["frames"] = frames;
  j["size"] = {size.x, size.y};
  if (!scene_name_.empty()) j["scene"] = scene_name_;
  if (!settings_.is_null()) j["settings"] = settings_;
  if (!memory_.is_null()) j["memory"] = memory_;
  j["cpu_ms"] = summarize(cpu_ms_);
  j["gpu_ms"] = summarize(gpu_ms_);
  j["wall_ms"] = summarize(wall_ms_);
  j["longest_frame_ms"] = wall_ms_.empty() ? 0.0 : *std::max_element(wall_ms_.begin(), wall_ms_.end());
  j["timing"] = {{"cpu_ms", "CPU time of update and draw submission"},
                 {"gpu_ms", "GPU timer queries around the passes (a software rasteriser's work is not in them)"},
                 {"wall_ms", "wall time of the frame to the buffer swap (window) or glFinish (headless)"}};
  nlohmann::json passes = nlohmann::json::object();
  for (const auto& [name, samples] : pass_gpu_ms_) {
    nlohmann::json p = counters(pass_last_.at(name));
    p["gpu_ms"] = summarize(samples);
    passes[name] = std::move(p);
  }
  j["passes"] = passes;
  nlohmann::json modules = nlohmann::json::object();
  for (const auto& [name, info] : modules_) modules[name] = info.is_object() ? info : nlohmann::json::object();
  for (const auto& [name, samples] : module_gpu_ms_) {
    nlohmann::json& m = modules[name];
    m["gpu_ms"] = summarize(samples);
    nlohmann::json mp = nlohmann::json::object();
    for (const auto& [pass, ms] : module_pass_ms_.at(name)) {
      nlohmann::json p = counters(module_pass_last_.at(name).at(pass));
      p["gpu_ms"] = summarize(ms);
      mp[pass] = std::move(p);
    }
    m["passes"] = std::move(mp);
  }
  for (const auto& [name, samples] : update_ms_) modules[name]["update_ms"] = summarize(samples);
  j["modules"] = modules;
  return j;
}

Status FrameRecorder::write(const std::filesystem::path& path, int frames, glm::ivec2 size) const {
  return write_file_atomic(path, to_json(frames, size).dump(2) + "\n");
}

}  // namespace sylva::player
