#include "frame_finish.hpp"

#include <fmt/format.h>

namespace sylva::bench {

Status finish_sky_frame(render::FrameProfiler& profiler, render::SkyRenderer& sky, const render::Camera& camera,
                        const render::Lighting& lighting, double time, const Stopwatch& cpu, std::string_view target,
                        FrameOutput& out) {
  profiler.begin("sky");
  sky.draw(camera, lighting, time);
  profiler.end("sky");
  profiler.add_cpu_counts("sky", render::PassStats{.draw_calls = 1});
  profiler.end_frame();
  out.cpu_ms = cpu.elapsed_ms();

  const std::optional<render::FrameStats> stats = profiler.flush();
  if (!stats) return make_error(ErrorCode::kGl, fmt::format("{}: the frame's GPU queries returned no result", target));
  out.gpu_ms = stats->gpu_ms;
  out.counts = sum_pass_counts(stats->passes);
  return {};
}

}  // namespace sylva::bench
