// Command-line parsing of sylva-bench (GL-free).
#include "bench_options.hpp"
#include "paper_tables.hpp"

#include <gtest/gtest.h>

namespace sylva::bench {
namespace {

Result<BenchOptions> parse(std::vector<std::string> args) { return parse_bench_options(args); }

TEST(BenchOptions, FullSweepCommandLine) {
  auto o = parse({"scene.json", "--sweep", "terrain.max_pixel_error=0.5,1,2", "--sweep=terrain.morph_fraction=0,0.25",
                  "--reference", "terrain.max_pixel_error=0.1", "--set", "sun.elevation_deg=30", "--camera-path",
                  "flyover", "--frames", "12", "--size", "128x72", "--cost", "frame_ms", "--error-metric",
                  "share_exceeding", "--threshold", "0.1", "--no-embed", "--out", "out/bench"});
  ASSERT_TRUE(o.ok()) << o.error().message;
  EXPECT_EQ(*o->scene, "scene.json");
  ASSERT_EQ(o->sweeps.size(), 2u);
  EXPECT_EQ(o->sweeps[1].path, "terrain.morph_fraction");
  ASSERT_EQ(o->reference.size(), 1u);
  EXPECT_EQ(o->reference[0], (Assignment{"terrain.max_pixel_error", "0.1"}));
  EXPECT_EQ(o->overrides[0], (Assignment{"sun.elevation_deg", "30"}));
  EXPECT_EQ(*o->camera_path, "flyover");
  EXPECT_EQ(*o->frames, 12);
  EXPECT_EQ(*o->size, glm::ivec2(128, 72));
  EXPECT_EQ(*o->cost, CostMetric::kFrameMs);
  EXPECT_EQ(o->error, ErrorMetric::kShareExceeding);
  EXPECT_FLOAT_EQ(o->threshold, 0.1f);
  EXPECT_FALSE(o->embed_images);
  EXPECT_EQ(o->out, "out/bench");
}

TEST(BenchOptions, SuiteAndStability) {
  auto o = parse({"--suite", "terrain", "--stability", "--out", "x"});
  ASSERT_TRUE(o.ok()) << o.error().message;
  EXPECT_EQ(*o->suite, "terrain");
  EXPECT_TRUE(o->stability);
  auto s = parse({"--stability", "--out", "x"});
  ASSERT_TRUE(s.ok()) << s.error().message;
}

TEST(BenchOptions, ErrorsNameTheArgument) {
  struct Case {
    std::vector<std::string> args;
    const char* expect;  // substring of the message
  };
  const std::vector<Case> cases = {
      {{"s.json", "--sweep", "a=1"}, "--out"},
      {{"s.json", "--sweep", "nopath", "--out", "x"}, "nopath"},
      {{"s.json", "--frames", "0", "--out", "x"}, "--frames"},
      {{"s.json", "--frames", "ten", "--out", "x"}, "ten"},
      {{"s.json", "--size", "128", "--out", "x"}, "--size"},
      {{"s.json", "--size", "8x8", "--out", "x"}, "outside 16..16384"},
      {{"s.json", "--threshold", "2", "--out", "x"}, "--threshold"},
      {{"s.json", "--cost", "wall", "--out", "x"}, "wall"},
      {{"s.json", "--error-metric", "mse", "--out", "x"}, "mse"},
      {{"s.json", "--suite", "rocks", "--out", "x"}, "rocks"},
      {{"s.json", "--suite", "grass", "--out", "x"}, "--suite grass brings its own scene"},
      {{"--suite", "grass", "--sweep", "a=1", "--out", "x"}, "curated"},
      {{"--sweep", "a=1", "--out", "x"}, "need a SCENE"},
      {{"--out", "x"}, "nothing to do"},
      {{"a.json", "b.json", "--out", "x"}, "only one scene"},
      {{"s.json", "--bogus", "--out", "x"}, "--bogus"},
      {{"s.json", "--reference", "novalue", "--out", "x"}, "novalue"},
      {{"s.json", "--frames"}, "--frames needs a value"},
  };
  for (const Case& c : cases) {
    auto o = parse(c.args);
    ASSERT_FALSE(o.ok()) << c.args[0] << " " << (c.args.size() > 1 ? c.args[1] : "");
    EXPECT_NE(o.error().message.find(c.expect), std::string::npos) << o.error().message;
  }
}

TEST(BenchOptions, HelpAndListingNeedNoOut) {
  auto h = parse({"--help"});
  ASSERT_TRUE(h.ok());
  EXPECT_TRUE(h->help);
  EXPECT_NE(bench_usage().find("--sweep"), std::string::npos);
  auto l = parse({"builtin:ground", "--list-params"});
  ASSERT_TRUE(l.ok()) << l.error().message;
  EXPECT_TRUE(l->list_params);
}

TEST(BenchOptions, PaperWithQuick) {
  auto o = parse({"--paper", "000", "--quick", "--out", "x"});
  ASSERT_TRUE(o.ok()) << o.error().message;
  EXPECT_EQ(*o->paper, "000");
  EXPECT_TRUE(o->quick);
  EXPECT_TRUE(parse({"--paper=all", "--out", "x"}).ok());
  auto bad = parse({"--paper", "005", "--out", "x"});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("--paper: \"005\" is not 000"), std::string::npos) << bad.error().message;
  auto mixed = parse({"--paper", "000", "--suite", "grass", "--out", "x"});
  ASSERT_FALSE(mixed.ok());
  EXPECT_NE(mixed.error().message.find("takes no SCENE, --suite"), std::string::npos) << mixed.error().message;
  auto quick_alone = parse({"--suite", "grass", "--quick", "--out", "x"});
  ASSERT_FALSE(quick_alone.ok());
  EXPECT_NE(quick_alone.error().message.find("--quick goes with --paper"), std::string::npos);
}

// --table picks tables of one thesis by their id or a part of a combined id.
TEST(BenchOptions, PaperTables) {
  auto o = parse({"--paper", "002", "--table", "4.8", "--table", "3.1", "--out", "x"});
  ASSERT_TRUE(o.ok()) << o.error().message;
  EXPECT_EQ(o->tables, (std::vector<std::string>{"4.8", "3.1"}));
  auto unknown = parse({"--paper", "000", "--table", "4.8", "--out", "x"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.error().message.find("--table: seed 000 has no table \"4.8\" (its tables: 5.1; 5.2; 5.3; 5.4; 5.5; 5.6)"),
            std::string::npos)
      << unknown.error().message;
  auto all = parse({"--paper", "all", "--table", "5.5", "--out", "x"});
  ASSERT_FALSE(all.ok());
  EXPECT_NE(all.error().message.find("--table goes with --paper and one thesis"), std::string::npos);
  const std::vector<PaperTable> t002 = paper_tables("002");
  EXPECT_TRUE(paper_table_matches(t002[6], "4.6, 4.8, 4.10"));
  EXPECT_TRUE(paper_table_matches(t002[6], "4.10"));
  EXPECT_FALSE(paper_table_matches(t002[6], "4.1"));
  EXPECT_FALSE(paper_table_matches(t002[6], "4.7"));
}

}  // namespace
}  // namespace sylva::bench
