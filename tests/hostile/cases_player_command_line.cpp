// sylva-player command lines: sizes, frame counts and --set assignments that are malformed,
// out of range, NaN or unknown, and options without their values. Each message must name what
// the user typed.

#include "hostile_case.hpp"

namespace sylva::hostile {

namespace {
InputFile ground() {
  return {"scene.json", [] { return ground_scene(); }};
}
HostileCase args(std::string name, std::string line, std::vector<std::string> words) {
  return {.name = std::move(name), .files = {ground()}, .args = "scene.json " + std::move(line), .words = std::move(words)};
}
}  // namespace

std::vector<HostileCase> player_command_line_cases() {
  const std::string f = " --frames 1";
  return {
      args("SizeZero", "--size 0x0" + f, {"--size", "0x0"}),
      args("SizeNotANumber", "--size abc" + f, {"--size", "abc"}),
      args("SizeMissingHeight", "--size 64x" + f, {"--size", "64x"}),
      args("SizeNegative", "--size -5x10" + f, {"--size", "-5x10"}),
      args("SizeHuge", "--size 100000x100000" + f, {"--size", "100000x100000"}),
      args("SizeOverflowsInt", "--size 4294967312x16" + f, {"--size", "4294967312x16"}),
      // The black PNG with exit 0: within the per-side limit, beyond what a frame holds.
      args("Size16384Squared", "--size 16384x16384 --screenshot shot.png" + f, {"--size", "16384x16384"}),
      args("SizeWithoutValue", "--frames 1 --size", {"--size"}),
      args("FramesZero", "--size 32x18 --frames 0", {"--frames", "0"}),
      args("FramesNaN", "--size 32x18 --frames nan", {"--frames", "nan"}),
      args("FramesOverflow", "--size 32x18 --frames 99999999999", {"--frames", "99999999999"}),
      args("SetUnknownPath", "--size 32x18 --set nope.path=1" + f, {"--set", "nope.path"}),
      args("SetUnknownLeaf", "--size 32x18 --set ground.nope=1" + f, {"--set", "ground.nope"}),
      args("SetNaN", "--size 32x18 --set ground.height=nan" + f, {"ground.height", "nan"}),
      args("SetInfinity", "--size 32x18 --set sun.elevation_deg=inf" + f, {"sun.elevation_deg", "inf"}),
      args("SetNotANumber", "--size 32x18 --set ground.height=abc" + f, {"ground.height", "abc"}),
      args("SetNumberOverflow", "--size 32x18 --set ground.height=1e999" + f, {"ground.height", "1e999"}),
      args("SetAboveRange", "--size 32x18 --set ground.resolution=1000000000" + f, {"ground.resolution", "1000000000"}),
      args("SetWithoutEquals", "--size 32x18 --set noeq" + f, {"--set", "noeq"}),
      args("SetEmptyPath", "--size 32x18 --set =5" + f, {"--set", "=5"}),
      args("SetWholeSection", "--size 32x18 --set ground=5" + f, {"--set", "ground"}),
      args("UnknownOption", "--size 32x18 --bogus" + f, {"--bogus"}),
      args("TwoScenes", "other.json --size 32x18" + f, {"scene.json", "other.json"}),
      args("BookmarkMissing", "--size 32x18 --bookmark nope" + f, {"--bookmark", "nope"}),
      args("CameraPathMissing", "--size 32x18 --camera-path nope" + f, {"--camera-path", "nope"}),
  };
}

}  // namespace sylva::hostile
