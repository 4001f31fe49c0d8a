// Output paths (player --screenshot / --stats, editor screenshot, bench --out) that cannot be
// written: a missing folder, a folder given as the file, a file given as the folder, an
// unknown image format, a folder nobody may write to (/proc: refused even to root), and the
// user's own input file. The message must name the path as typed, and the check must come
// before any work: the scenes here also name a missing map, which is only read when the scene
// is built, so a run that built the scene before checking its outputs names that map instead.

#include "hostile_case.hpp"

namespace sylva::hostile {

namespace {
InputFile scene_with_missing_map() {
  return {"scene.json", [] { return ground_scene("absent.png"); }};
}
HostileCase player_output(std::string name, std::string option, std::vector<std::string> words,
                          std::vector<InputFile> extra = {}) {
  std::vector<InputFile> files = {scene_with_missing_map()};
  files.insert(files.end(), extra.begin(), extra.end());
  return {.name = std::move(name), .files = std::move(files), .args = "scene.json --size 32x18 --frames 1 " + option,
          .exit_code = 1, .words = std::move(words), .absent = {"absent.png", ".tmp"}};
}
}  // namespace

std::vector<HostileCase> output_path_cases() {
  return {
      player_output("ScreenshotInMissingFolder", "--screenshot nodir/shot.png", {"nodir/shot.png", "does not exist"}),
      player_output("ScreenshotIsAFolder", "--screenshot shots", {"shots", "is a folder"}, {{"shots/", {}}}),
      player_output("ScreenshotUnderAFile", "--screenshot scene.json/shot.png", {"scene.json/shot.png", "not a folder"}),
      player_output("ScreenshotUnknownFormat", "--screenshot shot.xyz", {"shot.xyz", ".xyz"}),
      player_output("ScreenshotUnwritableFolder", "--screenshot /proc/sylva_hostile.png", {"/proc/sylva_hostile.png"}),
      player_output("ScreenshotOverTheScene", "--screenshot scene.json", {"scene.json"}),
      player_output("StatsInMissingFolder", "--stats nodir/stats.json", {"nodir/stats.json", "does not exist"}),
      player_output("StatsIsAFolder", "--stats stats", {"stats", "is a folder"}, {{"stats/", {}}}),
      player_output("StatsUnwritableFolder", "--stats /proc/sylva_hostile.json", {"/proc/sylva_hostile.json"}),
      // Stats are JSON, like the scene: writing them there would replace the user's scene.
      player_output("StatsOverTheScene", "--stats scene.json", {"scene.json", "input"}),
  };
}

}  // namespace sylva::hostile
