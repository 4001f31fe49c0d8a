#pragma once
// --stability: every available module's extreme cases (parameters, time steps, coordinates,
// inputs), each checking one named invariant, run in one process and written as a pass/fail
// table with NaN counts (stability.csv, stability.json, stability.html).
//
// Cases are built here from each module's public API (no module exposes a case list of its
// own yet). A module that is not part of the build gets one "not available" row, so its absence
// is visible; it does not count as a failure.

#include <sylva/core/result.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace sylva::bench {

struct StabilityOutcome {
  bool passed = false;
  std::uint64_t nan_count = 0;  // NaN/Inf values found in the case's outputs
  std::string detail;           // measured numbers ("max length change 0.02 %")
};

struct StabilityCase {
  std::string module;      // "core", "render", "bench", "terrain", ...
  std::string name;        // "wind_hurricane_1e7s"
  std::string invariant;   // what must hold ("no NaN in the wind vector; |w| <= bound")
  bool needs_gl = false;   // runs with the bench's headless context current
  std::function<StabilityOutcome()> run;
};

struct StabilityRow {
  std::string module;
  std::string name;
  std::string invariant;
  bool available = true;   // false: the module is not built (one row per missing module)
  bool passed = false;
  std::uint64_t nan_count = 0;
  std::string detail;
  double ms = 0.0;
};

struct StabilityReport {
  std::vector<StabilityRow> rows;
  struct Totals {
    int passed = 0;
    int failed = 0;
    int unavailable_modules = 0;
  };
  Totals totals() const;
};

struct StabilityOptions {
  std::optional<std::string> only_module;  // run one module's cases only
};

// Every case of every available module (GL cases need a current context when run).
std::vector<StabilityCase> all_stability_cases();
// Content modules that this build lacks (for "not available" rows).
std::vector<std::string> missing_stability_modules();

// Runs the cases (exceptions and asserts are not caught: a crash is a failure the tests see).
StabilityReport run_stability(const StabilityOptions& options, std::ostream& log);
StabilityReport run_stability_cases(const std::vector<StabilityCase>& cases, std::ostream& log);

std::string stability_csv(const StabilityReport& report);
std::string stability_json(const StabilityReport& report, const std::string& gl_renderer);
std::string stability_html(const StabilityReport& report, const std::string& gl_renderer);
Status write_stability_report(const StabilityReport& report, const std::filesystem::path& out,
                              const std::string& gl_renderer);

// Per-module case lists (stability_<module>.cpp); content modules only when built.
void add_core_stability_cases(std::vector<StabilityCase>& cases);
void add_render_stability_cases(std::vector<StabilityCase>& cases);
void add_scene_stability_cases(std::vector<StabilityCase>& cases);
void add_terrain_stability_cases(std::vector<StabilityCase>& cases);
void add_grass_stability_cases(std::vector<StabilityCase>& cases);
void add_vegetation_stability_cases(std::vector<StabilityCase>& cases);
void add_voxel_stability_cases(std::vector<StabilityCase>& cases);

}  // namespace sylva::bench
