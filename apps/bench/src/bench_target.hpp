#pragma once
// What sylva-bench renders: a scene whose parameters can be set by path, with named camera
// paths, rendering one frame at a time into the bench's framebuffer and reporting what it
// cost. Implementations: GroundTarget (built-in sky + fBm ground, no content module) and
// SceneTarget (a modules/scene scene file with the modules it lists).
//
// Life cycle per setting (runner.cpp): create a fresh target from the factory, set the
// --set overrides and the setting's assignments through params(), prepare(), then render the
// warm-up and measured frames with a fixed time step. A fresh target per setting keeps every
// setting independent of the previous one's simulation state (grass physics, streaming caches),
// which is what makes two runs agree in every count.

#include "camera_path.hpp"
#include "results.hpp"

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>

#include <glm/glm.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace sylva::bench {

struct FrameInput {
  int frame = 0;          // index along the camera path (warm-up frames are -1, -2, ...)
  double time = 0.0;      // scene time [s] = (warm-up frames + frame) * dt, identical in every run
  float dt = 0.0f;        // fixed step [s]
  CameraPose pose;
};

struct FrameOutput {
  double cpu_ms = kNaN;   // CPU time of update + draw submission, without waiting for the GPU
  double gpu_ms = kNaN;   // GPU time of all passes (timer queries)
  FrameCounts counts;
  std::map<std::string, double> metrics;  // module-reported numbers (terrain.max_projected_error_px)
};

// The frame's counters summed over its passes (lod_instances are left empty for the target).
inline FrameCounts sum_pass_counts(const std::map<std::string, render::PassStats>& passes) {
  FrameCounts c;
  for (const auto& [name, pass] : passes) {
    c.primitives += pass.primitives;
    c.fragments += pass.samples;
    c.triangles += pass.triangles;
    c.draw_calls += pass.draw_calls;
    c.instances += pass.instances;
  }
  return c;
}

class BenchTarget {
 public:
  virtual ~BenchTarget() = default;

  // Every parameter --set, --sweep and --reference may address. The descriptors point into the
  // target and stay valid until prepare() or destruction.
  virtual std::vector<ParamDescriptor> params() = 0;
  // Builds everything for rendering at `size` after the parameters are final (needs GL).
  virtual Status prepare(glm::ivec2 size) = 0;
  // Camera paths by name (available before prepare()); the first is the default.
  virtual std::vector<CameraPathInfo> camera_paths() const = 0;
  // Pose of frame `frame` of `frames` (0 <= frame < frames) along path `name`, after prepare()
  // (a scene resolves heights above its ground). Frame i samples the path at i / (frames - 1)
  // of its length, so any frame count sees the whole path. kNotFound for an unknown name.
  virtual Result<CameraPose> camera_pose(const std::string& name, int frame, int frames) = 0;
  // One frame into `target` (bound and cleared by the target itself). Must not read back.
  virtual Status render(const FrameInput& input, const render::Framebuffer& target, FrameOutput& out) = 0;
  // Modules this target draws ("terrain", "grass", ...); for the report.
  virtual std::vector<std::string> modules() const = 0;
};

using TargetFactory = std::function<Result<std::unique_ptr<BenchTarget>>()>;

}  // namespace sylva::bench
