#pragma once
// The thesis tables side by side with Sylva's measurements (GL-free): for every row of a table,
// the thesis's value and Sylva's, and each one's ratio to the table's first row (the shape of the
// table, which is what compares across a 2010 GPU and this machine). Written as paper.md (one
// Markdown section per table), paper.json (every number) and paper.html (the tables with their
// plots) into the thesis's output folder.

#include "paper_tables.hpp"
#include "results.hpp"

#include <sylva/core/result.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sylva::bench {

// What Sylva measured for one table: per row that ran, one SettingResult per column (same order
// as PaperTable::columns; a default one for a column Sylva lacks). Rows that did not run
// (--quick runs the first) are std::nullopt.
struct PaperOutcome {
  const PaperTable* table = nullptr;
  std::vector<std::optional<std::vector<SettingResult>>> rows;
  std::vector<std::string> row_reports;  // per row: folder of its sweep report, relative ("" = none)
  std::string failure;                   // non-empty: the table failed to run, and why
};

// Sylva's value of one quantity for one setting (ms: the cost metric's mean; counts per frame;
// metrics their mean). NaN for a setting that did not run (a default SettingResult).
double paper_measure(const SettingResult& result, const PaperValue& value, CostMetric cost);

// One table as text cells, shared by the Markdown and HTML writers: the header, per row the label
// and per column and value the thesis's number, its ratio, Sylva's number and its ratio (then DSSIM
// per column when the table has a reference), and per row its report folder or why it did not run.
struct PaperGrid {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> reports;  // per row: report folder relative to the thesis folder ("" = none)
  std::vector<std::string> not_run;  // per row: "not run" or "not run: <why Sylva cannot>"
};
PaperGrid paper_grid(const PaperOutcome& o, CostMetric cost);

// The shape of one column's quantity: per row, the thesis's and Sylva's value divided by their own
// first row (NaN where a row has no value), for the shape plot of paper.html.
struct PaperShape {
  std::string name;  // "LOD1 ms"
  std::vector<double> thesis;
  std::vector<double> sylva;
};
std::vector<PaperShape> paper_shapes(const PaperOutcome& o, CostMetric cost);

// Markdown of one thesis's tables (machine and date in the heading).
std::string paper_markdown(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                           const MachineInfo& machine, const std::string& gl_renderer);

nlohmann::json paper_json(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                          const MachineInfo& machine, const std::string& gl_renderer);

// paper.md, paper.json and paper.html (paper_html.hpp) in `folder` (created), each written atomically.
Status write_paper_report(const std::filesystem::path& folder, const std::string& thesis,
                          const std::vector<PaperOutcome>& outcomes, CostMetric cost, const MachineInfo& machine,
                          const std::string& gl_renderer);

}  // namespace sylva::bench
