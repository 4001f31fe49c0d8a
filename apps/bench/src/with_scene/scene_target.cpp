#include "with_scene/scene_target.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/scene/frame_stats.hpp>
#include <sylva/scene/scene.hpp>
#include <sylva/scene/scene_document.hpp>

#ifdef SYLVA_BENCH_WITH_TERRAIN
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/renderer.hpp>
#include <sylva/terrain/selection.hpp>
#endif

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace sylva::bench {
namespace {

constexpr const char* kStartPath = "start";
constexpr const char* kBookmarkPrefix = "bookmark:";

// Numeric leaves of a module's stats as metrics; "lod_instances" objects as LOD counts.
void collect_stats(const nlohmann::json& j, const std::string& prefix, const std::string& module, FrameOutput& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    const nlohmann::json& v = it.value();
    if ((it.key() == "lod_instances" || it.key() == "instances_per_lod") && v.is_object()) {
      for (auto l = v.begin(); l != v.end(); ++l) {
        if (l.value().is_number_unsigned() || l.value().is_number_integer()) {
          out.counts.lod_instances[module + "." + l.key()] += l.value().get<std::uint64_t>();
        }
      }
    } else if (v.is_object()) {
      collect_stats(v, key, module, out);
    } else if (v.is_number()) {
      out.metrics[module + "." + key] = v.get<double>();
    }
  }
}

#ifdef SYLVA_BENCH_WITH_TERRAIN
// The projected geometric error of the chunks the scene's terrain drew this frame:
// K * delta / (D - delta) with each chunk's measured delta and D the distance to its box (Ulrich's
// bound as the selection evaluates it, seed 002 §2.3), from the renderer's own selection and view.
// `drawn` covers every drawn chunk; `certified` only chunks that had finer children to refine
// into, which is what tau bounds: a leaf chunk is drawn however close the camera comes, with the
// error its flat-vertex reduction left (ChunkTreeSettings::flat_tolerance). Capped at 1e4 px.
//
// Beside it (issue 18: "triangles per pixel along the flight beside the projected-error
// histogram"), the drawn chunks by their projected error in px, bins kErrorBinEdges (the chunk
// count and their triangles per bin; exact leaves, error 0, in their own bin), so a run shows
// whether the triangles at tau sit near the bound (what it needs) or far below it (wasted).
struct TerrainError {
  double drawn = 0.0;
  double certified = 0.0;
  static constexpr std::array<double, 7> kErrorBinEdges{0.0, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0};
  // [0] "exact": error exactly 0; [i >= 1]: kErrorBinEdges[i-1] <= rho < kErrorBinEdges[i]; last: >= 8.
  std::array<double, kErrorBinEdges.size() + 1> chunks{};
  std::array<double, kErrorBinEdges.size() + 1> triangles{};
  static std::string bin_name(std::size_t bin) {
    if (bin == 0) return "exact";
    if (bin == kErrorBinEdges.size()) return fmt::format("{:g}+px", kErrorBinEdges.back());
    return fmt::format("{:g}-{:g}px", kErrorBinEdges[bin - 1], kErrorBinEdges[bin]);
  }
  void add(double rho, double chunk_triangles) {
    std::size_t bin = 0;
    if (rho > 0.0) {
      bin = 1;
      while (bin < kErrorBinEdges.size() && rho >= kErrorBinEdges[bin]) ++bin;
    }
    chunks[bin] += 1.0;
    triangles[bin] += chunk_triangles;
  }
};

std::optional<TerrainError> terrain_projected_error_px(scene::Scene& scene, const render::Camera& camera,
                                                       glm::ivec2 size) {
  scene::ModuleInstance* module = scene.module("terrain");
  if (module == nullptr) return std::nullopt;
  for (render::Drawable* d : module->drawables()) {
    const auto* renderer = dynamic_cast<const terrain::TerrainRenderer*>(d);
    if (renderer == nullptr) continue;
    const terrain::LodView view = terrain::TerrainRenderer::view_for(camera, size);
    const terrain::ChunkTree& tree = renderer->tree();
    TerrainError e;
    for (const terrain::SelectedChunk& s : renderer->selection().chunks) {
      const terrain::Chunk& c = tree.chunk(s.index);
      if (c.error <= 0.0f) {
        e.add(0.0, c.triangle_count);
        continue;
      }
      glm::dvec3 lo, hi;
      tree.chunk_bounds(s.index, lo, hi);
      const double dist = view.distance_to_box(lo, hi) - c.error;
      const double rho = std::min(dist > 1e-3 ? view.k * c.error / dist : 1.0e4, 1.0e4);
      e.drawn = std::max(e.drawn, rho);
      e.add(rho, c.triangle_count);
      if (c.key.level + 1 < tree.levels()) e.certified = std::max(e.certified, rho);
    }
    return e;
  }
  return std::nullopt;
}

// Terrain triangles drawn in the colour pass per pixel covered by opaque geometry: the sky pass
// shades exactly the samples no opaque draw covered (it passes only at the cleared depth), so the
// covered pixels are the screen minus its samples per pixel. In a scene whose only opaque module
// is the terrain (the terrain suite, the CDLOD race scene) that is the terrain's own coverage.
// nullopt when nothing is covered or the counts are missing.
std::optional<double> terrain_triangles_per_pixel(const scene::SceneFrameStats& s, glm::ivec2 size, int msaa_samples) {
  const auto module = s.modules.find("terrain");
  const auto sky = s.passes.find("sky");
  if (module == s.modules.end() || sky == s.passes.end()) return std::nullopt;
  const auto opaque = module->second.find("opaque");
  if (opaque == module->second.end()) return std::nullopt;
  const double screen = static_cast<double>(size.x) * size.y;
  const double covered = screen - static_cast<double>(sky->second.samples) / std::max(msaa_samples, 1);
  if (covered < 1.0) return std::nullopt;
  return static_cast<double>(opaque->second.triangles) / covered;
}
#endif

class SceneTarget final : public BenchTarget {
 public:
  explicit SceneTarget(scene::SceneDocument document)
      : document_(std::make_unique<scene::SceneDocument>(std::move(document))) {}

  std::vector<ParamDescriptor> params() override {
    if (scene_) return scene_->describe_params();
    registry_ = document_->params();
    return registry_.describe();
  }

  Status prepare(glm::ivec2 size) override {
    size_ = size;
    auto created = scene::Scene::create(std::move(*document_));
    if (!created.ok()) return created.error();
    scene_ = std::move(*created);
    return {};
  }

  std::vector<CameraPathInfo> camera_paths() const override {
    const scene::SceneDocument& doc = scene_ ? scene_->document() : *document_;
    std::vector<CameraPathInfo> out;
    for (const auto& [name, path] : doc.camera_paths) {
      out.push_back({name, fmt::format("{} keys over {:.3g} s{}", path.keys.size(), path.duration(),
                                       path.settings.loop ? ", looping" : "")});
    }
    out.push_back({kStartPath, "the scene's start camera, not moving"});
    for (const auto& [name, view] : doc.bookmarks) {
      out.push_back({kBookmarkPrefix + name, "bookmark, not moving"});
    }
    return out;
  }

  Result<CameraPose> camera_pose(const std::string& name, int frame, int frames) override {
    if (!scene_) return make_error(ErrorCode::kInvalidArgument, "camera_pose() before prepare()");
    const scene::SceneDocument& doc = scene_->document();
    scene::CameraView view;
    if (name == kStartPath) {
      view = scene_->resolve(doc.camera);
    } else if (name.rfind(kBookmarkPrefix, 0) == 0) {
      auto it = doc.bookmarks.find(name.substr(std::string(kBookmarkPrefix).size()));
      if (it == doc.bookmarks.end()) return make_error(ErrorCode::kNotFound, fmt::format("no bookmark \"{}\"", name));
      view = scene_->resolve(it->second);
    } else {
      auto it = doc.camera_paths.find(name);
      if (it == doc.camera_paths.end()) {
        return make_error(ErrorCode::kNotFound, fmt::format("camera_paths.{}: no such camera path", name));
      }
      const scene::CameraPath& path = it->second;
      const double u = frames > 1 ? static_cast<double>(frame) / (frames - 1) : 0.0;
      // A looping path wraps at its end time, which would show the first pose twice: stop one
      // frame's step short of it.
      const double span = path.settings.loop && frames > 1 ? path.duration() * (frames - 1) / frames : path.duration();
      auto v = scene_->camera_path_view(name, path.start_time() + u * span);
      if (!v.ok()) return v.error();
      view = *v;
    }
    return CameraPose{view.position, view.yaw_deg, view.pitch_deg, view.fov_deg};
  }

  Status render(const FrameInput& input, const render::Framebuffer& target, FrameOutput& out) override {
    scene::CameraView view;
    view.position = input.pose.position;
    view.yaw_deg = input.pose.yaw_deg;
    view.pitch_deg = input.pose.pitch_deg;
    view.fov_deg = input.pose.fov_deg;
    const render::Camera camera = scene_->make_camera(view, size_);
    Stopwatch cpu;
    scene_->update(camera, input.time, input.dt, size_);
    scene_->render(target, profiler_);
    out.cpu_ms = cpu.elapsed_ms();
    const std::optional<render::FrameStats> stats = profiler_.flush();
    if (!stats) return make_error(ErrorCode::kGl, "scene frame: the GPU queries returned no result");
    const scene::SceneFrameStats s = scene::split_frame_stats(*stats);
    out.gpu_ms = s.gpu_ms;
    out.counts = sum_pass_counts(s.passes);
    const nlohmann::json modules = scene_->module_stats();
    for (auto it = modules.begin(); it != modules.end(); ++it) {
      if (it.value().is_object()) collect_stats(it.value(), "", it.key(), out);
    }
#ifdef SYLVA_BENCH_WITH_TERRAIN
    if (std::optional<TerrainError> e = terrain_projected_error_px(*scene_, camera, size_)) {
      out.metrics["terrain.max_projected_error_px"] = e->drawn;
      out.metrics["terrain.certified_projected_error_px"] = e->certified;
      for (std::size_t b = 0; b < e->chunks.size(); ++b) {
        out.metrics["terrain.error_hist.chunks." + TerrainError::bin_name(b)] = e->chunks[b];
        out.metrics["terrain.error_hist.triangles." + TerrainError::bin_name(b)] = e->triangles[b];
      }
      if (std::optional<double> tpp = terrain_triangles_per_pixel(s, size_, scene_->document().render.msaa_samples)) {
        out.metrics["terrain.triangles_per_pixel"] = *tpp;
      }
    }
#endif
    // GPU time per pass, per module and per module and pass (issue #20: the per-pass columns of
    // seed 000 Tab 5.6 and seed 004 R1/R2), for the CSV and JSON.
    for (const auto& [pass, p] : s.passes) out.metrics["pass." + pass + ".gpu_ms"] = p.gpu_ms;
    for (const auto& [module, passes] : s.modules) {
      double ms = 0.0;
      for (const auto& [pass, p] : passes) {
        ms += p.gpu_ms;
        out.metrics[module + "." + pass + ".gpu_ms"] = p.gpu_ms;
      }
      out.metrics[module + ".gpu_ms"] = ms;
    }
    return {};
  }

  std::vector<std::string> modules() const override {
    std::vector<std::string> out;
    const scene::SceneDocument& doc = scene_ ? scene_->document() : *document_;
    for (const scene::ModuleSection& m : doc.modules()) out.push_back(m.name);
    return out;
  }

 private:
  std::unique_ptr<scene::SceneDocument> document_;
  ParamRegistry registry_;
  std::unique_ptr<scene::Scene> scene_;
  render::FrameProfiler profiler_;
  glm::ivec2 size_{256, 144};
};

}  // namespace

Result<TargetFactory> scene_file_factory(const std::string& path) {
  // Load once now so a broken file fails before any GL work, with the loader's message.
  std::vector<std::string> warnings;
  auto doc = scene::SceneDocument::load(path, warnings);
  if (!doc.ok()) return doc.error();
  for (const std::string& w : warnings) log_warn("sylva-bench: {}", w);
  return TargetFactory([path]() -> Result<std::unique_ptr<BenchTarget>> {
    std::vector<std::string> ignored;  // reported once above
    auto d = scene::SceneDocument::load(path, ignored);
    if (!d.ok()) return d.error();
    return std::unique_ptr<BenchTarget>(std::make_unique<SceneTarget>(std::move(*d)));
  });
}

TargetFactory scene_text_factory(std::string text, std::string source, std::filesystem::path directory) {
  return [text = std::move(text), source = std::move(source),
          directory = std::move(directory)]() -> Result<std::unique_ptr<BenchTarget>> {
    std::vector<std::string> warnings;
    auto d = scene::SceneDocument::from_text(text, source, warnings);
    if (!d.ok()) return d.error();
    for (const std::string& w : warnings) log_warn("sylva-bench: {}", w);
    d->set_directory(directory);
    return std::unique_ptr<BenchTarget>(std::make_unique<SceneTarget>(std::move(*d)));
  };
}

}  // namespace sylva::bench
