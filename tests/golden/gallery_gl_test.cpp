// `make gallery` (issue #19): scripts/make-gallery renders every shipped scene through the
// shipped player and writes an HTML page; this test runs it at a small size and opens the page
// in headless Chromium (Debian's chromium, scripts/install-deps), reading back the DOM after its
// script ran: every picture must have loaded and every figure must carry its frame statistics
// and render settings.

#include "golden_scene.hpp"

#include <gtest/gtest.h>

#include "run_command.hpp"

#include <filesystem>
#include <regex>
#include <string>
#include <unistd.h>

namespace sylva::golden {
namespace {

namespace fs = std::filesystem;

// The flags a root process in a closed network needs (no sandbox as root, no GPU, no calls home
// that the network would refuse), and a fresh profile so runs do not share state.
std::string chromium_command(const fs::path& profile) {
  return "chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
         "--disable-component-update --disable-sync --user-data-dir='" + profile.string() + "' --virtual-time-budget=10000";
}

int count(const std::string& text, const std::regex& pattern) {
  return static_cast<int>(std::distance(std::sregex_iterator(text.begin(), text.end(), pattern), std::sregex_iterator()));
}

TEST(Gallery, EveryShippedSceneShowsWithItsStatisticsInABrowser) {
  const fs::path out = fs::path(SYLVA_GALLERY_OUT_DIR) / std::to_string(::getpid());
  fs::remove_all(out);
  const auto made = test::run_command(SYLVA_MAKE_GALLERY, std::string(SYLVA_PLAYER_EXE) + " '" + out.string() +
                                                              "' --size 160x90 --frames 2 --scenes '" SYLVA_SCENES_DIR "'");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const int scenes = static_cast<int>(shipped_scenes(SYLVA_SCENES_DIR).size());
  for (const auto& s : shipped_scenes(SYLVA_SCENES_DIR)) {
    EXPECT_TRUE(fs::exists(out / (s.name + ".png"))) << s.name;
    EXPECT_TRUE(fs::exists(out / (s.name + ".stats.json"))) << s.name;
  }

  const auto dom = test::run_command(chromium_command(out / "profile"), "--dump-dom 'file://" + (out / "index.html").string() + "'");
  ASSERT_EQ(dom.exit_code, 0) << "headless chromium failed (is Debian's chromium installed? scripts/install-deps)\n" << dom.output;
  std::smatch body;
  ASSERT_TRUE(std::regex_search(dom.output, body, std::regex("<body[^>]*>"))) << dom.output.substr(0, 2000);
  const std::string tag = body.str();
  EXPECT_NE(tag.find("data-images-total=\"" + std::to_string(scenes) + "\""), std::string::npos) << tag;
  EXPECT_NE(tag.find("data-images-loaded=\"" + std::to_string(scenes) + "\""), std::string::npos)
      << "not every picture loaded in the browser: " << tag;
  // Each figure got its statistics (a measured wall time) and its settings table (MSAA samples).
  EXPECT_EQ(count(dom.output, std::regex("<figure data-scene=\"[^\"]+\" data-wall-ms=\"[0-9.]+\"")), scenes);
  EXPECT_EQ(count(dom.output, std::regex("render\\.msaa_samples</th>")), scenes);
  EXPECT_EQ(count(dom.output, std::regex("class=\"failed\"")), 0);
  fs::remove_all(out);
}

}  // namespace
}  // namespace sylva::golden
