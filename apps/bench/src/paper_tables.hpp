#pragma once
// The theses' experiments as data (issue 20, `sylva-bench --paper`): per table, the thesis's own
// numbers (transcribed from ../shared/seeds/, with the hardware the thesis ran on) and the recipe
// that makes Sylva run the same experiment: a scene, one setting per row and per column. GL-free;
// the runner (with_scene/paper_runs.cpp) renders, paper_report.hpp writes the tables side by side.
//
// Where a thesis measured FPS or GPU ms on a 2010 GPU, Sylva's column is ms on this machine and
// both get a ratio to the table's first row: a software rasteriser's absolute times do not compare
// with a GTX 470, the shape of the table does.

#include "sweep.hpp"

#include <glm/glm.hpp>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sylva::bench {

// What a value of a table is.
enum class PaperMeasure {
  kMs,          // time of a frame [ms]: the run's cost metric (frame_ms on llvmpipe, else gpu_ms), mean over frames
  kFragments,   // GL_SAMPLES_PASSED per frame
  kPrimitives,  // GL_PRIMITIVES_GENERATED per frame (after tessellation): the thesis's "polygons"
  kMetric,      // a module metric of the bench (PaperValue::metric, mean over frames), e.g. "grass.build_ms"
};

// One reported quantity of a column, with the thesis's value for each row (NaN: not in the thesis).
struct PaperValue {
  std::string name;             // "ms", "fragments"
  PaperMeasure measure = PaperMeasure::kMs;
  std::vector<double> thesis;   // one per row of the table; NaN where the thesis has "-"
  bool thesis_fps = false;      // the thesis gave frames per second: shown as ms = 1000 / FPS
  std::string metric;           // kMetric: the bench metric's name
  // >= 0: Sylva's value minus the same quantity of that column in the same row (a baseline column,
  // such as the scene without the measured object, so a count is the object's own).
  int minus_column = -1;
  double scale = 1.0;           // Sylva's value is multiplied by this (e.g. 0.001: a metric in ms shown in s)
};

// One column: a setting applied on top of the row's, and what is reported of it.
struct PaperColumn {
  PaperColumn() = default;
  PaperColumn(std::string name_, std::vector<Assignment> assignments_, std::vector<PaperValue> values_,
              std::string missing_ = {})
      : name(std::move(name_)), assignments(std::move(assignments_)), values(std::move(values_)), missing(std::move(missing_)) {}

  std::string name;                   // "LOD0"
  std::vector<Assignment> assignments;
  std::vector<PaperValue> values;
  std::string missing;                // non-empty: Sylva lacks this variant (why); shown, not run
};

struct PaperRow {
  PaperRow() = default;
  PaperRow(std::string label_, std::vector<Assignment> assignments_, std::string missing_ = {})
      : label(std::move(label_)), assignments(std::move(assignments_)), missing(std::move(missing_)) {}

  std::string label;                  // "10", "512 x 512", "+LOD1"
  std::vector<Assignment> assignments;
  std::string missing;                // non-empty: Sylva cannot set this row up yet (why); shown, not run
};

struct PaperTable {
  std::string thesis;                 // "000"
  std::string id;                     // "5.1" (the thesis's table number)
  std::string title;
  std::string row_header;             // "# instances"
  std::string thesis_hardware;        // what the thesis measured on
  std::string scene_json;             // the experiment's scene (modules/scene format)
  std::vector<Assignment> overrides;  // applied to every cell
  std::vector<PaperRow> rows;
  std::vector<PaperColumn> columns;
  // The maximum-quality setting the image error of each row is measured against; empty: the
  // table has no image-quality dimension (its report shows times and counts only).
  std::vector<Assignment> reference;
  glm::ivec2 size{1280, 720};         // the thesis's resolution
  std::string differences;            // deliberate differences from the thesis's set-up
  bool thesis_has_numbers = true;     // false: the thesis shows figures only; Sylva's column stands alone
  std::string missing;                // non-empty: Sylva cannot run this table yet, and why
  // Files the stage scene names by relative path (name, content), written next to it before the
  // table runs: a generated mesh, so a table needs nothing from the source tree.
  std::vector<std::pair<std::string, std::string>> stage_files;
};

// A value of a column (ms and counts per frame: see PaperMeasure) with the thesis's numbers.
PaperValue paper_value(std::string name, PaperMeasure measure, std::vector<double> thesis);

// Whether `id` names table t: its id ("5.5"), or one part of a combined id ("4.8" of "4.6, 4.8, 4.10").
bool paper_table_matches(const PaperTable& t, std::string_view id);

// Theses with a --paper command: "000" ... "004", in the order `--paper all` runs them.
std::vector<std::string> paper_names();

// The tables of one thesis, in the thesis's order. Unknown names give an empty list.
std::vector<PaperTable> paper_tables(const std::string& thesis);

}  // namespace sylva::bench
