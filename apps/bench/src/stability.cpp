#include "stability.hpp"

#include "results.hpp"
#include "svg_plot.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/timer.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <ostream>

namespace sylva::bench {

StabilityReport::Totals StabilityReport::totals() const {
  Totals t;
  for (const StabilityRow& r : rows) {
    if (!r.available) {
      ++t.unavailable_modules;
    } else if (r.passed) {
      ++t.passed;
    } else {
      ++t.failed;
    }
  }
  return t;
}

std::vector<StabilityCase> all_stability_cases() {
  std::vector<StabilityCase> cases;
  add_core_stability_cases(cases);
  add_render_stability_cases(cases);
#ifdef SYLVA_BENCH_WITH_SCENE
  add_scene_stability_cases(cases);
#endif
#ifdef SYLVA_BENCH_WITH_TERRAIN
  add_terrain_stability_cases(cases);
#endif
#ifdef SYLVA_BENCH_WITH_GRASS
  add_grass_stability_cases(cases);
#endif
#ifdef SYLVA_BENCH_WITH_VEGETATION
  add_vegetation_stability_cases(cases);
#endif
#ifdef SYLVA_BENCH_WITH_VOXEL
  add_voxel_stability_cases(cases);
#endif
  return cases;
}

std::vector<std::string> missing_stability_modules() {
  std::vector<std::string> missing;
#ifndef SYLVA_BENCH_WITH_SCENE
  missing.push_back("scene");
#endif
#ifndef SYLVA_BENCH_WITH_TERRAIN
  missing.push_back("terrain");
#endif
#ifndef SYLVA_BENCH_WITH_GRASS
  missing.push_back("grass");
#endif
#ifndef SYLVA_BENCH_WITH_VEGETATION
  missing.push_back("vegetation");
#endif
#ifndef SYLVA_BENCH_WITH_VOXEL
  missing.push_back("voxel");
#endif
  return missing;
}

StabilityReport run_stability_cases(const std::vector<StabilityCase>& cases, std::ostream& log) {
  StabilityReport report;
  for (const StabilityCase& c : cases) {
    StabilityRow row;
    row.module = c.module;
    row.name = c.name;
    row.invariant = c.invariant;
    Stopwatch watch;
    const StabilityOutcome outcome = c.run();
    row.ms = watch.elapsed_ms();
    row.passed = outcome.passed && outcome.nan_count == 0;
    row.nan_count = outcome.nan_count;
    row.detail = outcome.detail;
    log << fmt::format("  {:<5} {}.{} ({:.0f} ms): {}{}\n", row.passed ? "pass" : "FAIL", c.module, c.name, row.ms,
                       row.detail, row.nan_count ? fmt::format(" [{} NaN]", row.nan_count) : "");
    report.rows.push_back(std::move(row));
  }
  return report;
}

StabilityReport run_stability(const StabilityOptions& options, std::ostream& log) {
  std::vector<StabilityCase> cases;
  for (StabilityCase& c : all_stability_cases()) {
    if (!options.only_module || c.module == *options.only_module) cases.push_back(std::move(c));
  }
  log << fmt::format("stability: {} case(s)\n", cases.size());
  StabilityReport report = run_stability_cases(cases, log);
  for (const std::string& m : missing_stability_modules()) {
    if (options.only_module && *options.only_module != m) continue;
    StabilityRow row;
    row.module = m;
    row.name = "(module not available)";
    row.invariant = "the module is not part of this build, so none of its cases ran";
    row.available = false;
    log << fmt::format("  n/a   {}: module not available in this build\n", m);
    report.rows.push_back(std::move(row));
  }
  return report;
}

namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

const char* status_of(const StabilityRow& r) { return !r.available ? "not available" : r.passed ? "pass" : "fail"; }

}  // namespace

std::string stability_csv(const StabilityReport& report) {
  std::string out = "module,case,status,nan_count,ms,invariant,detail\n";
  for (const StabilityRow& r : report.rows) {
    out += fmt::format("{},{},{},{},{:.3f},{},{}\n", csv_field(r.module), csv_field(r.name), status_of(r), r.nan_count,
                       r.ms, csv_field(r.invariant), csv_field(r.detail));
  }
  return out;
}

std::string stability_json(const StabilityReport& report, const std::string& gl_renderer) {
  const MachineInfo m = MachineInfo::collect();
  nlohmann::json j;
  j["machine"] = {{"cpu_model", m.cpu_model}, {"cpu_cores", m.cpu_cores}, {"gl_renderer", gl_renderer},
                  {"build_type", m.build_type}, {"date_utc", m.date_utc}};
  nlohmann::json rows = nlohmann::json::array();
  for (const StabilityRow& r : report.rows) {
    rows.push_back({{"module", r.module}, {"case", r.name}, {"status", status_of(r)}, {"passed", r.passed},
                    {"available", r.available}, {"nan_count", r.nan_count}, {"ms", r.ms},
                    {"invariant", r.invariant}, {"detail", r.detail}});
  }
  j["cases"] = std::move(rows);
  const StabilityReport::Totals t = report.totals();
  j["totals"] = {{"passed", t.passed}, {"failed", t.failed}, {"unavailable_modules", t.unavailable_modules}};
  return j.dump(2) + "\n";
}

std::string stability_html(const StabilityReport& report, const std::string& gl_renderer) {
  const MachineInfo m = MachineInfo::collect();
  const StabilityReport::Totals t = report.totals();
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                  "<title>sylva-bench stability</title>\n<style>\n"
                  "body{font-family:sans-serif;margin:24px;color:#111}\n"
                  "table{border-collapse:collapse;font-size:13px}\n"
                  "th,td{border:1px solid #ccc;padding:3px 7px;text-align:left;vertical-align:top}\n"
                  "th{background:#f0f0f0} td.n{text-align:right}\n"
                  "tr.pass td.s{background:#dff2df} tr.fail td.s{background:#f6d4d4;font-weight:bold}\n"
                  "tr.na td{color:#777;background:#f6f6f6}\n"
                  "</style>\n</head>\n<body>\n<h1>sylva-bench stability report</h1>\n";
  h += fmt::format("<p>{} passed, {} failed, {} module(s) not available. Machine: {} ({} logical cores), {}; build {}; "
                   "{}.</p>\n",
                   t.passed, t.failed, t.unavailable_modules, html_escape(m.cpu_model), m.cpu_cores,
                   html_escape(gl_renderer), html_escape(m.build_type), m.date_utc);
  h += "<table class=\"stability\">\n<tr><th>module</th><th>case</th><th>status</th><th>NaN</th><th>ms</th>"
       "<th>invariant checked</th><th>measured</th></tr>\n";
  for (const StabilityRow& r : report.rows) {
    const char* cls = !r.available ? "na" : r.passed ? "pass" : "fail";
    h += fmt::format("<tr class=\"{}\"><td>{}</td><td>{}</td><td class=\"s\">{}</td><td class=\"n\">{}</td>"
                     "<td class=\"n\">{:.1f}</td><td>{}</td><td>{}</td></tr>\n",
                     cls, html_escape(r.module), html_escape(r.name), status_of(r), r.nan_count, r.ms,
                     html_escape(r.invariant), html_escape(r.detail));
  }
  h += "</table>\n</body>\n</html>\n";
  return h;
}

Status write_stability_report(const StabilityReport& report, const std::filesystem::path& out,
                              const std::string& gl_renderer) {
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create the output folder: {}", out.string(), ec.message()));
  SYLVA_TRY(write_file_atomic(out / "stability.csv", stability_csv(report)));
  SYLVA_TRY(write_file_atomic(out / "stability.json", stability_json(report, gl_renderer)));
  return write_file_atomic(out / "stability.html", stability_html(report, gl_renderer));
}

}  // namespace sylva::bench
