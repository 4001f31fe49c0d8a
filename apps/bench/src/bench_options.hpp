#pragma once
// Command line of sylva-bench (GL-free, unit-tested in tests/bench_options_test.cpp):
//
//   sylva-bench SCENE --sweep path=v1,v2,... [--sweep ...] [--reference path=value]...
//               [--set path=value]... [--camera-path NAME] [--frames N] [--size WxH]
//               [--warmup N] [--dt S] [--threshold T] [--cost gpu_ms|cpu_ms|frame_ms]
//               [--error-metric dssim|share_exceeding|coverage_loss|rmse] [--no-embed] --out DIR
//   sylva-bench --suite terrain|grass|trees|voxel|all [--frames N] [--size WxH] --out DIR
//   sylva-bench --stability [--suite ...] --out DIR
//   sylva-bench --paper 000|001|002|003|004|all [--quick] [--table ID]... [--frames N] [--size WxH] --out DIR
//   sylva-bench SCENE --list-params | --list-camera-paths
//
// SCENE is a scene JSON file or "builtin:ground" (the bench's own sky + fBm ground, which needs
// no content module). Every value is checked here for form (numbers, sizes); parameter paths
// are checked against the scene before anything is rendered (runner.hpp).

#include "results.hpp"
#include "sweep.hpp"

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sylva::bench {

struct BenchOptions {
  std::optional<std::string> scene;
  std::optional<std::string> suite;        // terrain, grass, trees, voxel or all
  std::optional<std::string> paper;        // --paper: 000 .. 004 or all (paper_tables.hpp)
  bool quick = false;                      // --paper --quick: one row per table, small and short
  std::vector<std::string> tables;         // --table (repeatable): only these tables of the one --paper thesis
  std::vector<SweepAxis> sweeps;           // --sweep, in order (first varies slowest)
  std::vector<Assignment> reference;       // --reference: the maximum-quality setting
  std::vector<Assignment> overrides;       // --set: applied to every setting and the reference
  std::optional<std::string> camera_path;  // named path of the scene; none: the scene's first
  std::optional<int> frames;               // frames of the camera path, 1..100000 (default 24)
  std::optional<glm::ivec2> size;          // render size, 16..8192 per side (default 256x144)
  int warmup = 2;                          // unmeasured frames before each setting, 0..1000
  double dt = 1.0 / 30.0;                  // fixed simulation step per frame [s], 0..10
  float threshold = 0.05f;                 // share_exceeding threshold on colour values, 0..1
  std::optional<CostMetric> cost;          // none: default_cost_metric(GL renderer)
  ErrorMetric error = ErrorMetric::kDssim;
  std::string out;                         // output folder (created)
  bool stability = false;
  bool embed_images = true;                // false: the report links the PNG files instead
  bool list_params = false;
  bool list_camera_paths = false;
  bool help = false;
};

inline constexpr int kDefaultFrames = 24;
inline constexpr glm::ivec2 kDefaultSize{256, 144};

// Parses argv[1..argc). Errors name the argument and what was expected.
Result<BenchOptions> parse_bench_options(const std::vector<std::string>& args);

std::string bench_usage();

}  // namespace sylva::bench
