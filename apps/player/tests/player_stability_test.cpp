// sylva-player under hostile input, end to end (the real executable, headless):
//  - non-finite or out-of-range values in a scene file or --set are refused with exit code 2 and
//    a message naming the parameter path, never rendered;
//  - extreme but valid runs (one pixel-row-thin viewport, long camera-path clocks, a scene far
//    from the origin) exit 0 and write statistics without a single NaN (JSON null) in them.
// Invariant names: "no NaN reaches the output", "bad numbers are named, not rendered".
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/params_json.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#include "run_command.hpp"

namespace fs = std::filesystem;

namespace {

using sylva::test::RunResult;

RunResult run_player(const std::string& args) { return sylva::test::run_command(SYLVA_PLAYER_EXE, args); }

fs::path out_dir() {
  const fs::path dir = fs::temp_directory_path() / ("sylva_player_stability_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

fs::path write_scene(const std::string& name, const std::string& text) {
  const fs::path p = out_dir() / name;
  EXPECT_TRUE(sylva::write_file_atomic(p, text).ok());
  return p;
}

// A small ground, centred at `centre`, with a looping camera path over it.
std::string small_scene(double centre) {
  const std::string c = std::to_string(centre);
  return R"({"sylva_scene": 1, "name": "stability",
    "camera": {"position": [)" + c + R"(, 60, )" + c + R"(], "yaw_deg": 30, "pitch_deg": -20},
    "ground": {"size": 256, "resolution": 65, "height": 30, "center": [)" + c + ", " + c + R"(]},
    "camera_paths": {"loop": {"loop": true, "interpolation": "catmull_rom", "keys": [
      {"time_s": 0, "position": [)" + c + R"(, 60, )" + c + R"(], "pitch_deg": -20},
      {"time_s": 0.001, "position": [)" + c + R"(, 61, )" + c + R"(], "yaw_deg": 179, "pitch_deg": -89},
      {"time_s": 0.002, "position": [)" + c + R"(, 60, )" + c + R"(], "yaw_deg": -179, "pitch_deg": 89}]}}})";
}

int count_nulls(const nlohmann::json& j) {
  if (j.is_null()) return 1;
  int n = 0;
  if (j.is_structured()) {
    for (const auto& item : j) n += count_nulls(item);
  }
  return n;
}

}  // namespace

// Invariant: bad numbers are named, not rendered.
TEST(PlayerStability, NonFiniteAndOutOfRangeValuesAreRefusedByPath) {
  const fs::path scene = write_scene("base.json", small_scene(0.0));
  for (const char* value : {"nan", "inf", "-inf", "1e39"}) {
    const RunResult r = run_player(scene.string() + " --headless --size 32x32 --frames 1 --set sun.intensity=" + value);
    EXPECT_EQ(r.exit_code, 2) << value << ": " << r.output;
    EXPECT_NE(r.output.find("sun.intensity"), std::string::npos) << value << ": " << r.output;
  }
  // JSON has no NaN; a number too large for a float is out of range and named by its path.
  const fs::path huge = write_scene("huge.json", R"({"sun": {"intensity": 1e300}, "ground": {"resolution": 65, "size": 128}})");
  const RunResult r = run_player(huge.string() + " --headless --size 32x32 --frames 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("sun.intensity"), std::string::npos) << r.output;
}

// Invariant: no NaN reaches the output (statistics and picture), also far from the origin, in a
// 16-pixel-high viewport and along a camera path whose keys are a millisecond apart.
TEST(PlayerStability, ExtremeRunsStayFinite) {
  for (double centre : {0.0, 1.0e6}) {
    const fs::path scene = write_scene("run.json", small_scene(centre));
    const fs::path stats = out_dir() / "stats.json";
    const fs::path png = out_dir() / "shot.exr";
    const RunResult r = run_player(scene.string() + " --headless --size 256x16 --frames 6 --camera-path loop --stats " +
                                   stats.string() + " --screenshot " + png.string());
    ASSERT_EQ(r.exit_code, 0) << centre << ": " << r.output;
    auto text = sylva::read_file(stats);
    ASSERT_TRUE(text.ok());
    auto json = sylva::parse_json_text(*text, stats.string());
    ASSERT_TRUE(json.ok()) << json.error().message;
    EXPECT_EQ(count_nulls(*json), 0) << "NaN in stats (written as null): " << json->dump();
    auto image = sylva::read_image(png);
    ASSERT_TRUE(image.ok()) << image.error().message;
    // The player renders to an 8-bit target, where a NaN is stored as 0: it shows as a zero
    // channel, never as a NaN in the file. No channel of this lit scene is near zero (the darkest
    // is about 0.2), so a zero channel is a NaN that reached the picture.
    int zero = 0;
    for (int y = 0; y < image->height(); ++y)
      for (int x = 0; x < image->width(); ++x)
        for (int c = 0; c < 3; ++c) zero += image->at(x, y, c) == 0.0f ? 1 : 0;
    EXPECT_EQ(zero, 0) << centre << ": zero channels (NaN on the 8-bit target)";
  }
}
