#include "script_runner.hpp"

#include "terrain_import.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/output_check.hpp>

#include <fmt/format.h>

#include <charconv>
#include <map>
#include <thread>

namespace sylva::editor {
namespace {

double number(const std::string& s) {
  double v = 0.0;
  std::from_chars(s.data(), s.data() + s.size(), v);  // validated by the parser
  return v;
}

std::filesystem::path resolve(const std::filesystem::path& base, const std::string& p) {
  const std::filesystem::path path(p);
  return path.is_absolute() || base.empty() ? path : base / path;
}

// What a run remembers between commands.
struct RunState {
  std::map<std::filesystem::path, int> reloads_seen;  // wait_reload: the count at the last wait
  TerrainImport import;                                // import_terrain / wait_import / cancel_import
};

// import_terrain PATH [bake OUT [hold]]: reads the source (waiting for it), then uses it or
// starts the bake (with hold: returns once the bake is parked at its first progress report).
Status import_terrain(EditorSession& s, const std::vector<std::string>& a, const std::filesystem::path& base,
                      std::ostream& out, TerrainImport& import) {
  SYLVA_TRY(import.start_read(s, resolve(base, a[0])));
  auto read = import.wait(s);
  if (!read || !read->ok()) return read ? Status(read->error()) : make_error(ErrorCode::kInvalidArgument, "nothing was read");
  out << "import: " << **read << "\n";
  if (a.size() == 1) return import.use_directly(s);
  const bool hold = a.size() == 4;
  SYLVA_TRY(import.start_bake(s, resolve(base, a[2]), hold));
  if (hold) import.wait_until_held();
  return {};
}

// wait_import [MAX_FRAMES]: frames go on while the bake runs (as in the window); progress is
// written each time it passes another 10 %.
Status wait_import(EditorSession& s, int max_frames, std::ostream& out, TerrainImport& import) {
  import.release();
  int frames = 0, shown = -1;
  for (; frames < max_frames && import.busy(); ++frames) {
    if (import.poll(s)) break;
    const int decile = static_cast<int>(import.progress() * 10.0f);
    if (decile > shown) {
      shown = decile;
      out << fmt::format("import: bake {} % (ETA {:.1f} s)\n", decile * 10, std::max(import.eta_s(), 0.0));
    }
    SYLVA_TRY(s.render_frame(1.0 / 30.0));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // a window's frame pacing
  }
  if (import.busy()) return make_error(ErrorCode::kLimit, fmt::format("the bake did not finish within {} frames", max_frames));
  auto done = import.take_last();
  if (!done) return make_error(ErrorCode::kInvalidArgument, "no import is running");
  out << "import: " << frames << " frames drawn during the bake\n";
  if (!done->ok()) return done->error();
  out << "import: " << **done << "\n";
  return {};
}

// cancel_import: the bake stops at its next chunk; the scene is left as it was.
Status cancel_import(EditorSession& s, std::ostream& out, TerrainImport& import) {
  if (!import.busy()) {
    auto done = import.take_last();
    if (done && done->ok()) return make_error(ErrorCode::kInvalidArgument, "the import finished before the cancel: " + **done);
    return make_error(ErrorCode::kInvalidArgument, "no import is running");
  }
  import.cancel();
  auto done = import.wait(s);
  if (done && done->ok()) return make_error(ErrorCode::kInvalidArgument, "the import finished before the cancel: " + **done);
  if (!done || done->error().code != ErrorCode::kCancelled) return done ? Status(done->error()) : Status(ok_status());
  out << "import: " << done->error().message << "\n";
  return {};
}

Status run_one(EditorSession& s, const ScriptCommand& c, const std::filesystem::path& base, std::ostream& out,
               const ScriptHooks& hooks, RunState& state) {
  const auto& a = c.args;
  if (c.name == "load") return s.load(resolve(base, a[0]));
  if (c.name == "new") return s.new_scene();
  if (c.name == "load_default") return s.open_default();
  if (c.name == "add_module") return s.add_module(a[0]);
  if (c.name == "remove_module") return s.remove_module(a[0]);
  if (c.name == "set") return s.set_param(a[0], a[1]);
  if (c.name == "brush") {
    // Staged on a copy, so a bad key leaves the brush unchanged.
    BrushSettings staged = s.brush();
    for (const std::string& kv : a) {
      auto assignment = parse_param_assignment(kv);
      if (!assignment.ok()) return assignment.error();
      SYLVA_TRY(set_param(staged, assignment->first, assignment->second));
    }
    s.brush() = staged;
    return {};
  }
  if (c.name == "stroke") return s.stroke(a[0], c.points);
  if (c.name == "preview") {
    PlantPreviewSettings staged = s.preview_settings();
    for (const std::string& kv : a) {
      auto assignment = parse_param_assignment(kv);
      if (!assignment.ok()) return assignment.error();
      SYLVA_TRY(set_param(staged, assignment->first, assignment->second));
    }
    s.preview_settings() = staged;
    s.preview_open() = true;
    out << "preview " << s.build_preview().summary() << "\n";
    return {};
  }
  if (c.name == "undo" || c.name == "redo") {
    for (int k = 0; k < c.count; ++k) SYLVA_TRY(c.name == "undo" ? s.undo() : s.redo());
    return {};
  }
  if (c.name == "camera") {
    if (a[0] == "bookmark") return s.go_to_bookmark(a[1]);
    scene::CameraView view = scene::Scene::view_of(s.camera());
    view.position = {number(a[0]), number(a[1]), number(a[2])};
    if (a.size() >= 5) {
      view.yaw_deg = static_cast<float>(number(a[3]));
      view.pitch_deg = static_cast<float>(number(a[4]));
    }
    if (a.size() == 6) view.fov_deg = static_cast<float>(number(a[5]));
    SYLVA_TRY(validate_params(view, "camera"));
    s.set_camera(view);
    return {};
  }
  if (c.name == "bookmark") return s.add_bookmark(a[0]);
  if (c.name == "frames") {
    for (int k = 0; k < c.count; ++k) SYLVA_TRY(s.render_frame(1.0 / 30.0));
    return {};
  }
  if (c.name == "debug") {
    auto set = set_param(s.scene().debug(), a[0], a[1] == "on" ? "true" : "false");
    return set;
  }
  if (c.name == "screenshot") {
    std::optional<glm::ivec2> size;
    if (a.size() == 2) size = parse_size(a[1]).value();
    const std::filesystem::path file = resolve(base, a[0]);
    SYLVA_TRY(s.screenshot(file, size));
    out << "sylva-editor: wrote " << std::filesystem::absolute(file).string() << "\n";
    return {};
  }
  if (c.name == "screenshot_ui") {
    if (!hooks.screenshot_ui) return make_error(ErrorCode::kUnsupported, "there is no window in a headless run");
    const std::filesystem::path file = resolve(base, a[0]);
    SYLVA_TRY(hooks.screenshot_ui(file));
    out << "sylva-editor: wrote " << std::filesystem::absolute(file).string() << "\n";
    return {};
  }
  if (c.name == "export_tree") {
    auto summary = s.export_tree(resolve(base, a[0]));
    if (!summary.ok()) return summary.error();
    out << "sylva-editor: " << *summary << "\n";
    return {};
  }
  // The window's importer when there is one, so a script's import shows in File > Import terrain...
  TerrainImport& import = hooks.terrain_import ? *hooks.terrain_import : state.import;
  if (c.name == "import_terrain") return import_terrain(s, a, base, out, import);
  if (c.name == "wait_import") return wait_import(s, a.empty() ? 100000 : c.count, out, import);
  if (c.name == "cancel_import") return cancel_import(s, out, import);
  if (c.name == "save") {
    if (a.empty()) return s.save();
    return s.save_as(resolve(base, a[0]));
  }
  if (c.name == "copy_file") {
    std::error_code ec;
    std::filesystem::copy_file(resolve(base, a[0]), resolve(base, a[1]), std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) return make_error(ErrorCode::kIo, fmt::format("{} -> {}: {}", a[0], a[1], ec.message()));
    return {};
  }
  if (c.name == "wait_reload") {
    const std::filesystem::path file = resolve(base, a[0]);
    int& seen = state.reloads_seen[file];
    const int max_frames = a.size() == 2 ? c.count : 600;
    for (int k = 0; k < max_frames && s.reloads(file) <= seen; ++k) SYLVA_TRY(s.render_frame(1.0 / 30.0));
    if (s.reloads(file) <= seen) {
      return make_error(ErrorCode::kNotFound, fmt::format("{} was not reloaded within {} frames", file.string(), max_frames));
    }
    seen = s.reloads(file);
    return {};
  }
  if (c.name == "wait_stream") {
    const int max_frames = a.size() == 1 ? c.count : 2000;
    nlohmann::json t = s.scene().module_stats().value("terrain", nlohmann::json::object());
    // A chunk that cannot be read is not asked for again (its parent is drawn): waiting for it
    // would only run out the frames, so the first new failure ends the wait with its reason.
    const std::uint64_t failures_before = t.value("stream_failures", std::uint64_t{0});
    const auto settled = [&] {
      t = s.scene().module_stats().value("terrain", nlohmann::json::object());
      return t.value("stream_pending", 0) == 0 &&
             (t.value("stream_misses_frame", 0) == 0 || t.value("stream_budget_limited", 0) == 1);
    };
    for (int k = 0; k < max_frames; ++k) {
      SYLVA_TRY(s.render_frame(1.0 / 30.0));
      const bool done = settled();
      if (const std::uint64_t failed = t.value("stream_failures", std::uint64_t{0}) - failures_before;
          failed > 0 && t.value("stream_pending", 0) == 0) {
        return make_error(ErrorCode::kCorrupt,
                          fmt::format("{} terrain chunk(s) could not be read; coarser parents are drawn there: {}", failed,
                                      t.value("stream_last_error", std::string("(no message)"))));
      }
      if (done) {
        if (t.value("stream_budget_limited", 0) == 1) {
          out << fmt::format("sylva-editor: wait_stream: terrain.stream.budget_mb ({:.2f} MiB) limits the view: {} "
                             "chunks do not fit, coarser parents are drawn there\n",
                             t.value("stream_budget_bytes", 0.0) / 1048576.0, t.value("stream_budget_refused", 0));
        }
        return {};
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));  // the loader thread reads meanwhile
    }
    return make_error(ErrorCode::kLimit, fmt::format("the terrain still streams after {} frames", max_frames));
  }
  if (c.name == "print_stats") {
    const nlohmann::json stats = s.scene().module_stats();
    if (!stats.contains(a[0])) return make_error(ErrorCode::kNotFound, fmt::format("the scene has no module \"{}\"", a[0]));
    out << a[0] << " " << stats[a[0]].dump() << "\n";
    return {};
  }
  if (c.name == "expect") {
    auto value = s.scene().get_param(a[0]);
    if (!value.ok()) return value.error();
    if (*value != a[1]) return make_error(ErrorCode::kInvalidArgument, fmt::format("{} is {}, expected {}", a[0], *value, a[1]));
    return {};
  }
  if (c.name == "expect_unsaved") {
    const bool want = a[0] == "yes";
    if (s.unsaved() != want) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("the scene {} unsaved changes", s.unsaved() ? "has" : "has no"));
    }
    return {};
  }
  if (c.name == "print") {
    std::string line;
    for (const std::string& w : a) line += (line.empty() ? "" : " ") + w;
    out << line << "\n";
    return {};
  }
  return make_error(ErrorCode::kInvalidArgument, "unknown command");  // the parser rejects these first
}

// Every file the script will write, checked before its first command runs: a screenshot that
// cannot be written fails at once, not after the scene was loaded and the frames rendered.
Status check_outputs(const std::vector<ScriptCommand>& commands, const std::string& source,
                     const std::filesystem::path& base_dir) {
  for (const ScriptCommand& c : commands) {
    if (c.name != "screenshot" && c.name != "screenshot_ui") continue;
    Status writable = check_output_image(resolve(base_dir, c.args[0]));
    if (!writable.ok()) {
      return make_error(writable.error().code,
                        fmt::format("{}: {}: {}", script_location(source, c.line), c.name, writable.error().message));
    }
  }
  return ok_status();
}

}  // namespace

Result<ScriptOutcome> run_script(EditorSession& session, const std::vector<ScriptCommand>& commands,
                                 const std::string& source, const std::filesystem::path& base_dir, std::ostream& out,
                                 const ScriptHooks& hooks) {
  SYLVA_TRY(check_outputs(commands, source, base_dir));
  ScriptOutcome outcome;
  RunState state;
  std::size_t messages_shown = session.messages().size();
  auto show_messages = [&] {
    for (; messages_shown < session.messages().size(); ++messages_shown) {
      out << "sylva-editor: " << session.messages()[messages_shown] << "\n";
    }
  };
  for (const ScriptCommand& c : commands) {
    if (c.name == "quit") {
      outcome.quit = true;
      break;
    }
    Status s = run_one(session, c, base_dir, out, hooks, state);
    show_messages();
    if (!s.ok()) {
      return make_error(s.error().code, fmt::format("{}: {}: {}", script_location(source, c.line), c.name, s.error().message));
    }
    ++outcome.commands_run;
    if (hooks.after_command) hooks.after_command();
    show_messages();
  }
  return outcome;
}

Result<std::vector<ScriptCommand>> read_script(const std::filesystem::path& file) {
  auto text = read_file(file);
  if (!text.ok()) return text.error();
  return parse_script(*text, file.string());
}

Result<ScriptOutcome> run_script_file(EditorSession& session, const std::filesystem::path& file, std::ostream& out,
                                      const ScriptHooks& hooks) {
  auto commands = read_script(file);
  if (!commands.ok()) return commands.error();
  return run_script(session, *commands, file.string(), file.parent_path(), out, hooks);
}

}  // namespace sylva::editor
