#pragma once
// Command line of sylva-player (DESIGN.md §3):
//   sylva-player [scene.json] [--headless] [--size WxH] [--frames N] [--screenshot PATH]
//                [--stats PATH] [--set path=value]... [--bookmark NAME] [--camera-path NAME]
//                [--list-modules] [--help]
// Parsing is separate from running so every bad argument is unit-tested.

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sylva::player {

struct PlayerOptions {
  std::optional<std::string> scene_path;  // none: the embedded default scene
  bool headless = false;                  // forced headless; also chosen when no display exists
  glm::ivec2 size{1280, 720};             // framebuffer size in pixels, each side in [16, 16384]
  std::optional<int> frames;              // frames to render, >= 1; none: until the window closes
                                          // (headless without it renders kDefaultHeadlessFrames)
  std::optional<std::string> screenshot_path;  // PNG (or any OIIO format) of the last frame
  std::optional<std::string> stats_path;       // JSON statistics of the run
  std::vector<std::pair<std::string, std::string>> overrides;  // --set path=value, in order
  std::optional<std::string> bookmark;     // start at this bookmark of the scene
  std::optional<std::string> camera_path;  // fly this camera path of the scene (time = frame clock)
  bool list_modules = false;
  bool help = false;
};

inline constexpr int kDefaultHeadlessFrames = 8;

// Parses argv[1..argc). Errors name the offending argument and say what was expected.
Result<PlayerOptions> parse_player_options(const std::vector<std::string>& args);

// The --help text.
std::string player_usage();

}  // namespace sylva::player
