// CSV, JSON, HTML and SVG writers on a hand-made report (GL-free).
#include "base64.hpp"
#include "report_html.hpp"
#include "results.hpp"
#include "svg_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace sylva::bench {
namespace {

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + needle.size())) ++n;
  return n;
}

FrameRecord frame(int i, double ms, double ssim, std::uint64_t triangles) {
  FrameRecord f;
  f.frame = i;
  f.cpu_ms = ms / 2;
  f.gpu_ms = ms;
  f.frame_ms = ms * 1.5;
  f.counts.triangles = triangles;
  f.counts.fragments = 100 + triangles;
  f.counts.draw_calls = 2;
  f.counts.instances = 3;
  f.counts.lod_instances["trees.lod0"] = 2;
  f.counts.lod_instances["trees.lod1"] = 1;
  f.error.mse = 1e-3 * (1.0 - ssim);
  f.error.psnr_db = f.error.mse > 0 ? 10 * std::log10(1 / f.error.mse) : INFINITY;
  f.error.ssim = ssim;
  f.error.share_exceeding = 1.0 - ssim;
  f.error.silhouette_coverage = 0.99;
  f.metrics["terrain.max_projected_error_px"] = 0.5 + i;
  return f;
}

BenchReport make_report() {
  BenchReport r;
  r.info.scene = "builtin:ground";
  r.info.camera_path = "flyover";
  r.info.frames = 2;
  r.info.width = 64;
  r.info.height = 36;
  r.info.sweep_groups = {{{"ground.resolution", {"17", "33", "65"}}}};
  r.info.reference = {{"ground.resolution", "513"}};
  r.info.machine.cpu_model = "Test <CPU> & co";
  r.info.cost = CostMetric::kGpuMs;
  r.info.error = ErrorMetric::kDssim;
  r.reference.reference = true;
  r.reference.setting = Setting{0, r.info.reference};
  r.reference.frame_records = {frame(0, 4.0, 1.0, 1000), frame(1, 4.0, 1.0, 1000)};
  r.reference.aggregate();
  // s000 cheap and bad, s001 dominated (slower and worse than s002), s002 good.
  const double ms[3] = {1.0, 3.0, 2.0};
  const double ssim[3] = {0.8, 0.85, 0.95};
  for (int i = 0; i < 3; ++i) {
    SettingResult s;
    s.setting = Setting{static_cast<std::size_t>(i), {{"ground.resolution", r.info.sweep_groups[0][0].values[i]}}};
    s.frame_records = {frame(0, ms[i], ssim[i], 100 * (i + 1)), frame(1, ms[i], ssim[i] - 0.1, 100 * (i + 1))};
    s.aggregate();
    s.thumbnail = "images/" + s.setting.id() + ".png";
    s.difference = "images/" + s.setting.id() + "-difference.png";
    s.reference_image = "images/" + s.setting.id() + "-reference.png";
    r.settings.push_back(std::move(s));
  }
  SettingResult failed;
  failed.setting = Setting{3, {{"ground.resolution", "9999"}}};
  failed.error_message = "ground.resolution: 9999 is above the maximum 2049";
  r.settings.push_back(std::move(failed));
  r.mark_pareto();
  return r;
}

TEST(Results, AggregateSumsCountsAndSummarisesErrors) {
  const BenchReport r = make_report();
  const SettingResult& s = r.settings[0];
  EXPECT_EQ(s.frames, 2);
  EXPECT_EQ(s.totals.triangles, 200u);
  EXPECT_EQ(s.totals.lod_instances.at("trees.lod0"), 4u);
  EXPECT_DOUBLE_EQ(s.ssim_mean, 0.75);
  EXPECT_DOUBLE_EQ(s.ssim_min, 0.7);
  EXPECT_EQ(s.worst_frame, 1);
  EXPECT_DOUBLE_EQ(s.gpu_ms.mean, 1.0);
  EXPECT_DOUBLE_EQ(s.frame_ms.mean, 1.5);
  ASSERT_TRUE(s.max_geometric_error_px().has_value());
  EXPECT_DOUBLE_EQ(*s.max_geometric_error_px(), 1.5);
  // The reference is identical to itself: infinite PSNR, SSIM 1.
  EXPECT_TRUE(std::isinf(r.reference.psnr_db));
  EXPECT_DOUBLE_EQ(r.reference.ssim_mean, 1.0);
}

TEST(Results, ParetoMarksNonDominatedSettings) {
  const BenchReport r = make_report();
  EXPECT_TRUE(r.settings[0].pareto);
  EXPECT_FALSE(r.settings[1].pareto);
  EXPECT_TRUE(r.settings[2].pareto);
  EXPECT_FALSE(r.settings[3].pareto);  // failed
  EXPECT_FALSE(r.reference.pareto);
}

TEST(Results, CsvHasOneRowPerSettingPlusReference) {
  const std::string csv = to_csv(make_report());
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 5);  // reference + 4 settings
  EXPECT_NE(header.find("ground.resolution"), std::string::npos);
  EXPECT_NE(header.find("instances.trees.lod1"), std::string::npos);
  EXPECT_NE(header.find("terrain.max_projected_error_px.max"), std::string::npos);
  EXPECT_NE(csv.find("reference"), std::string::npos);
  // Labels with commas are quoted.
  EXPECT_EQ(count(csv, "\"ground.resolution=9999\""), 0u);
  EXPECT_NE(csv.find("9999 is above the maximum"), std::string::npos);
}

TEST(Results, JsonCarriesRunMachineAndFrames) {
  const nlohmann::json j = to_json(make_report());
  EXPECT_EQ(j["run"]["scene"], "builtin:ground");
  EXPECT_EQ(j["settings"].size(), 4u);
  EXPECT_EQ(j["settings"][0]["frame_records"].size(), 2u);
  EXPECT_EQ(j["settings"][0]["totals"]["triangles"], 200);
  EXPECT_EQ(j["reference"]["image_error"]["psnr_db"], "inf");
  EXPECT_EQ(j["settings"][1]["pareto"], false);
  EXPECT_EQ(j["settings"][3]["error"], "ground.resolution: 9999 is above the maximum 2049");
  EXPECT_EQ(j["machine"]["cpu_model"], "Test <CPU> & co");
}

TEST(Report, HtmlHasOneRowPerSettingAndEscapes) {
  const BenchReport r = make_report();
  const std::string html = render_report_html(r, [](const std::string& rel) { return "data:" + rel; });
  EXPECT_EQ(count(html, "<tr class=\"setting"), 4u);
  EXPECT_EQ(count(html, "<tr class=\"reference"), 1u);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("Test &lt;CPU&gt; &amp; co"), std::string::npos);
  EXPECT_EQ(html.find("Test <CPU>"), std::string::npos);
  EXPECT_NE(html.find("src=\"data:images/s002-difference.png\""), std::string::npos);
  EXPECT_NE(html.find("failed: ground.resolution: 9999"), std::string::npos);
  EXPECT_NE(html.find("max geometric error px"), std::string::npos);
}

TEST(Report, PlotMarksTheFrontAndTheReference) {
  const std::string svg = report_plot_svg(make_report());
  EXPECT_EQ(count(svg, "class=\"point pareto\""), 2u);
  EXPECT_EQ(count(svg, "class=\"point\""), 1u);
  EXPECT_EQ(count(svg, "class=\"point reference\""), 1u);
  EXPECT_EQ(count(svg, "class=\"pareto-line\""), 1u);
}

TEST(SvgPlot, NonFinitePointsAreCountedNotDrawn) {
  const std::string svg = scatter_svg({{1, 2, "a", "", true, false}, {NAN, 1, "b", "", false, false}}, {"x", "y"});
  EXPECT_NE(svg.find("1 point(s) without finite values"), std::string::npos);
  EXPECT_EQ(count(svg, "<circle cx=\""), 1u + 2u);  // one point + two legend circles
}

TEST(SvgPlot, NiceTicksCoverTheRange) {
  const std::vector<double> t = nice_ticks(0.0, 7.3);
  ASSERT_GE(t.size(), 3u);
  EXPECT_LE(t.front(), 0.0);
  EXPECT_GE(t.back(), 7.3);
  const std::vector<double> flat = nice_ticks(2.0, 2.0);
  EXPECT_LT(flat.front(), 2.0);
  EXPECT_GT(flat.back(), 2.0);
}

TEST(Base64, Rfc4648Vectors) {
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64_encode(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(Results, NumbersForCsv) {
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(INFINITY), "inf");
  EXPECT_EQ(format_number(NAN), "nan");
  EXPECT_EQ(format_number(NAN, true), "");
}

}  // namespace
}  // namespace sylva::bench
