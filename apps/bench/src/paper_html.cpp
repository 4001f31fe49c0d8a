#include "paper_html.hpp"

#include "report_html.hpp"
#include "svg_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::bench {
namespace {

std::string table_html(const PaperGrid& g) {
  std::string h = "<table>\n<tr>";
  for (std::size_t i = 0; i < g.header.size(); ++i) {
    h += fmt::format("<th{}>{}</th>", i == 0 ? " class=\"l\"" : "", html_escape(g.header[i]));
  }
  h += "<th class=\"l\">report</th></tr>\n";
  for (std::size_t r = 0; r < g.rows.size(); ++r) {
    h += "<tr>";
    for (std::size_t i = 0; i < g.rows[r].size(); ++i) {
      h += fmt::format("<td{}>{}</td>", i == 0 ? " class=\"l\"" : "", html_escape(g.rows[r][i]));
    }
    const std::string& rep = g.reports[r];
    h += rep.empty() ? fmt::format("<td class=\"l\">{}</td>", html_escape(g.not_run[r]))
                     : fmt::format("<td class=\"l\"><a href=\"{0}/report.html\">{0}</a></td>", html_escape(rep));
    h += "</tr>\n";
  }
  return h + "</table>\n";
}

// Thesis (T) and Sylva (S) ratios to the first row, against the row number; empty when fewer than
// two rows have a value on either side (nothing to compare: a --quick run, a one-row table).
std::string shape_svg(const PaperTable& t, const std::vector<PaperShape>& shapes) {
  std::vector<PlotPoint> points;
  std::vector<bool> sylva_rows(t.rows.size(), false);
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const PaperShape& s = shapes[i];
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const double x = static_cast<double>(r + 1);
      if (std::isfinite(s.thesis[r])) {
        points.push_back({x, s.thesis[r], fmt::format("T{}", i + 1),
                          fmt::format("thesis {}, {} {}: {:.2f}x", s.name, t.row_header, t.rows[r].label, s.thesis[r])});
      }
      if (std::isfinite(s.sylva[r])) {
        sylva_rows[r] = true;
        points.push_back({x, s.sylva[r], fmt::format("S{}", i + 1),
                          fmt::format("Sylva {}, {} {}: {:.2f}x", s.name, t.row_header, t.rows[r].label, s.sylva[r])});
      }
    }
  }
  if (std::count(sylva_rows.begin(), sylva_rows.end(), true) < 2) return {};
  PlotSpec spec{fmt::format("row (1 = {} {})", t.row_header, t.rows.front().label), "ratio to the first row"};
  spec.height = 320;
  spec.legend = false;
  std::string legend;
  for (std::size_t i = 0; i < shapes.size(); ++i) legend += fmt::format("{}{} = {}", i ? ", " : "", i + 1, shapes[i].name);
  return scatter_svg(points, spec) + fmt::format("<p class=\"note\">T = thesis, S = Sylva; {}.</p>\n", html_escape(legend));
}

// Every measured cell of a table with a reference: Sylva's time against its image error (DSSIM
// against the table's maximum-quality setting), one point per row and column; empty without a
// reference or a measured cell.
std::string error_time_svg(const PaperOutcome& o, CostMetric cost) {
  const PaperTable& t = *o.table;
  if (t.reference.empty()) return {};
  std::vector<PlotPoint> points;
  for (std::size_t r = 0; r < o.rows.size(); ++r) {
    if (!o.rows[r]) continue;
    for (std::size_t c = 0; c < o.rows[r]->size() && c < t.columns.size(); ++c) {
      const SettingResult& s = (*o.rows[r])[c];
      if (s.frames <= 0) continue;
      const double x = cost_of(s, cost), y = error_of(s, ErrorMetric::kDssim);
      const std::string label = fmt::format("{} {}", t.rows[r].label, t.columns[c].name);
      points.push_back({x, y, label, fmt::format("{} {}, {}: {:.4g} ms, DSSIM {:.4g}", t.row_header, t.rows[r].label,
                                                 t.columns[c].name, x, y)});
    }
  }
  if (points.empty()) return {};
  PlotSpec spec{axis_title(cost), "DSSIM against the table's reference"};
  spec.legend = false;
  std::vector<double> xs;
  for (const PlotPoint& p : points) xs.push_back(p.x);
  spec.log_x = wants_log_axis(xs);
  return scatter_svg(points, spec);
}

}  // namespace

std::string paper_html(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                       const MachineInfo& machine, const std::string& gl_renderer) {
  std::string h = html_page_start("sylva-bench --paper " + thesis, ".note{color:#555;font-size:13px} .failed{color:#b01010}\n");
  h += fmt::format("<h1>sylva-bench --paper {}</h1>\n", html_escape(thesis));
  h += fmt::format(
      "<p>Sylva: {} ({} logical cores), {}, {} build, {}. Sylva's ms are <code>{}</code> (mean over the frames of a "
      "static camera). Ratios (x) are to the table's first row: compare the shape of the tables, not absolute times "
      "across machines.</p>\n",
      html_escape(machine.cpu_model), machine.cpu_cores, html_escape(gl_renderer), html_escape(machine.build_type),
      html_escape(machine.date_utc), to_string(cost));
  for (const PaperOutcome& o : outcomes) {
    const PaperTable& t = *o.table;
    h += fmt::format("<h2>Tab. {}: {}</h2>\n<p class=\"note\">Thesis: {}.</p>\n", html_escape(t.id), html_escape(t.title),
                     html_escape(t.thesis_hardware));
    if (!t.missing.empty()) {
      h += fmt::format("<p>Not reproduced: {}.</p>\n", html_escape(t.missing));
      continue;
    }
    if (!o.failure.empty()) h += fmt::format("<p class=\"failed\">Failed: {}</p>\n", html_escape(o.failure));
    h += table_html(paper_grid(o, cost));
    h += fmt::format("<p class=\"note\">Differences from the thesis: {}</p>\n", html_escape(t.differences));
    for (const PaperColumn& c : t.columns) {
      if (!c.missing.empty()) h += fmt::format("<p class=\"note\">Column \"{}\" not run: {}.</p>\n", html_escape(c.name), html_escape(c.missing));
    }
    if (const std::string shape = shape_svg(t, paper_shapes(o, cost)); !shape.empty()) {
      h += "<h3>Shape: each quantity against its first row</h3>\n" + shape;
    }
    if (const std::string plot = error_time_svg(o, cost); !plot.empty()) {
      h += "<h3>Image error against time (each row's own plot with every setting is in its report)</h3>\n" + plot;
    }
  }
  return h + "</body>\n</html>\n";
}

}  // namespace sylva::bench
