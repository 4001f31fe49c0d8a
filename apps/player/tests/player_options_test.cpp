// sylva-player command line: every option and every bad argument.
#include "player_options.hpp"

#include <gtest/gtest.h>

using sylva::player::parse_player_options;

TEST(PlayerOptions, DefaultsWithNoArguments) {
  auto o = parse_player_options({});
  ASSERT_TRUE(o.ok());
  EXPECT_FALSE(o->scene_path.has_value());
  EXPECT_FALSE(o->headless);
  EXPECT_EQ(o->size, glm::ivec2(1280, 720));
  EXPECT_FALSE(o->frames.has_value());
}

TEST(PlayerOptions, ParsesEveryOption) {
  auto o = parse_player_options({"scene.json", "--headless", "--size", "256x144", "--frames=3", "--screenshot",
                                 "out.png", "--stats", "s.json", "--set", "sun.elevation_deg=30",
                                 "--set=ground.octaves=4"});
  ASSERT_TRUE(o.ok()) << o.error().message;
  EXPECT_EQ(*o->scene_path, "scene.json");
  EXPECT_TRUE(o->headless);
  EXPECT_EQ(o->size, glm::ivec2(256, 144));
  EXPECT_EQ(*o->frames, 3);
  EXPECT_EQ(*o->screenshot_path, "out.png");
  EXPECT_EQ(*o->stats_path, "s.json");
  ASSERT_EQ(o->overrides.size(), 2u);
  EXPECT_EQ(o->overrides[0].first, "sun.elevation_deg");
  EXPECT_EQ(o->overrides[0].second, "30");
  EXPECT_EQ(o->overrides[1].first, "ground.octaves");
}

struct BadCase {
  std::vector<std::string> args;
  const char* must_mention;
};

TEST(PlayerOptions, BadArgumentsNameTheProblem) {
  const BadCase cases[] = {
      {{"--bogus"}, "--bogus"},
      {{"--size"}, "--size"},
      {{"--size", "0x0"}, "0x0"},
      {{"--size", "abc"}, "abc"},
      {{"--size", "100000x10"}, "100000x10"},
      {{"--size", "12x"}, "12x"},
      {{"--size", "16384x16384"}, "above the limit of 67108864"},
      {{"--frames", "-1"}, "--frames"},
      {{"--frames", "many"}, "many"},
      {{"--frames", "--headless"}, "--frames"},
      {{"--set", "novalue"}, "novalue"},
      {{"--set", "=3"}, "=3"},
      {{"a.json", "b.json"}, "b.json"},
      {{"--screenshot"}, "--screenshot"},
  };
  for (const BadCase& c : cases) {
    auto o = parse_player_options(c.args);
    ASSERT_FALSE(o.ok()) << c.args[0];
    EXPECT_NE(o.error().message.find(c.must_mention), std::string::npos) << o.error().message;
  }
}
