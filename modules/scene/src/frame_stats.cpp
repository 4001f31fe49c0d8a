#include <sylva/scene/frame_stats.hpp>

#include <sylva/render/gpu_memory.hpp>

#include <sys/resource.h>

namespace sylva::scene {

std::string module_scope(std::string_view pass, std::string_view module) {
  std::string s(pass);
  s += '/';
  s += module;
  return s;
}

SceneFrameStats split_frame_stats(const render::FrameStats& frame) {
  SceneFrameStats out;
  out.frame = frame.frame;
  out.cpu_ms = frame.cpu_ms;
  out.gpu_ms = frame.gpu_ms;
  for (const auto& [name, stats] : frame.passes) {
    const auto slash = name.find('/');
    if (slash == std::string::npos) {
      render::PassStats& pass = out.passes[name];
      pass.gpu_ms = stats.gpu_ms;
      // A pass scope's own counters (a pass without module scopes, e.g. the sky).
      pass.primitives += stats.primitives;
      pass.samples += stats.samples;
      pass.triangles += stats.triangles;
      pass.draw_calls += stats.draw_calls;
      pass.instances += stats.instances;
      continue;
    }
    const std::string pass_name = name.substr(0, slash);
    const std::string module = name.substr(slash + 1);
    out.modules[module][pass_name] = stats;
    render::PassStats& pass = out.passes[pass_name];
    pass.primitives += stats.primitives;
    pass.samples += stats.samples;
    pass.triangles += stats.triangles;
    pass.draw_calls += stats.draw_calls;
    pass.instances += stats.instances;
  }
  return out;
}

nlohmann::json pass_stats_json(const render::PassStats& s) {
  return {{"gpu_ms", s.gpu_ms},         {"primitives", s.primitives}, {"samples", s.samples},
          {"triangles", s.triangles},   {"draw_calls", s.draw_calls}, {"instances", s.instances}};
}

nlohmann::json memory_report() {
  nlohmann::json owners = nlohmann::json::object();
  for (const auto& [owner, usage] : render::gpu_memory_usage()) {
    nlohmann::json& o = owners[owner];
    for (int k = 0; k < render::kGpuMemoryKinds; ++k) {
      o[render::gpu_memory_kind_name(static_cast<render::GpuMemoryKind>(k))] = usage.bytes[k];
    }
    o["total"] = usage.total();
    o["peak"] = usage.peak_total;
  }
  rusage self{};
  ::getrusage(RUSAGE_SELF, &self);
  return {{"gpu_bytes", owners},
          {"gpu_total_bytes", render::gpu_memory_total()},
          {"gpu_peak_bytes", render::gpu_memory_peak_total()},
          {"peak_rss_bytes", static_cast<std::uint64_t>(self.ru_maxrss) * 1024u}};  // ru_maxrss is in KiB on Linux
}

}  // namespace sylva::scene
