#include "report_html.hpp"

#include "svg_plot.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

namespace sylva::bench {
namespace {

std::string num(double v, int digits = 3) {
  if (std::isnan(v)) return "&ndash;";
  if (std::isinf(v)) return v > 0 ? "&infin;" : "-&infin;";
  return fmt::format("{:.{}f}", v, digits);
}

std::string per_frame(std::uint64_t total, int frames) {
  if (frames <= 0) return "&ndash;";
  const double v = static_cast<double>(total) / frames;
  if (v >= 100.0) return fmt::format("{:.0f}", v);
  return fmt::format("{:.2f}", v);
}

std::string assignments_text(const std::vector<Assignment>& list) {
  if (list.empty()) return "(none)";
  std::string out;
  for (const Assignment& a : list) {
    if (!out.empty()) out += ", ";
    out += a.path + "=" + a.value;
  }
  return out;
}

std::string point_tooltip(const SettingResult& r, const RunInfo& info) {
  return fmt::format("{} {}: {} = {:.4g}, {} = {:.4g}", r.reference ? "reference" : r.setting.id(), r.setting.label(),
                     to_string(info.cost), cost_of(r, info.cost), to_string(info.error), error_of(r, info.error));
}

}  // namespace

std::string html_page_start(const std::string& title, const std::string& extra_css) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n" +
         fmt::format("<title>{}</title>\n", html_escape(title)) +
         "<style>\n"
         "body{font-family:sans-serif;margin:24px;color:#111;max-width:1400px}\n"
         "table{border-collapse:collapse;margin:8px 0 20px 0;font-size:13px}\n"
         "th,td{border:1px solid #ccc;padding:3px 7px;text-align:right}\n"
         "th{background:#f0f0f0} td.l,th.l{text-align:left}\n" +
         extra_css + "</style>\n</head>\n<body>\n";
}

std::string report_plot_svg(const BenchReport& report) {
  std::vector<PlotPoint> points;
  const RunInfo& info = report.info;
  if (report.reference.frames > 0) {
    points.push_back({cost_of(report.reference, info.cost), error_of(report.reference, info.error), "ref",
                      point_tooltip(report.reference, info), false, true});
  }
  for (const SettingResult& r : report.settings) {
    if (!r.error_message.empty()) continue;
    points.push_back({cost_of(r, info.cost), error_of(r, info.error), r.setting.id(), point_tooltip(r, info), r.pareto,
                      false});
  }
  PlotSpec spec{axis_title(info.cost), axis_title(info.error)};
  std::vector<double> xs;
  for (const PlotPoint& p : points) xs.push_back(p.x);
  spec.log_x = wants_log_axis(xs);
  return scatter_svg(points, spec);
}

std::string render_report_html(const BenchReport& report, const ImageSource& image_src) {
  const RunInfo& info = report.info;
  const MachineInfo& m = info.machine;
  std::string title = info.suite.empty() ? fmt::format("sylva-bench: {}", info.scene)
                                         : fmt::format("sylva-bench suite {}", info.suite);
  std::string h = html_page_start(title,
                                  "tr.reference td{background:#eef8ee} tr.pareto td.id{font-weight:bold;color:#b01010}\n"
                                  "tr.failed td{background:#fbeaea}\n"
                                  ".facts td{text-align:left} .facts th{text-align:left}\n"
                                  ".gallery{display:flex;flex-wrap:wrap;gap:14px}\n"
                                  ".card{border:1px solid #ccc;padding:6px;font-size:12px;max-width:800px}\n"
                                  ".card img{image-rendering:pixelated;margin-right:4px;border:1px solid #999}\n"
                                  ".note{color:#8a4b00}\n");
  h += fmt::format("<h1>{}</h1>\n", html_escape(title));
  if (!info.description.empty()) h += fmt::format("<p>{}</p>\n", html_escape(info.description));

  h += "<h2>Machine and build</h2>\n<table class=\"facts\">\n";
  auto fact = [&h](const char* k, const std::string& v) {
    h += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", k, html_escape(v));
  };
  fact("CPU", m.cpu_model);
  fact("Logical cores", std::to_string(m.cpu_cores));
  fact("GL renderer", m.gl_renderer);
  fact("GL version", m.gl_version);
  fact("OS", m.os);
  fact("Compiler", m.compiler);
  fact("Build type", m.build_type);
  fact("Date (UTC)", m.date_utc);
  h += "</table>\n<h2>Run</h2>\n<table class=\"facts\">\n";
  fact("Scene", info.scene);
  if (!info.suite.empty()) fact("Suite", info.suite);
  fact("Camera path", info.camera_path);
  fact("Frames", fmt::format("{} measured after {} warm-up frame(s), fixed step {:.4g} s", info.frames,
                             info.warmup_frames, info.dt));
  fact("Size", fmt::format("{}x{}", info.width, info.height));
  std::string sweeps;
  for (std::size_t g = 0; g < info.sweep_groups.size(); ++g) {
    if (g > 0) sweeps += " | then ";
    for (std::size_t k = 0; k < info.sweep_groups[g].size(); ++k) {
      const SweepAxis& a = info.sweep_groups[g][k];
      if (k > 0) sweeps += " × ";
      sweeps += a.path + " = ";
      for (std::size_t i = 0; i < a.values.size(); ++i) sweeps += (i ? ", " : "") + a.values[i];
    }
  }
  fact("Sweeps", sweeps.empty() ? "(none)" : sweeps);
  fact("Reference (maximum quality)", assignments_text(info.reference) +
                                          (info.reference_note.empty() ? "" : " — " + info.reference_note));
  fact("Overrides (--set)", assignments_text(info.overrides));
  fact("Difference threshold", fmt::format("{} (largest channel difference, colour values 0..1)", info.threshold));
  fact("Plot", fmt::format("{} against {}", to_string(info.error), to_string(info.cost)));
  h += "</table>\n";
  for (const std::string& n : info.notes) h += fmt::format("<p class=\"note\">Note: {}</p>\n", html_escape(n));

  h += "<h2>Image error against time</h2>\n";
  h += report_plot_svg(report);
  h += "<p>Lower left is better. Red points are on the Pareto front: no other setting is both faster and more "
       "accurate.</p>\n";

  // Table.
  std::set<std::string> lods;
  for (const auto& [k, v] : report.reference.totals.lod_instances) lods.insert(k);
  for (const SettingResult& r : report.settings) {
    for (const auto& [k, v] : r.totals.lod_instances) lods.insert(k);
  }
  bool any_geom = report.reference.max_geometric_error_px().has_value();
  for (const SettingResult& r : report.settings) any_geom = any_geom || r.max_geometric_error_px().has_value();

  h += "<h2>Results</h2>\n<table class=\"results\">\n<tr><th class=\"l\">id</th><th class=\"l\">setting</th>"
       "<th>frame ms mean</th><th>GPU ms mean</th><th>GPU ms p99</th><th>CPU ms mean</th><th>triangles / frame</th>"
       "<th>primitives / frame</th><th>fragments / frame</th><th>draw calls / frame</th><th>instances / frame</th>";
  for (const std::string& k : lods) h += fmt::format("<th>{} / frame</th>", html_escape(k));
  h += "<th>PSNR dB</th><th>SSIM mean</th><th>SSIM min</th><th>share &gt; threshold</th><th>silhouette coverage</th>";
  if (any_geom) h += "<th>max geometric error px</th>";
  h += "<th>Pareto</th></tr>\n";
  auto row = [&](const SettingResult& r) {
    std::string cls = r.reference ? "reference" : "setting";
    if (r.pareto) cls += " pareto";
    if (!r.error_message.empty()) cls += " failed";
    h += fmt::format("<tr class=\"{}\"><td class=\"l id\">{}</td><td class=\"l\">{}</td>", cls,
                     r.reference ? "ref" : r.setting.id(), html_escape(r.setting.label()));
    if (!r.error_message.empty()) {
      h += fmt::format("<td class=\"l\" colspan=\"{}\">failed: {}</td></tr>\n", 15 + lods.size() + (any_geom ? 1 : 0),
                       html_escape(r.error_message));
      return;
    }
    h += fmt::format("<td>{}</td><td>{}</td><td>{}</td><td>{}</td>", num(r.frame_ms.mean), num(r.gpu_ms.mean),
                     num(r.gpu_ms.p99), num(r.cpu_ms.mean));
    h += fmt::format("<td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>", per_frame(r.totals.triangles, r.frames),
                     per_frame(r.totals.primitives, r.frames), per_frame(r.totals.fragments, r.frames),
                     per_frame(r.totals.draw_calls, r.frames), per_frame(r.totals.instances, r.frames));
    for (const std::string& k : lods) {
      auto it = r.totals.lod_instances.find(k);
      h += fmt::format("<td>{}</td>", per_frame(it == r.totals.lod_instances.end() ? 0 : it->second, r.frames));
    }
    h += fmt::format("<td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>", num(r.psnr_db, 2), num(r.ssim_mean, 4),
                     num(r.ssim_min, 4), num(r.share_exceeding_mean, 4), num(r.silhouette_coverage_mean, 4));
    if (any_geom) {
      auto g = r.max_geometric_error_px();
      h += fmt::format("<td>{}</td>", g ? num(*g, 2) : "&ndash;");
    }
    h += fmt::format("<td>{}</td></tr>\n", r.reference ? "" : (r.pareto ? "&#9733;" : ""));
  };
  row(report.reference);
  for (const SettingResult& r : report.settings) row(r);
  h += "</table>\n";
  h += "<p>Counts are per frame, averaged over the camera path (the CSV and JSON hold exact sums). PSNR comes from the "
       "mean squared error over all frames; SSIM is the mean (and minimum) over frames of the luminance SSIM; "
       "silhouette coverage is the share of the reference's foreground pixels (depth written) that the setting also "
       "covers.</p>\n";

  // Images.
  h += "<h2>Images</h2>\n<p>For every setting, its frame with the lowest SSIM, the reference render of the same frame, "
       "and the difference heat map (black = equal, red, yellow, white = the threshold times four or more).</p>\n"
       "<div class=\"gallery\">\n";
  for (const SettingResult& r : report.settings) {
    if (!r.error_message.empty() || r.thumbnail.empty()) continue;
    h += fmt::format("<div class=\"card\" id=\"{}\"><div><b>{}</b> {} &mdash; frame {}, SSIM {}</div>\n", r.setting.id(),
                     r.setting.id(), html_escape(r.setting.label()), r.worst_frame, num(r.ssim_min, 4));
    auto img = [&](const std::string& rel, const char* alt) {
      if (rel.empty()) return;
      h += fmt::format("<img src=\"{}\" alt=\"{}\" title=\"{}\">", image_src(rel), alt, alt);
    };
    img(r.thumbnail, "setting");
    img(r.reference_image, "reference");
    img(r.difference, "difference");
    h += "\n</div>\n";
  }
  h += "</div>\n";
  h += "<p>Raw data: <a href=\"results.csv\">results.csv</a>, <a href=\"results.json\">results.json</a>.</p>\n";
  h += "</body>\n</html>\n";
  return h;
}

}  // namespace sylva::bench
