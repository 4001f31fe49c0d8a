#include "with_scene/paper_runs.hpp"

#include "paper_report.hpp"
#include "paper_tables.hpp"
#include "with_scene/scene_target.hpp"

#include <sylva/core/atomic_file.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <ostream>

namespace sylva::bench {
namespace {

constexpr int kPaperFrames = 8;       // frames of the static camera per setting (full mode)
constexpr int kQuickFrames = 2;
constexpr glm::ivec2 kQuickSize{256, 144};

// A table id as a folder name: "Fig. 4.7-4.10" -> "Fig-4.7-4.10" (links in paper.md stay plain).
std::string folder_name(const std::string& id) {
  std::string out;
  for (char c : id) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-';
    if (keep) out += c;
    else if (!out.empty() && out.back() != '-') out += '-';
  }
  return out;
}

RunSpec row_spec(const PaperTable& t, std::size_t row, const PaperRunOptions& o, const std::filesystem::path& folder,
                 const std::filesystem::path& stage_dir) {
  RunSpec spec;
  spec.factory = scene_text_factory(t.scene_json, fmt::format("<paper {} tab {}>", t.thesis, t.id), stage_dir);
  spec.scene = fmt::format("paper {} tab. {} stage", t.thesis, t.id);
  spec.suite = fmt::format("paper-{}", t.thesis);
  spec.description = fmt::format("Seed {} Tab. {}: {}; row {} = {}", t.thesis, t.id, t.title, t.row_header, t.rows[row].label);
  spec.overrides = t.overrides;
  spec.overrides.insert(spec.overrides.end(), t.rows[row].assignments.begin(), t.rows[row].assignments.end());
  for (const PaperColumn& c : t.columns) {
    if (!c.missing.empty()) continue;  // a variant Sylva lacks: shown with the thesis's numbers only
    std::vector<SweepAxis> group;
    for (const Assignment& a : c.assignments) group.push_back({a.path, {a.value}});
    spec.sweep_groups.push_back(std::move(group));
  }
  spec.reference = t.reference;
  spec.reference_note = t.reference.empty() ? "the row's setting (the table has no image-quality dimension)"
                                            : "the table's maximum-quality column";
  spec.camera_path = "start";  // the experiments' cameras are static
  spec.frames = o.quick ? kQuickFrames : kPaperFrames;
  spec.size = o.quick ? kQuickSize : t.size;
  spec.warmup = o.quick ? 1 : 2;
  spec.cost = default_cost_metric(o.gl_renderer);
  if (o.customise) o.customise(spec);  // the command line's --frames, --size, --cost, --set win
  spec.out = folder;
  spec.gl_renderer = o.gl_renderer;
  spec.gl_version = o.gl_version;
  return spec;
}

// Runs one table; rows beyond the first are skipped in quick mode.
PaperOutcome run_table(const PaperTable& t, const PaperRunOptions& o, const std::filesystem::path& thesis_dir,
                       CostMetric& cost, std::ostream& out) {
  PaperOutcome outcome;
  outcome.table = &t;
  outcome.rows.resize(t.rows.size());
  outcome.row_reports.resize(t.rows.size());
  if (!t.missing.empty()) return outcome;
  // The stage's own files (a generated mesh), next to where its scene is resolved.
  const std::filesystem::path stage_dir = thesis_dir / fmt::format("tab-{}", folder_name(t.id)) / "stage";
  for (const auto& [name, content] : t.stage_files) {
    std::error_code ec;
    std::filesystem::create_directories(stage_dir, ec);
    if (Status s = write_file_atomic(stage_dir / name, content); !s.ok()) {
      outcome.failure = s.error().message;
      return outcome;
    }
  }
  bool ran_one = false;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    if (!t.rows[r].missing.empty()) continue;  // shown with the thesis's numbers, not run
    if (o.quick && ran_one) break;             // --quick: the first row Sylva can run
    ran_one = true;
    const std::string rel = fmt::format("tab-{}/row-{}", folder_name(t.id), r);
    RunSpec spec = row_spec(t, r, o, thesis_dir / rel, stage_dir);
    cost = spec.cost;
    out << fmt::format("paper {} tab. {} row {} ({}): {} setting(s)\n", t.thesis, t.id, r, t.rows[r].label,
                       spec.sweep_groups.size());
    if (Status valid = validate_spec(spec); !valid.ok()) {
      outcome.failure = fmt::format("row {}: {}", t.rows[r].label, valid.error().message);
      return outcome;
    }
    auto report = run_sweep(spec, out);
    if (!report.ok()) {
      outcome.failure = fmt::format("row {}: {}", t.rows[r].label, report.error().message);
      return outcome;
    }
    for (const SettingResult& s : report->settings) {
      if (!s.error_message.empty()) outcome.failure = fmt::format("row {}: {}", t.rows[r].label, s.error_message);
    }
    if (Status written = write_report(*report, spec.out, o.embed_images); !written.ok()) {
      outcome.failure = written.error().message;
      return outcome;
    }
    // One result per column, in the table's order; a column Sylva lacks keeps a default result.
    std::vector<SettingResult> per_column(t.columns.size());
    std::size_t next = 0;
    for (std::size_t c = 0; c < t.columns.size() && next < report->settings.size(); ++c) {
      if (t.columns[c].missing.empty()) per_column[c] = report->settings[next++];
    }
    outcome.rows[r] = std::move(per_column);
    outcome.row_reports[r] = rel;
  }
  return outcome;
}

}  // namespace

int run_paper(const PaperRunOptions& o, std::ostream& out, std::ostream& err) {
  const std::vector<std::string> theses = o.which == "all" ? paper_names() : std::vector<std::string>{o.which};
  int status = 0;
  for (const std::string& thesis : theses) {
    std::vector<PaperTable> tables = paper_tables(thesis);
    if (!o.tables.empty()) {
      std::erase_if(tables, [&](const PaperTable& t) {
        return std::none_of(o.tables.begin(), o.tables.end(), [&](const std::string& id) { return paper_table_matches(t, id); });
      });
    }
    if (tables.empty()) {
      err << fmt::format("sylva-bench: --paper {}: not available yet: the tables of seed {} are not transcribed into "
                         "apps/bench/src/paper_tables.cpp (issue 20)\n",
                         thesis, thesis);
      if (status == 0) status = 3;
      continue;
    }
    const std::filesystem::path dir = o.out / fmt::format("paper-{}", thesis);
    std::vector<PaperOutcome> outcomes;
    CostMetric cost = default_cost_metric(o.gl_renderer);
    for (const PaperTable& t : tables) {
      outcomes.push_back(run_table(t, o, dir, cost, out));
      if (!outcomes.back().failure.empty()) {
        err << fmt::format("sylva-bench: paper {} tab. {}: {}\n", thesis, t.id, outcomes.back().failure);
        status = 1;
      }
    }
    MachineInfo machine = MachineInfo::collect();
    if (Status s = write_paper_report(dir, thesis, outcomes, cost, machine, o.gl_renderer); !s.ok()) {
      err << "sylva-bench: " << s.error().message << "\n";
      status = 1;
      continue;
    }
    out << fmt::format("sylva-bench: wrote {}\n", std::filesystem::absolute(dir / "paper.md").string());
  }
  return status;
}

}  // namespace sylva::bench
