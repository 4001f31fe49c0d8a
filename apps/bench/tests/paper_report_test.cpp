// The thesis tables beside Sylva's numbers (GL-free): values, ratios to the first row, rows that
// did not run, tables Sylva cannot run yet, and the thesis data itself (every row has a value).
#include "paper_html.hpp"
#include "paper_report.hpp"
#include "paper_tables.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::bench {
namespace {

PaperTable two_row_table() {
  PaperTable t;
  t.thesis = "000";
  t.id = "9.9";
  t.title = "test table";
  t.row_header = "# things";
  t.thesis_hardware = "a GPU";
  t.rows = {{"10", {}}, {"20", {}}};
  t.columns = {{"LOD0", {}, {paper_value("ms", PaperMeasure::kMs, {2.0, 5.0}), paper_value("fragments", PaperMeasure::kFragments, {100, 300})}}};
  t.differences = "none";
  return t;
}

SettingResult measured(double frame_ms, std::uint64_t fragments_total, int frames) {
  SettingResult r;
  r.frames = frames;
  r.frame_ms.mean = frame_ms;
  r.totals.fragments = fragments_total;
  r.ssim_mean = 0.95;
  r.totals.lod_instances["vegetation.lod0"] = 10u * static_cast<std::uint64_t>(frames);
  return r;
}

TEST(PaperReport, ThesisAndSylvaSideBySideWithRatiosToTheFirstRow) {
  const PaperTable t = two_row_table();
  PaperOutcome o;
  o.table = &t;
  o.rows = {std::vector<SettingResult>{measured(40.0, 2000, 2)}, std::vector<SettingResult>{measured(120.0, 9000, 3)}};
  o.row_reports = {"tab-9.9/row-0", "tab-9.9/row-1"};
  const std::string md = paper_markdown("000", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  // Row 1: thesis 5 ms (2.5x of 2 ms), Sylva 120 ms (3x of 40 ms); fragments per frame 3000 (3x of 1000).
  EXPECT_NE(md.find("| 20 | 5 | 2.50x | 120 | 3.00x | 300 | 3.00x | 3000 | 3.00x |"), std::string::npos) << md;
  EXPECT_NE(md.find("[tab-9.9/row-0](tab-9.9/row-0/report.html)"), std::string::npos);
  const nlohmann::json j = paper_json("000", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  EXPECT_DOUBLE_EQ(j["tables"][0]["rows"][1]["values"]["LOD0 ms"]["sylva"].get<double>(), 120.0);
  EXPECT_DOUBLE_EQ(j["tables"][0]["rows"][1]["values"]["LOD0 ms"]["thesis"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(j["tables"][0]["rows"][1]["lod_instances_per_frame"]["LOD0"]["vegetation.lod0"].get<double>(), 10.0);
}

// paper.html: the same cells as paper.md, the shape plot once two rows ran (thesis and Sylva
// points at their ratios), the table's error-against-time plot when it has a reference (a point
// per measured cell), and nothing unescaped.
TEST(PaperReport, HtmlHasTheTableTheShapePlotAndTheErrorPlot) {
  PaperTable t = two_row_table();
  t.differences = "<none>";
  PaperOutcome o;
  o.table = &t;
  o.rows = {std::vector<SettingResult>{measured(40.0, 2000, 2)}, std::vector<SettingResult>{measured(120.0, 9000, 3)}};
  o.row_reports = {"tab-9.9/row-0", "tab-9.9/row-1"};
  const std::string html = paper_html("000", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  EXPECT_NE(html.find("<td class=\"l\">20</td><td>5</td><td>2.50x</td><td>120</td><td>3.00x</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<a href=\"tab-9.9/row-1/report.html\">"), std::string::npos);
  EXPECT_NE(html.find("Shape: each quantity against its first row"), std::string::npos);
  EXPECT_NE(html.find("thesis LOD0 ms, # things 20: 2.50x"), std::string::npos) << html;
  EXPECT_NE(html.find("Sylva LOD0 ms, # things 20: 3.00x"), std::string::npos) << html;
  EXPECT_EQ(html.find("Pareto front"), std::string::npos) << "a shape plot has no front";
  EXPECT_EQ(html.find("Image error against time"), std::string::npos) << "no reference: no image-quality axis";
  EXPECT_NE(html.find("&lt;none&gt;"), std::string::npos);

  t.reference = {{"x", "1"}};
  const std::string with_error = paper_html("000", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  EXPECT_NE(with_error.find("Image error against time"), std::string::npos);
  EXPECT_NE(with_error.find("# things 20, LOD0: 120 ms"), std::string::npos) << with_error;
  // One row run (--quick): no shape to compare.
  o.rows[1] = std::nullopt;
  EXPECT_EQ(paper_html("000", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe").find("Shape:"), std::string::npos);
}

TEST(PaperReport, ABaselineColumnIsSubtracted) {
  PaperTable t = two_row_table();
  t.columns[0].values[1].minus_column = 1;  // LOD0 fragments minus the "empty" column's
  t.columns.push_back({"empty", {}, {}});
  PaperOutcome o;
  o.table = &t;
  o.rows = {std::vector<SettingResult>{measured(40.0, 2000, 2), measured(10.0, 1500, 2)}, std::nullopt};
  const nlohmann::json j = paper_json("000", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  EXPECT_DOUBLE_EQ(j["tables"][0]["rows"][0]["values"]["LOD0 fragments"]["sylva"].get<double>(), 250.0);  // 1000 - 750
  EXPECT_DOUBLE_EQ(j["tables"][0]["rows"][0]["values"]["LOD0 ms"]["sylva"].get<double>(), 40.0);  // not subtracted
}

TEST(PaperReport, RowsNotRunAndTablesNotReproducibleAreSaidSo) {
  PaperTable t = two_row_table();
  PaperOutcome o;
  o.table = &t;
  o.rows = {std::vector<SettingResult>{measured(40.0, 2000, 2)}, std::nullopt};
  o.row_reports = {"tab-9.9/row-0", ""};
  PaperTable missing = two_row_table();
  missing.missing = "a variant Sylva lacks";
  PaperOutcome m;
  m.table = &missing;
  const std::string md = paper_markdown("000", {o, m}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  EXPECT_NE(md.find("| 20 | 5 | 2.50x | – | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("not run |"), std::string::npos);
  EXPECT_NE(md.find("Not reproduced: a variant Sylva lacks."), std::string::npos);
  const nlohmann::json j = paper_json("000", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  EXPECT_TRUE(j["tables"][0]["rows"][1]["values"]["LOD0 ms"]["sylva"].is_null());
}

// The transcribed data: every table Sylva runs has a thesis value for every row of every column,
// and a scene (or the table says why Sylva cannot run it yet).
void expect_complete(const std::vector<PaperTable>& tables, const std::string& thesis) {
  for (const PaperTable& t : tables) {
    SCOPED_TRACE(t.id);
    EXPECT_EQ(t.thesis, thesis);
    if (!t.missing.empty()) continue;
    EXPECT_FALSE(t.scene_json.empty());
    ASSERT_FALSE(t.rows.empty());
    for (const PaperColumn& c : t.columns) {
      for (const PaperValue& v : c.values) {
        ASSERT_EQ(v.thesis.size(), t.rows.size()) << c.name << " " << v.name;
        // Every value is a number >= 0 or the thesis's "-" (NaN), and each quantity has numbers.
        int numbers = 0;
        for (double x : v.thesis) {
          EXPECT_TRUE(std::isnan(x) || x >= 0.0) << c.name;
          numbers += std::isfinite(x) ? 1 : 0;
        }
        if (t.thesis_has_numbers) {
          EXPECT_GT(numbers, 0) << c.name << " " << v.name;
        }
      }
    }
  }
}

TEST(PaperTables, Seed000IsCompleteAndConsistent) {
  const std::vector<PaperTable> tables = paper_tables("000");
  ASSERT_EQ(tables.size(), 6u);  // Tab. 5.1 - 5.6
  expect_complete(tables, "000");
  EXPECT_EQ(tables[0].rows.back().label, "1000");
  EXPECT_DOUBLE_EQ(tables[0].columns[1].values[0].thesis.back(), 57.16);  // Tab. 5.1 LOD1 at 1000
  // Tab. 5.5: four animation levels by LOD1/LOD2 at 10..100 trees; the thesis's LOD2 x100 "+ leaves".
  EXPECT_TRUE(tables[4].missing.empty());
  ASSERT_EQ(tables[4].rows.size(), 4u);
  ASSERT_EQ(tables[4].columns.size(), 12u);  // 8 measured, 4 stands without trees (baselines)
  EXPECT_EQ(tables[4].columns[7].name, "LOD2 x100");
  EXPECT_DOUBLE_EQ(tables[4].columns[7].values[0].thesis.back(), 6.44);
  EXPECT_DOUBLE_EQ(tables[4].columns[3].values[0].thesis.front(), 11.31);  // LOD1 x100, static
  EXPECT_TRUE(paper_tables("005").empty());
}

TEST(PaperTables, Seed001And004AreComplete) {
  expect_complete(paper_tables("001"), "001");
  EXPECT_FALSE(paper_tables("001")[0].thesis_has_numbers);
  const std::vector<PaperTable> t004 = paper_tables("004");
  ASSERT_EQ(t004.size(), 4u);  // R1 - R4
  expect_complete(t004, "004");
  EXPECT_TRUE(t004[2].rows[2].missing.empty());  // R3: five cascades run (up to 8)
}

TEST(PaperTables, Seed003IsCompleteAndKeepsTheThesisDashes) {
  const std::vector<PaperTable> tables = paper_tables("003");
  ASSERT_EQ(tables.size(), 6u);  // Tab. 4.1 - 4.6
  expect_complete(tables, "003");
  EXPECT_TRUE(std::isnan(tables[2].columns[0].values[0].thesis[0]));  // Tab. 4.3, 1x1: "-"
  EXPECT_TRUE(tables[1].columns[1].missing.empty());                  // Tab. 4.2: wide billboards (grass.far.wide_billboards)
}

TEST(PaperTables, Seed002FpsAreShownAsMs) {
  const std::vector<PaperTable> tables = paper_tables("002");
  ASSERT_EQ(tables.size(), 8u);  // 3.1 - 3.5, 3.6-3.7, general model by level (4.6/4.8/4.10) and by reduction
  EXPECT_TRUE(tables[6].missing.empty());
  EXPECT_EQ(tables[6].id, "4.6, 4.8, 4.10");
  EXPECT_DOUBLE_EQ(tables[7].columns[0].values[1].thesis.back(), 93.0);  // Tab. 4.9 at 90 %: 93 FPS
  EXPECT_TRUE(tables[7].columns[0].values[1].thesis_fps);
  ASSERT_EQ(tables[6].stage_files.size(), 1u);
  EXPECT_NE(tables[6].stage_files[0].second.find("\nf 1 98 2\n"), std::string::npos) << "a 96-quad sheet, first triangle";
  expect_complete(tables, "002");
  const PaperTable& t31 = tables[0];
  EXPECT_EQ(t31.id, "3.1");
  ASSERT_TRUE(t31.columns[0].values[0].thesis_fps);
  PaperOutcome o;
  o.table = &t31;
  o.rows.resize(t31.rows.size());
  const std::string md = paper_markdown("002", {o}, CostMetric::kFrameMs, MachineInfo{}, "llvmpipe");
  // 230 FPS is 4.35 ms; 30 FPS at 2048 is 7.67x the time at 128.
  EXPECT_NE(md.find("| 128 | 4.35 | 1.00x | – | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 2048 | 33.3 | 7.67x |"), std::string::npos) << md;
}

}  // namespace
}  // namespace sylva::bench
