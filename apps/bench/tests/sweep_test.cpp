// Sweep parsing and cartesian expansion (GL-free).
#include "sweep.hpp"

#include <gtest/gtest.h>

namespace sylva::bench {
namespace {

TEST(Sweep, ParsesPathAndValues) {
  auto axis = parse_sweep("terrain.max_pixel_error=0.5, 1,2 ,4");
  ASSERT_TRUE(axis.ok()) << axis.error().message;
  EXPECT_EQ(axis->path, "terrain.max_pixel_error");
  EXPECT_EQ(axis->values, (std::vector<std::string>{"0.5", "1", "2", "4"}));
}

TEST(Sweep, BracketsKeepVectorValuesTogether) {
  auto axis = parse_sweep("camera.position=[0,10,0],[1, 2, 3]");
  ASSERT_TRUE(axis.ok()) << axis.error().message;
  EXPECT_EQ(axis->values, (std::vector<std::string>{"[0,10,0]", "[1, 2, 3]"}));
}

TEST(Sweep, MalformedTextIsRejectedWithTheText) {
  for (const char* bad : {"terrain.max_pixel_error", "=1,2", "a.b=", "a.b=1,,2", "a.b=[1,2", "a.b=1]"}) {
    auto axis = parse_sweep(bad);
    EXPECT_FALSE(axis.ok()) << bad;
    if (!axis.ok()) {
      EXPECT_EQ(axis.error().code, ErrorCode::kInvalidArgument) << bad;
    }
  }
  auto empty_value = parse_sweep("grass.density=1,,2");
  ASSERT_FALSE(empty_value.ok());
  EXPECT_NE(empty_value.error().message.find("grass.density"), std::string::npos) << empty_value.error().message;
}

TEST(Sweep, CartesianProductFirstAxisSlowest) {
  auto settings = expand_sweeps({{"a", {"1", "2"}}, {"b", {"x", "y", "z"}}});
  ASSERT_TRUE(settings.ok());
  ASSERT_EQ(settings->size(), 6u);
  const std::vector<std::pair<std::string, std::string>> expected = {{"1", "x"}, {"1", "y"}, {"1", "z"},
                                                                     {"2", "x"}, {"2", "y"}, {"2", "z"}};
  for (std::size_t i = 0; i < 6; ++i) {
    const Setting& s = (*settings)[i];
    EXPECT_EQ(s.index, i);
    ASSERT_EQ(s.assignments.size(), 2u);
    EXPECT_EQ(s.assignments[0], (Assignment{"a", expected[i].first}));
    EXPECT_EQ(s.assignments[1], (Assignment{"b", expected[i].second}));
  }
  EXPECT_EQ((*settings)[4].label(), "a=2, b=y");
  EXPECT_EQ((*settings)[4].id(), "s004");
}

TEST(Sweep, NoAxesGivesOneSettingAsLoaded) {
  auto settings = expand_sweeps({});
  ASSERT_TRUE(settings.ok());
  ASSERT_EQ(settings->size(), 1u);
  EXPECT_TRUE(settings->front().assignments.empty());
  EXPECT_EQ(settings->front().label(), "(scene as loaded)");
}

TEST(Sweep, DuplicatePathAndHugeProductsAreErrors) {
  auto dup = expand_sweeps({{"a", {"1"}}, {"a", {"2"}}});
  ASSERT_FALSE(dup.ok());
  EXPECT_NE(dup.error().message.find("a is given twice"), std::string::npos) << dup.error().message;
  std::vector<std::string> hundred;
  for (int i = 0; i < 100; ++i) hundred.push_back(std::to_string(i));
  auto huge = expand_sweeps({{"a", hundred}, {"b", hundred}, {"c", {"1", "2"}}});
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().code, ErrorCode::kLimit);
}

TEST(Sweep, GroupsConcatenateWithRunningIndices) {
  auto settings = expand_sweep_groups({{{"crit", {"ss"}}, {"tau", {"1", "2"}}}, {{"crit", {"dist"}}, {"d", {"5", "9", "13"}}}});
  ASSERT_TRUE(settings.ok());
  ASSERT_EQ(settings->size(), 5u);
  EXPECT_EQ((*settings)[1].label(), "crit=ss, tau=2");
  EXPECT_EQ((*settings)[2].label(), "crit=dist, d=5");
  for (std::size_t i = 0; i < settings->size(); ++i) EXPECT_EQ((*settings)[i].index, i);
  EXPECT_EQ(swept_paths({{{"crit", {"ss"}}, {"tau", {"1"}}}, {{"crit", {"x"}}, {"d", {"5"}}}}),
            (std::vector<std::string>{"crit", "tau", "d"}));
}

}  // namespace
}  // namespace sylva::bench
