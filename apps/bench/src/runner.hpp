#pragma once
// Runs a sweep on a BenchTarget (needs a current GL 4.5 context) and writes the outputs.
//
// Order of work: validate every path and value on a throw-away target (nothing is rendered when
// a path is unknown or a value is out of range; the message names the path), render the
// reference (maximum quality) along the camera path and keep its frames, then for every setting
// render the same frames, compare each with the reference frame, and keep the images of the
// frame with the lowest SSIM for the report. A setting that fails to build (for example a
// shader error) is recorded with its message and the run goes on; a failing reference stops
// the run.

#include "bench_target.hpp"
#include "results.hpp"

#include <sylva/core/image.hpp>

#include <filesystem>
#include <iosfwd>
#include <optional>

namespace sylva::bench {

struct RunSpec {
  TargetFactory factory;
  std::string scene;                      // for the report
  std::string suite;
  std::string description;
  std::vector<std::vector<SweepAxis>> sweep_groups;  // see expand_sweep_groups
  std::vector<Assignment> reference;      // applied after the overrides for the reference render
  std::string reference_note;
  std::vector<Assignment> overrides;      // applied to every render
  std::optional<std::string> camera_path; // none: the target's first
  int frames = 24;
  glm::ivec2 size{256, 144};
  int warmup = 2;
  double dt = 1.0 / 30.0;
  float threshold = 0.05f;
  CostMetric cost = CostMetric::kGpuMs;
  ErrorMetric error = ErrorMetric::kDssim;
  std::filesystem::path out;              // images go to out/images
  std::string gl_renderer;
  std::string gl_version;
};

// Checks overrides, reference assignments and every swept value against the target's
// parameters without rendering. Errors name the option and the path ("--sweep
// ground.resolutoin: no parameter ... did you mean ground.resolution?").
Status validate_spec(const RunSpec& spec);

// Validates, renders, compares. Progress lines go to `log`.
Result<BenchReport> run_sweep(const RunSpec& spec, std::ostream& log);

// results.csv, results.json and report.html in `out` (created), each written atomically.
// embed_images: the report carries the PNGs as data: URIs (self-contained), else links them.
Status write_report(const BenchReport& report, const std::filesystem::path& out, bool embed_images);

// Image helpers (exposed for tests).
Image to_rgb(const Image& rgba);
// Box-filtered copy no wider than max_width (unchanged when already small enough).
Image downscale(const Image& image, int max_width);
// Per-frame comparison of a setting's frame with the reference frame.
Result<FrameError> compare_frames(const Image& reference_rgb, const Image& reference_depth, const Image& test_rgb,
                                  const Image& test_depth, float threshold);

}  // namespace sylva::bench
