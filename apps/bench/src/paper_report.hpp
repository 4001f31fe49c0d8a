#pragma once
// The thesis tables side by side with Sylva's measurements (GL-free): for every row of a table,
// the thesis's value and Sylva's, and each one's ratio to the table's first row (the shape of the
// table, which is what compares across a 2010 GPU and this machine). Written as paper.md (one
// Markdown section per table) and paper.json (every number) into the thesis's output folder.

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

// Markdown of one thesis's tables (machine and date in the heading).
std::string paper_markdown(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                           const MachineInfo& machine, const std::string& gl_renderer);

nlohmann::json paper_json(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                          const MachineInfo& machine, const std::string& gl_renderer);

// paper.md and paper.json in `folder` (created), each written atomically.
Status write_paper_report(const std::filesystem::path& folder, const std::string& thesis,
                          const std::vector<PaperOutcome>& outcomes, CostMetric cost, const MachineInfo& machine,
                          const std::string& gl_renderer);

}  // namespace sylva::bench
