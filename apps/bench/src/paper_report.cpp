#include "paper_report.hpp"

#include "paper_html.hpp"

#include <sylva/core/atomic_file.hpp>

#include <fmt/format.h>

#include <cmath>

namespace sylva::bench {
namespace {

std::string number(double v) {
  if (!std::isfinite(v)) return "–";
  if (std::fabs(v) >= 100.0) return fmt::format("{:.0f}", v);
  if (std::fabs(v) >= 10.0) return fmt::format("{:.1f}", v);
  return fmt::format("{:.3g}", v);
}

std::string ratio(double v, double first) {
  if (!std::isfinite(v) || !std::isfinite(first) || first == 0.0) return "–";
  return fmt::format("{:.2f}x", v / first);
}

// The thesis's value in row r, as ms where the thesis gave FPS.
double thesis_value(const PaperValue& v, std::size_t r) {
  if (r >= v.thesis.size()) return std::nan("");
  return v.thesis_fps ? 1000.0 / v.thesis[r] : v.thesis[r];
}

// Sylva's value of (column, value) in row r, NaN when that row did not run.
double sylva_value(const PaperOutcome& o, std::size_t r, std::size_t c, const PaperValue& v, CostMetric cost) {
  if (r >= o.rows.size() || !o.rows[r] || c >= o.rows[r]->size()) return std::nan("");
  const double value = paper_measure((*o.rows[r])[c], v, cost);
  const auto base = static_cast<std::size_t>(v.minus_column);
  if (v.minus_column < 0 || base >= o.rows[r]->size()) return value;
  return value - paper_measure((*o.rows[r])[base], v, cost);
}

// The first row with a value (the ratio's base): the thesis's first row, Sylva's first row that ran.
double first_sylva(const PaperOutcome& o, std::size_t c, const PaperValue& v, CostMetric cost) {
  for (std::size_t r = 0; r < o.table->rows.size(); ++r) {
    const double x = sylva_value(o, r, c, v, cost);
    if (std::isfinite(x)) return x;
  }
  return std::nan("");
}

std::string heading(const std::string& thesis, CostMetric cost, const MachineInfo& m, const std::string& gl_renderer) {
  return fmt::format(
      "# sylva-bench --paper {}\n\nSylva: {} ({} logical cores), {}, {} build, {}. Sylva's ms are `{}` (mean over "
      "the frames of a static camera). Ratios (x) are to the table's first row: compare the shape of the tables, not "
      "absolute times across machines.\n\n",
      thesis, m.cpu_model, m.cpu_cores, gl_renderer, m.build_type, m.date_utc, to_string(cost));
}

// A value as measured (ms: the cost metric's mean; counts per frame; metrics their mean).
double unscaled_measure(const SettingResult& result, const PaperValue& value, CostMetric cost) {
  const auto per_frame = [&](std::uint64_t total) {
    return result.frames > 0 ? static_cast<double>(total) / result.frames : std::nan("");
  };
  switch (value.measure) {
    case PaperMeasure::kMs: return cost_of(result, cost);
    case PaperMeasure::kFragments: return per_frame(result.totals.fragments);
    case PaperMeasure::kPrimitives: return per_frame(result.totals.primitives);
    case PaperMeasure::kMetric: {
      const auto it = result.metrics.find(value.metric);
      return it == result.metrics.end() ? std::nan("") : it->second.mean;
    }
  }
  return std::nan("");
}

}  // namespace

double paper_measure(const SettingResult& result, const PaperValue& value, CostMetric cost) {
  return value.scale * unscaled_measure(result, value, cost);
}

PaperGrid paper_grid(const PaperOutcome& o, CostMetric cost) {
  const PaperTable& t = *o.table;
  PaperGrid g;
  // Header: row | per column and value: thesis, x, Sylva, x; then DSSIM per column when the table
  // has an image-quality dimension.
  g.header.push_back(t.row_header);
  for (const PaperColumn& c : t.columns) {
    for (const PaperValue& v : c.values) {
      g.header.push_back(fmt::format("{} {} thesis{}", c.name, v.name, v.thesis_fps ? " (1000/FPS)" : ""));
      g.header.push_back("x");
      g.header.push_back(fmt::format("{} {} Sylva", c.name, v.name));
      g.header.push_back("x");
    }
  }
  if (!t.reference.empty()) {
    for (const PaperColumn& c : t.columns) g.header.push_back(c.name + " DSSIM");
  }
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    std::vector<std::string> cells{t.rows[r].label};
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      for (const PaperValue& v : t.columns[c].values) {
        const double th = thesis_value(v, r);
        const double sy = sylva_value(o, r, c, v, cost);
        cells.insert(cells.end(), {number(th), ratio(th, thesis_value(v, 0)), number(sy), ratio(sy, first_sylva(o, c, v, cost))});
      }
    }
    if (!t.reference.empty()) {
      for (std::size_t c = 0; c < t.columns.size(); ++c) {
        const bool ran = r < o.rows.size() && o.rows[r] && c < o.rows[r]->size();
        cells.push_back(ran ? number(error_of((*o.rows[r])[c], ErrorMetric::kDssim)) : std::string("–"));
      }
    }
    g.rows.push_back(std::move(cells));
    g.reports.push_back(r < o.row_reports.size() ? o.row_reports[r] : "");
    g.not_run.push_back(t.rows[r].missing.empty() ? "not run" : "not run: " + t.rows[r].missing);
  }
  return g;
}

std::vector<PaperShape> paper_shapes(const PaperOutcome& o, CostMetric cost) {
  const PaperTable& t = *o.table;
  std::vector<PaperShape> shapes;
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    for (const PaperValue& v : t.columns[c].values) {
      PaperShape s{t.columns[c].name + " " + v.name, {}, {}};
      const double th0 = thesis_value(v, 0), sy0 = first_sylva(o, c, v, cost);
      for (std::size_t r = 0; r < t.rows.size(); ++r) {
        s.thesis.push_back(thesis_value(v, r) / th0);
        s.sylva.push_back(sylva_value(o, r, c, v, cost) / sy0);
      }
      shapes.push_back(std::move(s));
    }
  }
  return shapes;
}

std::string paper_markdown(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                           const MachineInfo& machine, const std::string& gl_renderer) {
  std::string md = heading(thesis, cost, machine, gl_renderer);
  for (const PaperOutcome& o : outcomes) {
    const PaperTable& t = *o.table;
    md += fmt::format("## Tab. {}: {}\n\nThesis: {}.\n\n", t.id, t.title, t.thesis_hardware);
    if (!t.missing.empty()) {
      md += fmt::format("Not reproduced: {}.\n\n", t.missing);
      continue;
    }
    if (!o.failure.empty()) md += fmt::format("**Failed:** {}\n\n", o.failure);
    const PaperGrid g = paper_grid(o, cost);
    std::string head = "|", rule = "|";
    for (std::size_t i = 0; i < g.header.size(); ++i) {
      head += " " + g.header[i] + " |";
      rule += i == 0 ? "---|" : "---:|";
    }
    md += head + " report |\n" + rule + "---|\n";
    for (std::size_t r = 0; r < g.rows.size(); ++r) {
      std::string line = "|";
      for (const std::string& cell : g.rows[r]) line += " " + cell + " |";
      const std::string& rep = g.reports[r];
      md += line + " " + (rep.empty() ? g.not_run[r] : fmt::format("[{0}]({0}/report.html)", rep)) + " |\n";
    }
    md += fmt::format("\nDifferences from the thesis: {}\n", t.differences);
    for (const PaperColumn& c : t.columns) {
      if (!c.missing.empty()) md += fmt::format("Column \"{}\" not run: {}.\n", c.name, c.missing);
    }
    md += "\n";
  }
  return md;
}

nlohmann::json paper_json(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                          const MachineInfo& machine, const std::string& gl_renderer) {
  auto finite_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json tables = nlohmann::json::array();
  for (const PaperOutcome& o : outcomes) {
    const PaperTable& t = *o.table;
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      nlohmann::json cells = nlohmann::json::object();
      for (std::size_t c = 0; c < t.columns.size(); ++c) {
        for (const PaperValue& v : t.columns[c].values) {
          cells[t.columns[c].name + " " + v.name] = {
              {"thesis", finite_or_null(thesis_value(v, r))},
              {"sylva", finite_or_null(sylva_value(o, r, c, v, cost))},
              {"minus_baseline", v.minus_column >= 0},
              {"column_missing", t.columns[c].missing}};
        }
      }
      // Instances per LOD level per frame, per column: what the column's setting selected.
      nlohmann::json lods = nlohmann::json::object();
      for (std::size_t c = 0; r < o.rows.size() && o.rows[r] && c < o.rows[r]->size(); ++c) {
        const SettingResult& s = (*o.rows[r])[c];
        for (const auto& [level, count] : s.totals.lod_instances) {
          lods[t.columns[c].name][level] = s.frames > 0 ? static_cast<double>(count) / s.frames : 0.0;
        }
      }
      rows.push_back({{"label", t.rows[r].label}, {"values", cells}, {"lod_instances_per_frame", lods},
                      {"report", r < o.row_reports.size() ? o.row_reports[r] : ""}});
    }
    tables.push_back({{"table", t.id}, {"title", t.title}, {"thesis_hardware", t.thesis_hardware},
                      {"rows", rows}, {"missing", t.missing}, {"failure", o.failure}, {"differences", t.differences}});
  }
  return {{"thesis", thesis},
          {"cost_metric", to_string(cost)},
          {"machine", {{"cpu", machine.cpu_model}, {"cores", machine.cpu_cores}, {"gl_renderer", gl_renderer},
                       {"build", machine.build_type}, {"date_utc", machine.date_utc}}},
          {"tables", tables}};
}

Status write_paper_report(const std::filesystem::path& folder, const std::string& thesis,
                          const std::vector<PaperOutcome>& outcomes, CostMetric cost, const MachineInfo& machine,
                          const std::string& gl_renderer) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create ({})", folder.string(), ec.message()));
  SYLVA_TRY(write_file_atomic(folder / "paper.md", paper_markdown(thesis, outcomes, cost, machine, gl_renderer)));
  SYLVA_TRY(write_file_atomic(folder / "paper.html", paper_html(thesis, outcomes, cost, machine, gl_renderer)));
  return write_file_atomic(folder / "paper.json", paper_json(thesis, outcomes, cost, machine, gl_renderer).dump(2) + "\n");
}

}  // namespace sylva::bench
