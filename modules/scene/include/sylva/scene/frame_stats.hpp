#pragma once
// Per-pass and per-module statistics of a scene frame (DESIGN.md §2 "Measurements").
//
// Scene::render() opens one FrameProfiler scope per pass ("shadow", "opaque", "sky",
// "transparent") and, inside it, one per module ("opaque/grass"), so GPU time is known per
// module and per pass. GL counting queries do not nest, so primitives and samples are counted in
// the module scopes (except for modules that run their own counting queries) and the pass
// totals are sums over its modules; triangles, draw calls and instances are what the modules
// report from draw().

#include <sylva/render/queries.hpp>

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>

namespace sylva::scene {

// "opaque/grass": the profiler scope of one module in one pass.
std::string module_scope(std::string_view pass, std::string_view module);

struct SceneFrameStats {
  std::uint64_t frame = 0;
  double cpu_ms = 0.0;   // CPU time of the whole frame (update + render submission)
  double gpu_ms = 0.0;   // sum of the pass scopes
  // Pass totals: gpu_ms of the pass scope; counters summed over its module scopes.
  std::map<std::string, render::PassStats> passes;
  // module -> pass -> that module's share.
  std::map<std::string, std::map<std::string, render::PassStats>> modules;
};

// Splits a profiler frame into passes and modules by scope name.
SceneFrameStats split_frame_stats(const render::FrameStats& frame);

// {"gpu_ms", "primitives", "samples", "triangles", "draw_calls", "instances"}.
nlohmann::json pass_stats_json(const render::PassStats& s);

// Memory now (issue #20): tracked GPU bytes per owner (the scene attributes each module's
// allocations to its name; render/gpu_memory.hpp) split into buffers, textures and render
// targets, their total and peak, and the process's peak resident set size (getrusage):
//   {"gpu_bytes": {"<owner>": {"buffers", "textures", "render_targets", "total", "peak"}},
//    "gpu_total_bytes", "gpu_peak_bytes", "peak_rss_bytes"}
nlohmann::json memory_report();

}  // namespace sylva::scene
