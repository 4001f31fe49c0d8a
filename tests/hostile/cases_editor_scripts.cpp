// sylva-editor --script: junk and malformed scripts, commands with NaN and unknown parameter
// paths, scenes that cannot load, and screenshots that cannot be written (checked before the
// script starts: the scene here names a missing map, so a late check reports the map instead).
// A malformed script exits 2, a failing command 1, each naming "<script>:<line>".

#include "hostile_bytes.hpp"
#include "hostile_case.hpp"

namespace sylva::hostile {

namespace {
const std::string kRun = "--script s.txt --size 32x18";
HostileCase script(std::string name, std::string text, int exit_code, std::vector<std::string> words,
                   std::string scene = ground_scene()) {
  return {.name = std::move(name), .tool = Tool::kEditor,
          .files = {{"s.txt", [text] { return text; }}, {"scene.json", [scene] { return scene; }}},
          .args = kRun, .exit_code = exit_code, .words = std::move(words)};
}
HostileCase late_output(std::string name, std::string command, std::vector<std::string> words) {
  HostileCase c = script(std::move(name), "load scene.json\nframes 1\n" + command + "\nquit\n", 1, std::move(words),
                         ground_scene("absent.png"));
  c.absent = {"absent.png", ".tmp"};
  return c;
}
}  // namespace

std::vector<HostileCase> editor_script_cases() {
  return {
      script("ScriptBinaryJunk", junk(500), 2, {"s.txt:1"}),
      script("ScriptUnknownCommand", "frobnicate\nquit\n", 2, {"s.txt:1", "frobnicate"}),
      script("ScriptNulByte", std::string("load scene.json\0\nquit\n", 22), 2, {"s.txt:1"}),
      script("ScriptMegabyteLine", std::string(1 << 20, 'x') + "\nquit\n", 2, {"s.txt:1"}),
      script("ScriptFramesZero", "load scene.json\nframes 0\nquit\n", 2, {"s.txt:2", "0"}),
      script("ScriptStrokeNaN", "load scene.json\nstroke ground.height nan,nan\nquit\n", 2, {"s.txt:2", "nan"}),
      script("ScriptScreenshotHugeSize", "load scene.json\nscreenshot x.png 100000x100000\nquit\n", 2,
             {"s.txt:2", "100000x100000"}),
      script("ScriptLoadMissingScene", "load nothere.json\nquit\n", 1, {"s.txt:1", "nothere.json"}),
      script("ScriptLoadDeepScene", "load scene.json\nquit\n", 1, {"s.txt:1", "scene.json", "nested deeper than"},
             nested_json(70'000)),
      script("ScriptSetUnknownPath", "load scene.json\nset nope.path 1\nquit\n", 1, {"s.txt:2", "nope.path"}),
      script("ScriptSetNaN", "load scene.json\nset ground.height nan\nquit\n", 1, {"s.txt:2", "ground.height", "nan"}),
      script("ScriptBrushNaN", "load scene.json\nbrush radius=nan\nquit\n", 1, {"s.txt:2", "radius", "nan"}),
      script("ScriptStrokeUnknownMap", "load scene.json\nstroke nope.map 0,0 1,1\nquit\n", 1, {"s.txt:2", "nope.map"}),
      {.name = "ScriptMissing", .tool = Tool::kEditor, .args = "--script none.txt", .words = {"none.txt"}},
      {.name = "ScriptIsAFolder", .tool = Tool::kEditor, .files = {{"s.txt/", {}}}, .args = kRun,
       .words = {"s.txt", "folder"}},
      {.name = "EditorSizeZero", .tool = Tool::kEditor, .files = {{"s.txt", [] { return std::string("quit\n"); }}},
       .args = "--script s.txt --size 0x0", .words = {"--size", "0x0"}},
      late_output("ScriptScreenshotInMissingFolder", "screenshot nodir/x.png 32x18", {"s.txt:3", "nodir/x.png", "does not exist"}),
      late_output("ScriptScreenshotIsAFolder", "screenshot s.txt/x.png 32x18", {"s.txt:3", "s.txt/x.png", "not a folder"}),
      late_output("ScriptScreenshotUnwritable", "screenshot /proc/sylva_hostile.png 32x18",
                  {"s.txt:3", "/proc/sylva_hostile.png"}),
      late_output("ScriptScreenshotUnknownFormat", "screenshot x.xyz 32x18", {"s.txt:3", "x.xyz"}),
  };
}

}  // namespace sylva::hostile
