#include "frame_recorder.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/stats.hpp>

namespace sylva::player {

void FrameRecorder::add_gpu_frame(const render::FrameStats& frame) {
  // The profiler reports its newest complete frame; the same one may be seen twice.
  if (any_gpu_frame_ && frame.frame <= last_gpu_frame_) return;
  any_gpu_frame_ = true;
  last_gpu_frame_ = frame.frame;
  gpu_ms_.push_back(frame.gpu_ms);
  for (const auto& [name, pass] : frame.passes) {
    pass_gpu_ms_[name].push_back(pass.gpu_ms);
    pass_last_[name] = pass;
  }
}

nlohmann::json FrameRecorder::to_json(int frames, glm::ivec2 size) const {
  nlohmann::json j;
  j["frames"] = frames;
  j["size"] = {size.x, size.y};
  j["cpu_ms"] = summarize(cpu_ms_);
  j["gpu_ms"] = summarize(gpu_ms_);
  nlohmann::json passes = nlohmann::json::object();
  for (const auto& [name, samples] : pass_gpu_ms_) {
    const render::PassStats& last = pass_last_.at(name);
    passes[name] = {{"gpu_ms", summarize(samples)},
                    {"primitives", last.primitives},
                    {"samples", last.samples},
                    {"triangles", last.triangles},
                    {"draw_calls", last.draw_calls},
                    {"instances", last.instances}};
  }
  j["passes"] = passes;
  nlohmann::json modules = nlohmann::json::object();
  for (const auto& [name, info] : modules_) modules[name] = info;
  j["modules"] = modules;
  return j;
}

Status FrameRecorder::write(const std::filesystem::path& path, int frames, glm::ivec2 size) const {
  return write_file_atomic(path, to_json(frames, size).dump(2) + "\n");
}

}  // namespace sylva::player
