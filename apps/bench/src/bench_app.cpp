#include "bench_app.hpp"

#include "bench_options.hpp"
#include "runner.hpp"
#include "scene_source.hpp"
#include "stability.hpp"
#include "suites.hpp"
#ifdef SYLVA_BENCH_WITH_SCENE
#include "with_scene/paper_runs.hpp"
#include "with_scene/species_suite.hpp"
#include "with_scene/stream_suite.hpp"
#endif
#include "svg_plot.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/output_check.hpp>

#include <sylva/render/gl_context.hpp>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <ostream>

namespace sylva::bench {
namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitUnavailable = 3;

void print_params(BenchTarget& target, std::ostream& out) {
  for (const ParamDescriptor& p : target.params()) {
    std::string range;
    if (std::isfinite(p.info.min) || std::isfinite(p.info.max)) range = fmt::format(" [{}..{}]", p.info.min, p.info.max);
    out << fmt::format("{} = {} ({}{}{}{}){}{}\n", p.path, p.get_string(), p.type_name(), range,
                       *p.info.unit ? " " : "", p.info.unit, *p.info.help ? "  " : "", p.info.help);
  }
}

void print_paths(BenchTarget& target, std::ostream& out) {
  for (const CameraPathInfo& p : target.camera_paths()) out << fmt::format("{}: {}\n", p.name, p.description);
}

// Issue 18: a terrain's triangles per covered pixel beside the drawn chunks' projected-error
// histogram (metrics "terrain.triangles_per_pixel", "terrain.error_hist.chunks.<bin>" from the
// scene target), one line per setting that has them; means over the frames (every frame's
// figures are in results.json).
void print_terrain_lod_summary(const BenchReport& report, std::ostream& out) {
  const std::string chunks_prefix = "terrain.error_hist.chunks.";
  for (const SettingResult& r : report.settings) {
    auto tpp = r.metrics.find("terrain.triangles_per_pixel");
    if (tpp == r.metrics.end()) continue;
    std::string hist;
    for (const auto& [name, m] : r.metrics) {
      if (name.rfind(chunks_prefix, 0) != 0) continue;
      const std::string bin = name.substr(chunks_prefix.size());
      const auto tri = r.metrics.find("terrain.error_hist.triangles." + bin);
      hist += fmt::format(" {} {:.1f} ({:.0f} tri)", bin, m.mean, tri == r.metrics.end() ? 0.0 : tri->second.mean);
    }
    out << fmt::format("terrain {}{}: triangles/pixel mean {:.3f} max {:.3f}; chunks by projected error:{}\n",
                       r.setting.label(), r.reference ? " (reference)" : "", tpp->second.mean, tpp->second.max, hist);
  }
}

// Runs one sweep and writes its outputs; returns the exit code.
int run_and_write(const RunSpec& spec, bool embed, std::ostream& out, std::ostream& err) {
  Status valid = validate_spec(spec);
  if (!valid.ok()) {
    err << "sylva-bench: " << valid.error().message << "\n";
    return kExitUsage;
  }
  auto report = run_sweep(spec, out);
  if (!report.ok()) {
    err << "sylva-bench: " << report.error().message << "\n";
    return kExitFailed;
  }
  Status written = write_report(*report, spec.out, embed);
  if (!written.ok()) {
    err << "sylva-bench: " << written.error().message << "\n";
    return kExitFailed;
  }
  print_terrain_lod_summary(*report, out);
  out << fmt::format("sylva-bench: wrote {}\n", std::filesystem::absolute(spec.out / "report.html").string());
  for (const SettingResult& r : report->settings) {
    if (!r.error_message.empty()) return kExitFailed;
  }
  return kExitOk;
}

void apply_common(const BenchOptions& o, RunSpec& spec) {
  if (o.frames) spec.frames = *o.frames;
  if (o.size) spec.size = *o.size;
  if (o.camera_path) spec.camera_path = o.camera_path;
  spec.warmup = o.warmup;
  spec.dt = o.dt;
  spec.threshold = o.threshold;
  if (o.cost) spec.cost = *o.cost;
  spec.error = o.error;
  for (const Assignment& a : o.overrides) spec.overrides.push_back(a);
}

struct SuiteOutcome {
  std::string name;
  std::string text;  // description, or why it is not available / failed
  bool ran = false;
};

// --suite all: one page linking each suite's report, with the ones that did not run and why.
std::string suites_index_html(const std::vector<SuiteOutcome>& outcomes) {
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>sylva-bench suites</title>\n"
                  "<style>body{font-family:sans-serif;margin:24px} td,th{border:1px solid #ccc;padding:4px 8px;"
                  "text-align:left;vertical-align:top} table{border-collapse:collapse} .na{color:#a00}</style>\n"
                  "</head>\n<body>\n<h1>sylva-bench suites</h1>\n<table>\n<tr><th>suite</th><th>report</th><th>what it "
                  "measures</th></tr>\n";
  for (const SuiteOutcome& s : outcomes) {
    if (s.ran) {
      h += fmt::format("<tr><td>{0}</td><td><a href=\"{0}/report.html\">{0}/report.html</a></td><td>{1}</td></tr>\n",
                       html_escape(s.name), html_escape(s.text));
    } else {
      h += fmt::format("<tr class=\"na\"><td>{}</td><td>none</td><td class=\"na\">{}</td></tr>\n", html_escape(s.name),
                       html_escape(s.text));
    }
  }
  return h + "</table>\n</body>\n</html>\n";
}

#ifdef SYLVA_BENCH_WITH_SCENE
// The row-printing suites (species_suite.hpp, stream_suite.hpp) take the same command-line
// options: warm-up, --set, --out, and --size / --frames where given.
template <class SuiteOptions, class Run>
int run_row_suite(const BenchOptions& o, const std::filesystem::path& out_dir, Run run, std::ostream& out, std::ostream& err) {
  SuiteOptions so{.warmup = o.warmup, .overrides = o.overrides, .out = out_dir};
  if (o.size) so.size = *o.size;
  if (o.frames) so.frames = *o.frames;
  return run(so, out, err);
}
#endif

}  // namespace

int run_bench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  auto parsed = parse_bench_options(args);
  if (!parsed.ok()) {
    err << "sylva-bench: " << parsed.error().message << "\n";
    return kExitUsage;
  }
  const BenchOptions& o = *parsed;
  if (o.help) {
    out << bench_usage();
    return kExitOk;
  }

  // Listing needs no GL: parameters and paths exist before prepare().
  if (o.list_params || o.list_camera_paths) {
    TargetFactory factory;
    if (o.scene) {
      auto f = open_scene(*o.scene);
      if (!f.ok()) {
        err << "sylva-bench: " << f.error().message << "\n";
        return kExitUsage;
      }
      factory = *f;
    } else {
      auto suite = make_suite(*o.suite);
      if (!suite.ok()) {
        err << "sylva-bench: " << suite.error().message << "\n";
        return suite.error().code == ErrorCode::kUnsupported ? kExitUnavailable : kExitUsage;
      }
      factory = suite->run.factory;
    }
    auto target = factory();
    if (!target.ok()) {
      err << "sylva-bench: " << target.error().message << "\n";
      return kExitUsage;
    }
    if (o.list_params) print_params(**target, out);
    if (o.list_camera_paths) print_paths(**target, out);
    return kExitOk;
  }

  // Everything else writes into --out: a folder that cannot be made or written fails now, not
  // after every setting (or the whole stability report) was rendered.
  if (Status writable = check_output_folder(o.out); !writable.ok()) {
    err << "sylva-bench: --out " << writable.error().message << "\n";
    return kExitFailed;
  }

  // Everything else renders: one headless context for the whole run.
  auto context = render::GlContext::create_headless({.debug = false});
  if (!context.ok()) {
    err << "sylva-bench: " << context.error().message << "\n";
    return kExitFailed;
  }
  const std::filesystem::path out_dir = o.out;
  int status = kExitOk;
  auto merge = [&status](int s) {
    // The most severe outcome wins: usage errors, then failures, then unavailable modules.
    auto rank = [](int code) { return code == kExitUsage ? 3 : code == kExitFailed ? 2 : code == kExitUnavailable ? 1 : 0; };
    if (rank(s) > rank(status)) status = s;
  };

  if (o.scene) {
    auto factory = open_scene(*o.scene);
    if (!factory.ok()) {
      err << "sylva-bench: " << factory.error().message << "\n";
      return kExitUsage;
    }
    RunSpec spec;
    spec.factory = *factory;
    spec.scene = *o.scene;
    if (!o.sweeps.empty()) spec.sweep_groups.push_back(o.sweeps);
    spec.reference = o.reference;
    spec.frames = kDefaultFrames;
    spec.size = kDefaultSize;
    apply_common(o, spec);
    spec.out = out_dir;
    spec.gl_renderer = context->renderer();
    spec.gl_version = context->version();
    if (!o.cost) spec.cost = default_cost_metric(spec.gl_renderer);
    merge(run_and_write(spec, o.embed_images, out, err));
  }

  if (o.suite && (*o.suite == "species" || *o.suite == "stream")) {  // rows, not an error/time sweep
#ifdef SYLVA_BENCH_WITH_SCENE
    merge(*o.suite == "species" ? run_row_suite<SpeciesSuiteOptions>(o, out_dir, run_species_suite, out, err)
                                : run_row_suite<StreamSuiteOptions>(o, out_dir, run_stream_suite, out, err));
#else
    err << "sylva-bench: suite " << *o.suite
        << ": module not available: it needs the scene module, which is not part of this build\n";
    merge(kExitUnavailable);
#endif
  } else if (o.suite) {
    const std::vector<std::string> names = *o.suite == "all" ? suite_names() : std::vector<std::string>{*o.suite};
    std::vector<SuiteOutcome> outcomes;
    for (const std::string& name : names) {
      auto suite = make_suite(name);
      if (!suite.ok()) {
        err << fmt::format("sylva-bench: suite {}: {}\n", name, suite.error().message);
        merge(suite.error().code == ErrorCode::kUnsupported ? kExitUnavailable : kExitFailed);
        outcomes.push_back({name, suite.error().message, false});
        continue;
      }
      RunSpec spec = suite->run;
      apply_common(o, spec);
      spec.out = names.size() > 1 ? out_dir / name : out_dir;
      spec.gl_renderer = context->renderer();
      spec.gl_version = context->version();
      if (!o.cost) spec.cost = default_cost_metric(spec.gl_renderer);
      out << fmt::format("suite {}: {}\n", name, spec.description);
      const int code = run_and_write(spec, o.embed_images, out, err);
      merge(code);
      outcomes.push_back({name, code == kExitOk ? spec.description : fmt::format("failed (exit code {})", code),
                          code == kExitOk});
    }
    if (names.size() > 1) {
      Status index = write_file_atomic(out_dir / "index.html", suites_index_html(outcomes));
      if (!index.ok()) {
        err << "sylva-bench: " << index.error().message << "\n";
        merge(kExitFailed);
      }
    }
  }

  if (o.paper) {
#ifdef SYLVA_BENCH_WITH_SCENE
    PaperRunOptions po;
    po.which = *o.paper;
    po.quick = o.quick;
    po.tables = o.tables;
    po.out = out_dir;
    po.customise = [&o](RunSpec& spec) { apply_common(o, spec); };
    po.embed_images = o.embed_images;
    po.gl_renderer = context->renderer();
    po.gl_version = context->version();
    merge(run_paper(po, out, err));
#else
    err << "sylva-bench: --paper needs the scene module, which is not part of this build\n";
    merge(kExitUnavailable);
#endif
  }

  if (o.stability) {
    StabilityOptions so;
    if (o.suite && *o.suite != "all") so.only_module = *o.suite == "trees" ? "vegetation" : *o.suite;
    const StabilityReport report = run_stability(so, out);
    Status written = write_stability_report(report, out_dir, context->renderer());
    if (!written.ok()) {
      err << "sylva-bench: " << written.error().message << "\n";
      merge(kExitFailed);
    } else {
      out << fmt::format("sylva-bench: wrote {}\n", std::filesystem::absolute(out_dir / "stability.html").string());
    }
    const StabilityReport::Totals t = report.totals();
    out << fmt::format("stability: {} passed, {} failed, {} module(s) not available\n", t.passed, t.failed,
                       t.unavailable_modules);
    // Modules that are not built are listed in the table as not available; they do not fail the
    // run (only --suite asks for a specific module).
    if (t.failed > 0) merge(kExitFailed);
  }
  return status;
}

}  // namespace sylva::bench
