#pragma once
// What a benchmark run measured, as plain data (GL-free), and the CSV / JSON writers.
//
// Counts are exact integers summed over the frames of the camera path, so two runs of the same
// setting on the same machine must agree in them exactly (tests/reproducible_gl_test.cpp);
// times are summaries over frames (mean, p50, p99) and agree only within noise.
// Image errors compare each frame with the reference render of the same frame (see
// error_metrics.hpp for the definitions).

#include "sweep.hpp"

#include <sylva/core/stats.hpp>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sylva::bench {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Counters of one frame (or their sum over frames). Names follow render::PassStats.
struct FrameCounts {
  std::uint64_t triangles = 0;   // submitted by the CPU side of every module
  std::uint64_t primitives = 0;  // GL_PRIMITIVES_GENERATED (after tessellation)
  std::uint64_t fragments = 0;   // GL_SAMPLES_PASSED
  std::uint64_t draw_calls = 0;
  std::uint64_t instances = 0;
  // Instances per LOD level, "<module>.<level>" such as "trees.lod0" (module-defined names).
  std::map<std::string, std::uint64_t> lod_instances;

  FrameCounts& operator+=(const FrameCounts& o);
  bool operator==(const FrameCounts&) const = default;
};

// Image error of one frame against the reference frame.
struct FrameError {
  double mse = kNaN;                  // mean squared error over RGB
  double psnr_db = kNaN;              // 10 log10(1 / mse); +inf for identical frames
  double ssim = kNaN;                 // mean SSIM (luminance, Gaussian 11x11, valid windows)
  double share_exceeding = kNaN;      // share of pixels whose largest channel error > threshold
  double silhouette_coverage = kNaN;  // |R and T| / |R| of the foreground masks (depth > 0)
  double silhouette_iou = kNaN;       // |R and T| / |R or T|
};

struct FrameRecord {
  int frame = 0;
  double cpu_ms = kNaN;  // CPU time of update + draw submission (no read-back)
  double gpu_ms = kNaN;  // GPU time from timer queries around all passes
  double frame_ms = kNaN;  // wall time from the start of the frame until glFinish returned
  FrameCounts counts;
  FrameError error;
  // Module-reported per-frame numbers, e.g. "terrain.max_projected_error_px".
  std::map<std::string, double> metrics;
};

// Aggregate of one module metric over the frames.
struct MetricAggregate {
  double mean = kNaN;
  double max = kNaN;
};

struct SettingResult {
  Setting setting;
  bool reference = false;   // the maximum-quality render the others are compared with
  bool pareto = false;      // on the error-against-time Pareto front
  int frames = 0;
  SampleSummary gpu_ms;
  SampleSummary cpu_ms;
  SampleSummary frame_ms;
  FrameCounts totals;       // sums over the frames
  // Errors over the frames: psnr_db from the mean MSE (so it is finite unless every frame is
  // identical), psnr_min_db from the worst frame, means and minima/maxima of the others.
  double psnr_db = kNaN;
  double psnr_min_db = kNaN;
  double ssim_mean = kNaN;
  double ssim_min = kNaN;
  double share_exceeding_mean = kNaN;
  double share_exceeding_max = kNaN;
  double silhouette_coverage_mean = kNaN;
  double silhouette_coverage_min = kNaN;
  std::map<std::string, MetricAggregate> metrics;
  int worst_frame = -1;     // frame with the lowest SSIM (its images are in the report)
  std::string thumbnail;    // PNG path relative to the output folder ("" = none)
  std::string difference;   // heat-map PNG path relative to the output folder
  std::string reference_image;  // the reference render of worst_frame, relative path
  std::vector<FrameRecord> frame_records;
  std::string error_message;  // non-empty: this setting failed (the run continues)

  // Fills gpu_ms ... metrics and worst_frame from frame_records.
  void aggregate();
  // The geometric error bound a terrain reports, if any: max of "terrain.max_projected_error_px".
  std::optional<double> max_geometric_error_px() const;
};

// Host and build facts printed with every result.
struct MachineInfo {
  std::string cpu_model;    // /proc/cpuinfo "model name"
  int cpu_cores = 0;        // logical processors
  std::string gl_renderer;  // GL_RENDERER
  std::string gl_version;   // GL_VERSION
  std::string os;           // uname sysname release machine
  std::string compiler;
  std::string build_type;   // CMAKE_BUILD_TYPE of this binary
  std::string date_utc;     // ISO 8601 time of the run

  // Everything except the GL strings (filled by whoever has a context).
  static MachineInfo collect();
};

// Which numbers the plot and the Pareto front use.
// kFrameMs (submission until glFinish) is what a software rasteriser such as llvmpipe can be
// judged by: its timer queries only see command submission, not the rasterisation that happens
// on the CPU threads at the flush.
enum class CostMetric { kGpuMs, kCpuMs, kFrameMs };
// gpu_ms on hardware, frame_ms on a software rasteriser (by GL_RENDERER).
CostMetric default_cost_metric(const std::string& gl_renderer);
enum class ErrorMetric { kDssim, kShareExceeding, kCoverageLoss, kRmse };
const char* to_string(CostMetric m);
const char* to_string(ErrorMetric m);
const char* axis_title(CostMetric m);
const char* axis_title(ErrorMetric m);
Result<CostMetric> parse_cost_metric(std::string_view text);
Result<ErrorMetric> parse_error_metric(std::string_view text);
double cost_of(const SettingResult& r, CostMetric m);
double error_of(const SettingResult& r, ErrorMetric m);

struct RunInfo {
  std::string tool_version = "sylva-bench 1";
  std::string scene;          // scene file or built-in name
  std::string suite;          // "" for a free sweep
  std::string description;    // what the run shows (suites say what matters)
  std::string camera_path;
  int frames = 0;
  int width = 0;
  int height = 0;
  int warmup_frames = 0;
  double dt = 0.0;            // fixed simulation step per frame [s]
  float threshold = 0.0f;     // share_exceeding threshold
  std::vector<std::vector<SweepAxis>> sweep_groups;  // see expand_sweep_groups
  std::vector<Assignment> reference;  // assignments of the reference render
  std::vector<Assignment> overrides;  // --set applied to every setting
  std::string reference_note;         // what "maximum quality" means here
  CostMetric cost = CostMetric::kGpuMs;
  ErrorMetric error = ErrorMetric::kDssim;
  MachineInfo machine;
  std::vector<std::string> notes;     // warnings worth reading next to the numbers
};

struct BenchReport {
  RunInfo info;
  SettingResult reference;
  std::vector<SettingResult> settings;

  // Marks SettingResult::pareto over the settings that did not fail (reference excluded).
  void mark_pareto();
};

// Columns: setting, id, one per swept path, frames, timing, counts, LOD instance columns (union
// over settings, sorted), errors, module metrics, pareto. The reference is the first row.
std::string to_csv(const BenchReport& report);
nlohmann::json to_json(const BenchReport& report);

// A double for CSV: shortest round-trip text, "inf", "-inf", "nan" (empty for NaN when
// empty_nan).
std::string format_number(double v, bool empty_nan = false);

}  // namespace sylva::bench
