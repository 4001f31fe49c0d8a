// --suite stream (stream_suite.hpp): a terrain streamed from its baked chunk file against the
// same terrain built in memory, flown along the same path in one run.
#include "with_scene/stream_suite.hpp"

#include "with_scene/row_suite.hpp"

#include <sylva/core/params_json.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/scene/height_source.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/terrain/bake.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <cmath>
#include <ostream>
#include <system_error>
#include <unistd.h>

namespace sylva::bench {
namespace {

namespace fs = std::filesystem;

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitUnavailable = 3;
constexpr int kDefaultResolution = 4097;  // the 4k field
constexpr double kDefaultBudgetMb = 64.0;  // a 4097^2 file holds 1.1 GB of meshes
constexpr const char* kPath = "flight";

// The terrain suite's scene at the suite's field size and budget, without the tree cache; `baked` (when not empty) makes
// its terrain section stream that chunk file instead of building the tree (the height keys then
// stay in the section, unused: the ground comes from the file).
std::string suite_scene(const fs::path& baked) {
  nlohmann::json doc = nlohmann::json::parse(terrain_suite_scene());
  doc["name"] = baked.empty() ? "bench: terrain flight, in memory" : "bench: terrain flight, streamed";
  doc["terrain"]["resolution"] = kDefaultResolution;
  doc["terrain"]["stream"]["budget_mb"] = kDefaultBudgetMb;
  doc["terrain"]["tree_cache"]["directory"] = "";  // the in-memory row builds the tree, never reopens a cached one
  if (!baked.empty()) doc["terrain"]["baked_file"] = baked.string();
  return doc.dump();
}

// The scene's target with the --set `settings` applied (not yet built).
Result<std::unique_ptr<BenchTarget>> make_target(const std::string& scene, const std::vector<Assignment>& settings) {
  return make_scene_target(scene, "<bench stream suite>", settings);
}

// Copies every parameter of `into` from the target's "<prefix><path>" (the values the in-memory
// scene builds with, --set included), so the bake uses the scene's own field and tree settings.
template <class T>
Status copy_from_target(const std::vector<ParamDescriptor>& target, const std::string& prefix, T& into) {
  for (const ParamDescriptor& p : describe_params(into)) {
    auto value = get_param(target, prefix + p.path);
    if (!value.ok()) return value.error();
    SYLVA_TRY(set_param(into, p.path, *value));
  }
  return {};
}

// The scene's ground as the scene makes it from its height keys (the grid is freed on return).
Result<HeightField> generate_field(const scene::HeightSourceSettings& source) {
  auto grid = scene::make_height_grid(source, std::nullopt);
  if (!grid.ok()) return grid.error();
  return scene::height_field_from_grid(*grid);
}

// Frame times [ms] of one scene and the metrics of each frame that the rows need.
struct Flight {
  double build_ms = 0.0;
  std::vector<double> frame_ms;
  double max_resident_bytes = 0.0;
  double max_triangles = 0.0;
  std::map<std::string, double> last;  // metrics of the last frame
};

// The value at quantile q of `ms` (nearest rank; 0 for none).
double quantile(std::vector<double> ms, double q) {
  if (ms.empty()) return 0.0;
  std::sort(ms.begin(), ms.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(ms.size())));
  return ms[std::clamp<std::size_t>(rank, 1, ms.size()) - 1];
}

double metric(const std::map<std::string, double>& m, const std::string& key) {
  const auto it = m.find(key);
  return it == m.end() ? 0.0 : it->second;
}

// Builds `scene`, renders the warm-up frames at the path's first pose, then the measured frames
// along it; the target is gone when this returns (one scene's memory at a time).
Result<Flight> fly(const std::string& scene, const StreamSuiteOptions& o, const std::vector<Assignment>& settings) {
  Flight flight;
  auto built = build_scene_target(scene, "<bench stream suite>", o.size, settings);
  if (!built.ok()) return built.error();
  BenchTarget* target = built->target.get();
  flight.build_ms = built->build_ms;
  Stopwatch wall;
  auto fb = render::Framebuffer::create({.width = o.size.x, .height = o.size.y, .color_formats = {GL_RGBA8}});
  if (!fb.ok()) return fb.error();
  const float dt = 1.0f / 30.0f;
  for (int i = -o.warmup; i < o.frames; ++i) {
    auto pose = target->camera_pose(kPath, std::max(i, 0), o.frames);
    if (!pose.ok()) return pose.error();
    FrameOutput out;
    wall.restart();
    SYLVA_TRY(target->render({i, (i + o.warmup) * static_cast<double>(dt), dt, *pose}, *fb, out));
    glFinish();
    const double ms = wall.elapsed_ms();
    if (i < 0) continue;
    flight.frame_ms.push_back(ms);
    flight.max_resident_bytes = std::max(flight.max_resident_bytes, metric(out.metrics, "terrain.stream_resident_bytes"));
    flight.max_triangles = std::max(flight.max_triangles, metric(out.metrics, "terrain.triangles"));
    flight.last = std::move(out.metrics);
  }
  return flight;
}

class Suite {
 public:
  Suite(const StreamSuiteOptions& o, std::ostream& out)
      : o_(o), out_(out),
        baked_(fs::temp_directory_path() / fmt::format("sylva-bench-stream-{}.sylvaterrain", ::getpid())) {}

  // The in-memory scene's field and tree settings, baked into the temporary chunk file.
  Status bake(const std::vector<ParamDescriptor>& memory_params) {
    scene::HeightSourceSettings source;
    terrain::BakeOptions options;
    SYLVA_TRY(copy_from_target(memory_params, "terrain.", source));
    SYLVA_TRY(copy_from_target(memory_params, "terrain.tree.", options.tree));
    auto field = generate_field(source);
    if (!field.ok()) return field.error();
    resolution_ = field->columns();
    Stopwatch wall;
    auto report = terrain::bake_chunk_file(std::move(*field), baked_.path(), options);
    if (!report.ok()) return report.error();
    const double ms = wall.elapsed_ms();
    print(fmt::format("stream: bake field={}^2 chunks={} triangles={} file_bytes={} bake_ms={:.0f} (grids {:.0f}, meshes "
                      "{:.0f}, merge {:.0f})\n",
                      resolution_, report->chunks, report->triangles, report->bytes, ms, report->prepare_ms,
                      report->meshes_ms, report->merge_ms));
    rows_.push_back({"bake", fmt::format("{}^2", resolution_), static_cast<double>(report->chunks), ms, "ms"});
    rows_.push_back({"bake_file", fmt::format("{}^2", resolution_), static_cast<double>(report->triangles),
                     static_cast<double>(report->bytes), "bytes"});
    return {};
  }

  Status flight_rows(const std::string& name, const std::string& scene, const std::vector<Assignment>& settings) {
    auto flight = fly(scene, o_, settings);
    if (!flight.ok()) return make_error(flight.error().code, fmt::format("{}: {}", name, flight.error().message));
    const Flight& f = *flight;
    const double p50 = quantile(f.frame_ms, 0.5);
    const double p99 = quantile(f.frame_ms, 0.99);
    const double longest = quantile(f.frame_ms, 1.0);
    const auto frames = static_cast<double>(f.frame_ms.size());
    std::string line = fmt::format("stream: {} field={}^2 frames={} p50_ms={:.2f} p99_ms={:.2f} longest_ms={:.2f} "
                                   "build_ms={:.0f} max_triangles={}",
                                   name, resolution_, f.frame_ms.size(), p50, p99, longest, f.build_ms, f.max_triangles);
    const std::string field = fmt::format("{}^2", resolution_);
    rows_.push_back({name + "_p50", field, frames, p50, "ms/frame"});
    rows_.push_back({name + "_p99", field, frames, p99, "ms/frame"});
    rows_.push_back({name + "_longest", field, frames, longest, "ms/frame"});
    rows_.push_back({name + "_build", field, 1, f.build_ms, "ms"});
    if (f.last.count("terrain.stream_budget_bytes") != 0) {  // the scene streams (it has a ChunkStreamer)
      const double budget = metric(f.last, "terrain.stream_budget_bytes");
      const double requests = metric(f.last, "terrain.stream_requests");
      const double loads = metric(f.last, "terrain.stream_loads");
      const double misses = metric(f.last, "terrain.stream_misses");
      const double evictions = metric(f.last, "terrain.stream_evictions");
      const double failures = metric(f.last, "terrain.stream_failures");
      line += fmt::format(" budget_bytes={} max_resident_bytes={} requests={} loads={} misses={} evictions={} failures={}",
                          budget, f.max_resident_bytes, requests, loads, misses, evictions, failures);
      rows_.push_back({"streamed_resident_max", field, budget, f.max_resident_bytes, "bytes"});
      rows_.push_back({"streamed_requests", field, frames, requests, "chunks"});
      rows_.push_back({"streamed_loads", field, frames, loads, "chunks"});
      rows_.push_back({"streamed_misses", field, frames, misses, "chunks"});
      rows_.push_back({"streamed_evictions", field, frames, evictions, "chunks"});
      rows_.push_back({"streamed_failures", field, frames, failures, "chunks"});
    }
    print(line + "\n");
    return {};
  }

  const fs::path& baked() const { return baked_.path(); }

  // One row line, flushed: a long run shows its rows as they come.
  void print(const std::string& line) { out_ << line << std::flush; }

  const std::vector<SuiteRow>& rows() const { return rows_; }

 private:
  const StreamSuiteOptions& o_;
  std::ostream& out_;
  ScratchPath baked_;  // the temporary chunk file, removed when the suite ends
  int resolution_ = 0;
  std::vector<SuiteRow> rows_;
};

}  // namespace

int run_stream_suite(const StreamSuiteOptions& options, std::ostream& out, std::ostream& err) {
  if (scene::find_module("terrain") == nullptr) {
    err << "sylva-bench: suite stream: module not available: the stream suite needs the terrain module in "
           "modules/scene, which this build leaves out\n";
    return kExitUnavailable;
  }
  // A --set path or value the scene lacks is a usage error, found before anything is measured.
  const std::string memory_scene = suite_scene({});
  auto probe = make_target(memory_scene, options.overrides);
  if (!probe.ok()) {
    err << "sylva-bench: suite stream: " << probe.error().message << "\n";
    return kExitUsage;
  }
  out << fmt::format("suite stream: the terrain suite's flight, in memory against streamed from its bake ({}x{}, {} "
                     "frames after {} warm-up frames)\n",
                     options.size.x, options.size.y, options.frames, options.warmup);
  Suite suite(options, out);
  Status status = suite.bake((*probe)->params());
  probe->reset();
  if (status.ok()) status = suite.flight_rows("memory", memory_scene, options.overrides);
  if (status.ok()) status = suite.flight_rows("streamed", suite_scene(suite.baked()), options.overrides);
  if (!status.ok()) err << fmt::format("sylva-bench: suite stream: {}\n", status.error().message);
  if (Status written = write_rows_csv(suite.rows(), options.out, out); !written.ok()) {
    err << "sylva-bench: " << written.error().message << "\n";
    return kExitFailed;
  }
  return status.ok() ? kExitOk : kExitFailed;
}

}  // namespace sylva::bench
