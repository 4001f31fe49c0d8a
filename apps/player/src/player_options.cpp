#include "player_options.hpp"

#include <sylva/core/render_size.hpp>

#include <fmt/format.h>

#include <charconv>

namespace sylva::player {
namespace {

Result<int> parse_int(const std::string& text, const std::string& what) {
  int value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: expected a whole number, got \"{}\"", what, text));
  }
  return value;
}

}  // namespace

Result<PlayerOptions> parse_player_options(const std::vector<std::string>& args) {
  PlayerOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    // Options that take a value accept both "--opt value" and "--opt=value".
    std::string name = arg;
    std::optional<std::string> inline_value;
    if (arg.rfind("--", 0) == 0) {
      if (auto eq = arg.find('='); eq != std::string::npos && arg.rfind("--set", 0) != 0) {
        name = arg.substr(0, eq);
        inline_value = arg.substr(eq + 1);
      }
    }
    auto value = [&](const char* what) -> Result<std::string> {
      if (inline_value) return *inline_value;
      if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) {
        return make_error(ErrorCode::kInvalidArgument, fmt::format("{} needs a value: {}", name, what));
      }
      return args[++i];
    };

    if (name == "--help" || name == "-h") {
      options.help = true;
    } else if (name == "--headless") {
      options.headless = true;
    } else if (name == "--list-modules") {
      options.list_modules = true;
    } else if (name == "--size") {
      auto v = value("WxH, e.g. 256x144");
      if (!v.ok()) return v.error();
      auto size = parse_render_size(*v, "--size");
      if (!size.ok()) return size.error();
      options.size = *size;
    } else if (name == "--frames") {
      auto v = value("a frame count >= 1");
      if (!v.ok()) return v.error();
      auto n = parse_int(*v, "--frames");
      if (!n.ok()) return n.error();
      if (*n < 1 || *n > 10'000'000) {
        return make_error(ErrorCode::kInvalidArgument, fmt::format("--frames: {} is outside 1..10000000", *n));
      }
      options.frames = *n;
    } else if (name == "--screenshot") {
      auto v = value("an output image path such as out/demo.png");
      if (!v.ok()) return v.error();
      options.screenshot_path = *v;
    } else if (name == "--stats") {
      auto v = value("an output JSON path");
      if (!v.ok()) return v.error();
      options.stats_path = *v;
    } else if (name == "--bookmark") {
      auto v = value("the name of a bookmark in the scene");
      if (!v.ok()) return v.error();
      options.bookmark = *v;
    } else if (name == "--camera-path") {
      auto v = value("the name of a camera path in the scene");
      if (!v.ok()) return v.error();
      options.camera_path = *v;
    } else if (name == "--set" || arg.rfind("--set=", 0) == 0) {
      std::string assignment;
      if (arg.rfind("--set=", 0) == 0) {
        assignment = arg.substr(6);
      } else {
        auto v = value("path=value, e.g. terrain.max_pixel_error=2");
        if (!v.ok()) return v.error();
        assignment = *v;
      }
      const auto eq = assignment.find('=');
      if (eq == std::string::npos || eq == 0) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("--set: expected path=value, got \"{}\"", assignment));
      }
      options.overrides.emplace_back(assignment.substr(0, eq), assignment.substr(eq + 1));
    } else if (arg.rfind("-", 0) == 0) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("unknown option \"{}\" (see --help)", arg));
    } else if (options.scene_path) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("only one scene file may be given; got \"{}\" and \"{}\"", *options.scene_path, arg));
    } else {
      options.scene_path = arg;
    }
  }
  return options;
}

std::string player_usage() {
  return "usage: sylva-player [scene.json] [options]\n"
         "Plays a Sylva scene in a window, or headless when there is no display.\n"
         "  scene.json            scene file; without it the embedded default scene plays\n"
         "  --headless            render off-screen even when a display exists\n"
         "  --size WxH            framebuffer size in pixels (default 1280x720)\n"
         "  --frames N            render N frames, then quit (headless default: 8)\n"
         "  --screenshot PATH     save the last frame (PNG, EXR, TIFF, ...)\n"
         "  --stats PATH          write frame statistics as JSON\n"
         "  --set path=value      override a scene parameter, e.g. --set sun.elevation_deg=30\n"
         "  --bookmark NAME       start at a camera bookmark of the scene\n"
         "  --camera-path NAME    fly a camera path of the scene (headless: 1/30 s per frame)\n"
         "  --list-modules        list the modules compiled into this player and quit\n"
         "  --help                show this text\n"
         "Window controls: WASD fly, mouse look (hold right button), Shift faster, Esc quits.\n";
}

}  // namespace sylva::player
