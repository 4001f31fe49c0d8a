// Stability cases of modules/scene: hostile scene documents are refused with a message, and whole
// scene frames (ground, sky, fog, the shadow pass and tone mapping together) stay finite far from
// the origin, with the sun at the zenith, at and below the horizon, and at extreme time steps.
// Frames are rendered into an RGBA32F target so any NaN or Inf pixel is counted.
#include "stability.hpp"

#include <sylva/core/image.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>
#include <sylva/scene/scene_document.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <utility>
#include <string>
#include <vector>

namespace sylva::bench {
namespace {

struct HostileDocument {
  const char* what;
  const char* text;
};

// Each must be refused (Result error with a message), never crash or load silently.
constexpr HostileDocument kHostile[] = {
    {"truncated JSON", R"({"sylva_scene": 1, "camera": {"position": [0, 1)"},
    {"future format version", R"({"sylva_scene": 99})"},
    {"string where a number belongs", R"({"sylva_scene": 1, "camera": {"fov_deg": "wide"}})"},
    {"out-of-range ground resolution", R"({"sylva_scene": 1, "ground": {"resolution": -5}})"},
    {"1e300 m ground", R"({"sylva_scene": 1, "ground": {"size": 1e300}})"},
    {"camera position of two numbers", R"({"sylva_scene": 1, "camera": {"position": [1, 2]}})"},
    {"not an object", R"([1, 2, 3])"},
};

StabilityOutcome hostile_documents() {
  StabilityOutcome o;
  int refused = 0;
  std::string loaded;
  for (const HostileDocument& h : kHostile) {
    std::vector<std::string> warnings;
    auto doc = scene::SceneDocument::from_text(h.text, "<stability>", warnings);
    if (!doc.ok() && !doc.error().message.empty()) {
      ++refused;
    } else {
      loaded += loaded.empty() ? h.what : std::string(", ") + h.what;
    }
  }
  const int total = static_cast<int>(std::size(kHostile));
  o.passed = refused == total;
  o.detail = loaded.empty() ? fmt::format("all {} hostile documents refused with a message", total)
                            : fmt::format("{} of {} refused; loaded: {}", refused, total, loaded);
  return o;
}

struct SceneFrame {
  scene::CameraView view;
  double time = 0.0;
  float dt = 0.0f;
  std::vector<std::pair<std::string, std::string>> set = {};  // Scene::set_param before the frame
};

// Called after each frame with its index and Scene::module_stats().
using FrameStatsSink = std::function<void(std::size_t, const nlohmann::json&)>;

// Builds the scene from `text` and renders `frames` into a 96x54 RGBA32F target; counts
// non-finite pixels over all frames.
StabilityOutcome render_scene(const std::string& text, const std::vector<SceneFrame>& frames,
                              const FrameStatsSink& sink = nullptr) {
  StabilityOutcome o;
  std::vector<std::string> warnings;
  auto doc = scene::SceneDocument::from_text(text, "<stability>", warnings);
  if (!doc.ok()) {
    o.detail = doc.error().describe();
    return o;
  }
  auto created = scene::Scene::create(std::move(*doc));
  if (!created.ok()) {
    o.detail = created.error().describe();
    return o;
  }
  scene::Scene& s = **created;
  const glm::ivec2 size(96, 54);
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA32F}});
  if (!fb.ok()) {
    o.detail = fb.error().describe();
    return o;
  }
  render::FrameProfiler profiler;
  float lo = INFINITY, hi = -INFINITY;
  std::uint64_t fragments = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const SceneFrame& f = frames[i];
    for (const auto& [path, value] : f.set) {
      const Status set = s.set_param(path, value);
      if (!set.ok()) {
        o.detail = set.error().describe();
        return o;
      }
    }
    const render::Camera camera = s.make_camera(s.resolve(f.view), size);
    s.update(camera, f.time, f.dt, size);
    s.render(*fb, profiler);
    if (auto stats = profiler.flush()) {
      for (const auto& [name, pass] : stats->passes) fragments += pass.samples;
    }
    auto color = render::read_color(*fb);
    if (!color.ok()) {
      o.detail = color.error().describe();
      return o;
    }
    o.nan_count += find_non_finite(*color).count;
    for (float v : color->data()) {
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    if (sink) sink(i, s.module_stats());
  }
  o.passed = o.nan_count == 0 && lo >= 0.0f && fragments > 0;
  o.detail = fmt::format("{} frame(s): {} non-finite values; colour range [{:.3f}, {:.3f}]; {} fragments", frames.size(),
                         o.nan_count, lo, hi, fragments);
  return o;
}

// A small ground around `center` (x = z) with shadows on and tone mapping as asked.
std::string ground_scene(const std::string& center, const std::string& sun, bool tone_map) {
  return fmt::format(R"({{
  "sylva_scene": 1,
  "camera": {{"position": [{0}, 40.0, {0}], "fov_deg": 60.0}},
  "sun": {1},
  "render": {{"tone_map": {2}, "shadows": {{"enabled": true, "cascade_count": 3, "resolution": 256}}}},
  "ground": {{"center": [{0}, {0}], "size": 800.0, "resolution": 65, "height": 60.0, "generator": "hills_and_ridges"}}
}})",
                     center, sun, tone_map ? "true" : "false");
}

scene::CameraView view_at(double x, double y, double z, float yaw, float pitch, float fov = 60.0f) {
  scene::CameraView v;
  v.position = glm::dvec3(x, y, z);
  v.yaw_deg = yaw;
  v.pitch_deg = pitch;
  v.fov_deg = fov;
  return v;
}

// A small forest (seed 000 trees with image-based LOD1/LOD2, 32-texel slices) on flat ground.
constexpr const char* kForestScene = R"({
  "sylva_scene": 1,
  "camera": {"position": [0.0, 6.0, 70.0], "fov_deg": 60.0},
  "sun": {"azimuth_deg": 150.0, "elevation_deg": 40.0},
  "render": {"shadows": {"enabled": true, "cascade_count": 1, "resolution": 256}},
  "ground": {"size": 300.0, "resolution": 33, "height": 0.0, "generator": "flat"},
  "vegetation": {"area_min": [-30.0, -30.0], "area_max": [30.0, 30.0], "trees_per_hectare": 40.0, "min_spacing": 6.0,
                 "seed": 4, "forest": {"lod": {"slice_resolution": 32}}}
})";

// Per-level instance counts from the scene's vegetation stats.
std::array<std::uint64_t, 3> lod_counts(const nlohmann::json& stats) {
  std::array<std::uint64_t, 3> n{0, 0, 0};
  if (!stats.contains("vegetation") || !stats["vegetation"].contains("instances_per_lod")) return n;
  const nlohmann::json& per = stats["vegetation"]["instances_per_lod"];
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string key = fmt::format("lod{}", i);
    if (per.contains(key) && per[key].is_number()) n[i] = per[key].get<std::uint64_t>();
  }
  return n;
}

// Extreme LOD thresholds (seed 000 §2.8 v1/v2, the screen-size criterion, band and hysteresis at
// their limits, v1 > v2), set at run time on one scene (so the programs are built once): every
// frame finite, and the levels the thresholds demand are used.
StabilityOutcome vegetation_lod_extremes() {
  using Set = std::vector<std::pair<std::string, std::string>>;
  struct Variant {
    const char* name;
    Set set;
    int expect;  // -1: any mix; else the only level that may be drawn
  };
  const std::string l = "vegetation.forest.lod.";
  const std::vector<Variant> variants = {
      {"v1 = v2 = 0", {{l + "v1", "0"}, {l + "v2", "0"}, {l + "band", "0"}}, 2},
      {"v1 = v2 = 1e7 m", {{l + "v1", "1e7"}, {l + "v2", "1e7"}}, 0},
      {"screen size, s1 = s2 = 1e5 px", {{l + "criterion", "screen_size"}, {l + "s1", "1e5"}, {l + "s2", "1e5"}}, 2},
      {"v1 > v2, band 4, hysteresis 1",
       {{l + "criterion", "distance"}, {l + "v1", "30"}, {l + "v2", "10"}, {l + "band", "4"}, {l + "hysteresis", "1"}},
       -1},
  };
  // One frame per variant from outside the forest (trees from 20 to 95 m away): a camera within
  // 1.5 bounding radii of a tree always gets LOD0 for it (vegetation/lod_selection.hpp), which
  // is not what these thresholds test.
  std::vector<SceneFrame> frames;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    frames.push_back({view_at(0.0, 3.0, 50.0, 10.0f, -2.0f), static_cast<double>(i) / 30.0, 1.0f / 30.0f, variants[i].set});
  }
  std::vector<std::array<std::uint64_t, 3>> counts(variants.size());
  StabilityOutcome o = render_scene(kForestScene, frames,
                                    [&](std::size_t i, const nlohmann::json& stats) { counts[i] = lod_counts(stats); });
  bool levels_ok = true;
  std::string detail;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const std::array<std::uint64_t, 3>& n = counts[i];
    bool ok = n[0] + n[1] + n[2] > 0;
    if (variants[i].expect >= 0) {
      for (int lv = 0; lv < 3; ++lv) ok = ok && (lv == variants[i].expect || n[static_cast<std::size_t>(lv)] == 0);
    }
    levels_ok = levels_ok && ok;
    detail += fmt::format("{}{}: LOD0/1/2 {}/{}/{}{}", detail.empty() ? "" : "; ", variants[i].name, n[0], n[1], n[2],
                          ok ? "" : " (unexpected levels)");
  }
  o.passed = o.passed && levels_ok;
  o.detail = detail + "; " + o.detail;
  return o;
}

}  // namespace

void add_scene_stability_cases(std::vector<StabilityCase>& cases) {
  if (scene::find_module("vegetation") != nullptr) {
    cases.push_back({"vegetation", "lod_extreme_thresholds",
                     "image-based LOD with v1 = v2 = 0 (all LOD2), v1 = v2 = 1e7 m (all LOD0), v1 > v2 with band 4 and "
                     "hysteresis 1, and the screen-size criterion at 1e5 px (all LOD2): no NaN pixel, instances drawn, "
                     "only the levels the thresholds demand",
                     true, vegetation_lod_extremes});
  }
  cases.push_back({"scene", "hostile_documents",
                   "truncated JSON, a future version, wrong types, out-of-range and absurd values are refused with a "
                   "message (no crash, nothing loaded)",
                   false, hostile_documents});
  cases.push_back({"scene", "far_from_origin_shadows_tone_mapped",
                   "a whole frame (ground, sky, fog, 3 shadow cascades, tone mapping) with the ground centred 1e6 m "
                   "from the origin: no NaN pixel, colours >= 0",
                   true, [] {
                     return render_scene(ground_scene("1000000.0", R"({"azimuth_deg": 150.0, "elevation_deg": 30.0})", true),
                                         {{view_at(1e6 - 200.0, 120.0, 1e6 + 200.0, -45.0f, -15.0f), 0.0, 1.0f / 30.0f},
                                          {view_at(1e6 - 199.999, 120.0, 1e6 + 200.0, -45.0f, -15.0f), 0.033, 1.0f / 30.0f}});
                   }});
  cases.push_back({"scene", "sun_zenith_horizon_below",
                   "the sun straight up, exactly at the horizon and under it, with shadows on: no NaN pixel, colours "
                   ">= 0",
                   true, [] {
                     StabilityOutcome total{true, 0, ""};
                     for (const char* sun : {R"({"azimuth_deg": 0.0, "elevation_deg": 90.0})",
                                             R"({"azimuth_deg": 90.0, "elevation_deg": 0.0})",
                                             R"({"azimuth_deg": 270.0, "elevation_deg": -10.0})"}) {
                       StabilityOutcome o = render_scene(ground_scene("0.0", sun, false),
                                                         {{view_at(-200.0, 80.0, 200.0, -45.0f, -12.0f), 0.0, 0.0f}});
                       total.passed = total.passed && o.passed;
                       total.nan_count += o.nan_count;
                       total.detail += (total.detail.empty() ? "" : "; ") + o.detail;
                     }
                     return total;
                   }});
  cases.push_back({"scene", "extreme_time_steps",
                   "updates with dt = 0, 1e-6 s and 10 s at t = 1e7 s, camera looking straight down and straight up: "
                   "no NaN pixel",
                   true, [] {
                     return render_scene(ground_scene("0.0", R"({"azimuth_deg": 200.0, "elevation_deg": 45.0})", false),
                                         {{view_at(0.0, 150.0, 0.0, 0.0f, -90.0f), 1e7, 0.0f},
                                          {view_at(0.0, 150.0, 0.0, 0.0f, 90.0f), 1e7 + 1e-6, 1e-6f},
                                          {view_at(0.0, 150.0, 0.0, 30.0f, -30.0f, 0.01f), 1e7 + 10.0, 10.0f}});
                   }});
}

}  // namespace sylva::bench
