// --stability: the built-in cases of core, render and the bench's ground run and pass; a
// failing or NaN-producing case is reported as failed; the three files are written.
#include "stability.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

namespace sylva::bench {
namespace {

using StabilityReportTest = render::GlTest;

TEST_F(StabilityReportTest, BuiltInCasesPassAndNameTheirInvariant) {
  std::vector<StabilityCase> cases;
  add_core_stability_cases(cases);
  add_render_stability_cases(cases);
  ASSERT_GE(cases.size(), 8u);
  std::ostringstream log;
  const StabilityReport report = run_stability_cases(cases, log);
  ASSERT_EQ(report.rows.size(), cases.size());
  for (const StabilityRow& row : report.rows) {
    EXPECT_TRUE(row.passed) << row.module << "." << row.name << ": " << row.detail;
    EXPECT_EQ(row.nan_count, 0u) << row.name;
    EXPECT_FALSE(row.invariant.empty()) << row.name;
    EXPECT_FALSE(row.detail.empty()) << row.name;
  }
}

// Every available content module's cases (terrain, grass, vegetation, voxel as built) pass,
// and the modules that are not built are listed, not silently dropped.
TEST_F(StabilityReportTest, EveryAvailableModuleCasePasses) {
  std::ostringstream log;
  const StabilityReport report = run_stability({}, log);
  const StabilityReport::Totals t = report.totals();
  EXPECT_EQ(t.failed, 0) << log.str();
  EXPECT_EQ(static_cast<std::size_t>(t.unavailable_modules), missing_stability_modules().size());
  EXPECT_GT(t.passed, 10);
}

TEST_F(StabilityReportTest, FailuresAndNanAreReportedAndWritten) {
  std::vector<StabilityCase> cases;
  cases.push_back({"test", "passes", "always holds", false, [] { return StabilityOutcome{true, 0, "ok"}; }});
  cases.push_back({"test", "fails", "never holds", false, [] { return StabilityOutcome{false, 0, "broken"}; }});
  cases.push_back({"test", "nan", "passes but produced NaN", false, [] { return StabilityOutcome{true, 3, "3 NaN"}; }});
  std::ostringstream log;
  StabilityReport report = run_stability_cases(cases, log);
  StabilityRow missing;
  missing.module = "voxel";
  missing.name = "(module not available)";
  missing.available = false;
  report.rows.push_back(missing);
  const StabilityReport::Totals t = report.totals();
  EXPECT_EQ(t.passed, 1);
  EXPECT_EQ(t.failed, 2);
  EXPECT_EQ(t.unavailable_modules, 1);
  EXPECT_NE(log.str().find("FAIL"), std::string::npos);

  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("sylva-bench-stability-" + std::to_string(::getpid()));
  std::filesystem::remove_all(out);
  ASSERT_TRUE(write_stability_report(report, out, "test renderer").ok());
  auto html = read_file(out / "stability.html");
  auto csv = read_file(out / "stability.csv");
  auto json = read_file(out / "stability.json");
  ASSERT_TRUE(html.ok() && csv.ok() && json.ok());
  EXPECT_NE(html->find("<tr class=\"fail\"><td>test</td><td>nan</td>"), std::string::npos);
  EXPECT_NE(html->find("not available"), std::string::npos);
  EXPECT_NE(csv->find("test,nan,fail,3,"), std::string::npos) << *csv;
  EXPECT_NE(json->find("\"failed\": 2"), std::string::npos);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace sylva::bench
