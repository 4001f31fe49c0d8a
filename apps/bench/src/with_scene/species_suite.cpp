// --suite species (species_suite.hpp): load + bake of species files, plants per second from
// grammar files, and a mixed three-species forest against one species at the same tree count.
#include "with_scene/species_suite.hpp"

#include "with_scene/row_suite.hpp"
#include "with_scene/scene_target.hpp"
#include "with_scene/shipped_files.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/scene/module_registry.hpp>

#ifdef SYLVA_BENCH_WITH_VOXEL
#include <sylva/voxel/plant.hpp>
#include <sylva/voxel/species.hpp>
#endif

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <array>
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
constexpr int kForestSpecies = 3;
constexpr std::uint64_t kGrammarWarmup = 20;
constexpr const char* kDefaultSpecies[kForestSpecies] = {"scenes/species/painted_birch.json",
                                                         "scenes/species/slender_conifer.json", "scenes/species/sapling.json"};
constexpr const char* kDefaultGrammarTable = "modules/voxel/data/species.json";

// The files the suite reads (the user's from --set, or the shipped ones) and the other --set
// assignments, applied to every scene it builds.
struct SuiteFiles {
  std::array<fs::path, kForestSpecies> species;
  fs::path grammar_table;
  std::vector<Assignment> scene_settings;
};

Result<SuiteFiles> suite_files(const std::vector<Assignment>& overrides) {
  SuiteFiles files;
  std::array<bool, kForestSpecies> given{};
  bool table_given = false;
  for (const Assignment& a : overrides) {
    bool known = false;
    for (int i = 0; i < kForestSpecies; ++i) {
      if (a.path == fmt::format("vegetation.species_files.{}.file", i)) {
        files.species[static_cast<std::size_t>(i)] = fs::absolute(a.value);
        given[static_cast<std::size_t>(i)] = known = true;
      }
    }
    if (a.path == "voxel.flora.species_file") {
      files.grammar_table = fs::absolute(a.value);
      table_given = known = true;
    }
    if (!known) files.scene_settings.push_back(a);
  }
  for (int i = 0; i < kForestSpecies; ++i) {
    if (given[static_cast<std::size_t>(i)]) continue;
    auto found = find_shipped_file(kDefaultSpecies[i], "the species suite");
    if (!found.ok()) return found.error();
    files.species[static_cast<std::size_t>(i)] = *found;
  }
  if (!table_given) {
    auto found = find_shipped_file(kDefaultGrammarTable, "the species suite");
    if (!found.ok()) return found.error();
    files.grammar_table = *found;
  }
  return files;
}

// A flat 200 m ground, the camera 35 m south of a 50 m x 50 m stand looking into it; `files`
// fill the species slots in order (none: no trees). Slice bake on, cached in `cache`.
std::string forest_scene(const std::vector<fs::path>& files, const fs::path& cache) {
  std::string slots;
  for (std::size_t i = 0; i < files.size(); ++i) {
    slots += fmt::format(R"({}"{}": {{"file": {}}})", i ? ", " : "", i, nlohmann::json(files[i].string()).dump());
  }
  const std::string vegetation =
      files.empty() ? ""
                    : fmt::format(R"(, "vegetation": {{"area_min": [-25, -25], "area_max": [25, 25], "trees_per_hectare": 60,
                    "min_spacing": 4, "seed": 4, "forest": {{"lod": {{"cache_directory": {}}}}}, "species_files": {{{}}}}})",
                                  nlohmann::json(cache.string()).dump(), slots);
  return fmt::format(R"({{"sylva_scene": 1, "name": "bench: species",
      "camera": {{"position": [0, 6, 60], "yaw_deg": 0, "pitch_deg": -4, "fov_deg": 55}},
      "sun": {{"azimuth_deg": 150, "elevation_deg": 40, "fog_density": 0.002}}, "environment": {{"season": 0.3}},
      "wind": {{"direction_deg": 10, "strength": 4, "gust_amplitude": 2, "seed": 2}},
      "ground": {{"size": 200, "resolution": 33, "generator": "flat"}}{}}})",
                     vegetation);
}

using Built = BuiltTarget;

// The scene's target with the --set `settings` applied (not yet built).
Result<std::unique_ptr<BenchTarget>> make_target(const std::string& scene, const std::vector<Assignment>& settings) {
  return make_scene_target(scene, "<bench species suite>", settings);
}

Result<Built> build(const std::string& scene, glm::ivec2 size, const std::vector<Assignment>& settings) {
  return build_scene_target(scene, "<bench species suite>", size, settings);
}

// One frame at the scene's camera at `time`; its wall time [ms] (render + glFinish) and the
// vegetation module's tree count.
struct Frame {
  double ms = 0.0;
  double trees = 0.0;
  std::map<std::string, double> per_species;  // trees by species name (the module's stats)
};
Result<Frame> render_frame(BenchTarget& target, const render::Framebuffer& fb, double time) {
  auto pose = target.camera_pose("start", 0, 1);
  if (!pose.ok()) return pose.error();
  FrameOutput out;
  Stopwatch wall;
  SYLVA_TRY(target.render({0, time, 1.0f / 30.0f, *pose}, fb, out));
  glFinish();
  const double ms = wall.elapsed_ms();
  Frame frame{ms, 0.0, {}};
  const std::string per_species = "vegetation.trees_per_species.";
  for (const auto& [key, value] : out.metrics) {
    if (key == "vegetation.trees") frame.trees = value;
    if (key.rfind(per_species, 0) == 0) frame.per_species[key.substr(per_species.size())] = value;
  }
  return frame;
}

class Suite {
 public:
  Suite(const SpeciesSuiteOptions& o, std::ostream& out)
      : o_(o), out_(out), scratch_(fs::temp_directory_path() / fmt::format("sylva-bench-species-{}", ::getpid())),
        cache_(scratch_.path()) {}

  // Cold and cached builds of each species alone, and the ground without trees. A file that
  // fails does not stop the others; the first failure is returned.
  Status load_rows(const SuiteFiles& files) {
    // The ground scene has no vegetation section: the --set assignments of trees stay out.
    std::vector<Assignment> ground_settings;
    for (const Assignment& a : files.scene_settings) {
      if (a.path.rfind("vegetation.", 0) != 0) ground_settings.push_back(a);
    }
    auto ground = build(forest_scene({}, cache_), o_.size, ground_settings);
    if (!ground.ok()) return ground.error();
    Status first_failure;
    for (const fs::path& file : files.species) {
      std::error_code ec;
      fs::remove_all(cache_, ec);
      const std::string scene = forest_scene({file}, cache_);
      auto cold = build(scene, o_.size, files.scene_settings);
      auto cached = cold.ok() ? build(scene, o_.size, files.scene_settings) : Result<Built>(cold.error());
      if (!cached.ok()) {
        if (first_failure.ok()) first_failure = make_error(cached.error().code, fmt::format("{}: {}", file.string(), cached.error().message));
        continue;
      }
      print(fmt::format("species load: {} cold_ms={:.1f} cached_ms={:.1f} ground_ms={:.1f}\n", file.filename().string(),
                        cold->build_ms, cached->build_ms, ground->build_ms));
      rows_.push_back({"load_cold", file.filename().string(), 1, cold->build_ms, "ms"});
      rows_.push_back({"load_cached", file.filename().string(), 1, cached->build_ms, "ms"});
    }
    rows_.push_back({"load_ground", "no trees", 0, ground->build_ms, "ms"});
    return first_failure;
  }

  // The mixed forest and each species alone, `rounds` times in turn, `frames` frames each.
  Status forest_rows(const SuiteFiles& files) {
    std::vector<std::vector<fs::path>> forests = {{files.species.begin(), files.species.end()}};
    for (const fs::path& f : files.species) forests.push_back({f});
    std::vector<Built> built;
    for (const auto& forest : forests) {
      auto b = build(forest_scene(forest, cache_), o_.size, files.scene_settings);
      if (!b.ok()) {
        const std::string which = forest.size() == 1 ? forest.front().string() : "the mixed forest";
        return make_error(b.error().code, fmt::format("{}: {}", which, b.error().message));
      }
      built.push_back(std::move(*b));
    }
    auto fb = render::Framebuffer::create({.width = o_.size.x, .height = o_.size.y, .color_formats = {GL_RGBA8}});
    if (!fb.ok()) return fb.error();
    std::vector<double> total_ms(built.size(), 0.0);
    std::vector<Frame> counts(built.size());  // the trees of each forest (the same every frame)
    const int warmup = o_.warmup;
    for (std::size_t k = 0; k < built.size(); ++k) {
      for (int w = 0; w < warmup; ++w) {
        auto f = render_frame(*built[k].target, *fb, w / 30.0);
        if (!f.ok()) return f.error();
      }
    }
    for (int round = 0; round < o_.rounds; ++round) {
      for (std::size_t k = 0; k < built.size(); ++k) {
        for (int i = 0; i < o_.frames; ++i) {
          auto f = render_frame(*built[k].target, *fb, (warmup + round * o_.frames + i) / 30.0);
          if (!f.ok()) return f.error();
          total_ms[k] += f->ms;
          counts[k] = std::move(*f);
        }
      }
    }
    const double frames = static_cast<double>(o_.rounds) * o_.frames;
    std::map<std::string, double> one_ms;  // each species alone, by name
    for (std::size_t k = 0; k < built.size(); ++k) {
      const std::string name = k == 0 ? "mixed" : forests[k].front().filename().string();
      const double ms = total_ms[k] / frames;
      std::string mix;
      for (const auto& [species, n] : counts[k].per_species) mix += fmt::format("{}{}: {}", mix.empty() ? "" : ", ", species, n);
      print(fmt::format("forest: {} species={} trees={} ({}) ms_per_frame={:.2f}\n", name, forests[k].size(), counts[k].trees,
                        mix, ms));
      rows_.push_back({k == 0 ? "forest_mixed" : "forest_one", name, counts[k].trees, ms, "ms/frame"});
      if (k > 0 && counts[k].per_species.size() == 1) one_ms[counts[k].per_species.begin()->first] = ms;
    }
    // What the mixed forest would cost if a tree cost what it costs in its one-species forest:
    // the one-species times weighted by the mixed forest's composition. The ratio is the price
    // of mixing (per-species draws, state changes, textures).
    double expected = 0.0;
    for (const auto& [species, n] : counts[0].per_species) {
      const auto alone = one_ms.find(species);
      if (alone == one_ms.end() || counts[0].trees <= 0.0) {
        return make_error(ErrorCode::kNotFound, fmt::format("the mixed forest has trees of \"{}\", but no one-species forest has "
                                                            "(two species files of the same name?)", species));
      }
      expected += n / counts[0].trees * alone->second;
    }
    const double ratio = total_ms[0] / frames / expected;
    print(fmt::format("forest: mixed / composition-weighted one-species = {:.3f} (expected {:.2f} ms)\n", ratio, expected));
    rows_.push_back({"forest_mixed_ratio", "mixed / weighted one-species", counts[0].trees, ratio, "ratio"});
    return {};
  }

#ifdef SYLVA_BENCH_WITH_VOXEL
  // Each species of the table: `plants` plants from its grammar file, salts 1..plants.
  Status grammar_rows(const fs::path& table_file) {
    std::vector<std::string> warnings;
    auto table = voxel::load_species_table(table_file, voxel::BlockPalette::standard(), warnings);
    if (!table.ok()) return table.error();
    for (const Error& e : table->rejected) print(fmt::format("grammar: {}; the species is left out\n", e.message));
    for (const voxel::SpeciesDef& s : table->species) {
      // A few unmeasured plants first, so the first species does not pay the caches' warm-up.
      for (std::uint64_t salt = 0; salt < kGrammarWarmup; ++salt) {
        auto plant = voxel::generate_plant(s.lsystem, s.growth, ~salt);
        if (!plant.ok()) return plant.error();
      }
      std::size_t parts = 0;
      Stopwatch wall;
      for (int i = 1; i <= o_.plants; ++i) {
        auto plant = voxel::generate_plant(s.lsystem, s.growth, static_cast<std::uint64_t>(i));
        if (!plant.ok()) return plant.error();
        parts += plant->part_count();
      }
      const double seconds = wall.elapsed_s();
      const double rate = static_cast<double>(o_.plants) / seconds;
      const std::string name = fmt::format("{} ({} #{})", s.name, s.grammar, s.system);
      print(fmt::format("grammar: {} plants={} plants_per_s={:.0f} blocks_per_plant={:.1f}\n", name, o_.plants, rate,
                        static_cast<double>(parts) / o_.plants));
      rows_.push_back({"grammar", name, static_cast<double>(o_.plants), rate, "plants/s"});
    }
    return {};
  }
#endif

  // One row line, flushed: a long run shows its rows as they come.
  void print(const std::string& line) { out_ << line << std::flush; }

  const std::vector<SuiteRow>& rows() const { return rows_; }

 private:
  const SpeciesSuiteOptions& o_;
  std::ostream& out_;
  ScratchPath scratch_;  // the species cache, removed when the suite ends
  const fs::path& cache_;
  std::vector<SuiteRow> rows_;
};

}  // namespace

int run_species_suite(const SpeciesSuiteOptions& options, std::ostream& out, std::ostream& err) {
  if (scene::find_module("vegetation") == nullptr) {
    err << "sylva-bench: suite species: module not available: the species suite needs the vegetation module in "
           "modules/scene, which this build leaves out\n";
    return kExitUnavailable;
  }
  auto files = suite_files(options.overrides);
  if (!files.ok()) {
    err << "sylva-bench: " << files.error().message << "\n";
    return kExitFailed;
  }
  // A --set path or value the scene lacks is a usage error, found before anything is measured.
  if (auto probe = make_target(forest_scene({files->species[0]}, {}), files->scene_settings); !probe.ok()) {
    err << "sylva-bench: suite species: " << probe.error().message << "\n";
    return kExitUsage;
  }
  out << fmt::format("suite species: load + bake of species files, plants/s from grammar files, a mixed three-species "
                     "forest against one species ({}x{}, {} frames x {} rounds)\n",
                     options.size.x, options.size.y, options.frames, options.rounds);
  Suite suite(options, out);
  int status = kExitOk;
  auto part = [&](const char* name, const Status& s) {
    if (s.ok()) return;
    err << fmt::format("sylva-bench: suite species: {}: {}\n", name, s.error().message);
    status = kExitFailed;
  };
  part("load", suite.load_rows(*files));
#ifdef SYLVA_BENCH_WITH_VOXEL
  part("grammar", suite.grammar_rows(files->grammar_table));
#else
  err << "sylva-bench: suite species: grammar: module not available: the voxel module is not part of this build\n";
#endif
  part("forest", suite.forest_rows(*files));
  if (Status written = write_rows_csv(suite.rows(), options.out, out); !written.ok()) {
    err << "sylva-bench: " << written.error().message << "\n";
    return kExitFailed;
  }
  return status;
}

}  // namespace sylva::bench
