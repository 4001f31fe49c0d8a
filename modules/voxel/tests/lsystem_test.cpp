// L-system parsing and derivation: the seed's grammars parse and expand deterministically; bad
// files report the right line and column; an exploding grammar stops at the cap.

#include <sylva/voxel/lsystem.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

namespace sylva::voxel {
namespace {

// "<source>:<line>:<col>: ..." -> (line, col)
std::pair<int, int> where(const Error& e) {
  const std::string& m = e.message;
  const auto c1 = m.find(':');
  const auto c2 = m.find(':', c1 + 1);
  const auto c3 = m.find(':', c2 + 1);
  if (c1 == std::string::npos || c2 == std::string::npos || c3 == std::string::npos) return {-1, -1};
  return {std::stoi(m.substr(c1 + 1, c2 - c1 - 1)), std::stoi(m.substr(c2 + 1, c3 - c2 - 1))};
}

TEST(LSystemParse, SeedAcaciaVerbatim) {
  auto r = load_builtin_lsystems("acacia.lsys");
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_EQ(r->size(), 1u);
  const LSystem& s = r->front();
  EXPECT_FLOAT_EQ(s.yaw_angle, 45.0f);
  EXPECT_FLOAT_EQ(s.pitch_angle, 45.0f);
  EXPECT_FLOAT_EQ(s.shrink_ratio, 0.8f);
  EXPECT_EQ(s.axiom, "^uA1S&F+F+F+F");
  ASSERT_EQ(s.rules.size(), 10u);
  EXPECT_EQ(s.rules_for('A').size(), 6u);  // 1/6 each (seed §4.4)
  EXPECT_EQ(s.rules_for('E').size(), 3u);
  EXPECT_EQ(s.rules_for('U').size(), 1u);
  EXPECT_EQ(s.rules[7].production, "x[++++UE1S&F+F+F+F]+UE") << "whitespace inside productions is ignored";
  EXPECT_EQ(s.rules[7].line, 13);
}

TEST(LSystemParse, EveryShippedFileParses) {
  const auto files = builtin_lsystem_files();
  EXPECT_GE(files.size(), 5u);
  for (const auto& f : files) {
    auto r = load_builtin_lsystems(f);
    EXPECT_TRUE(r.ok()) << f << ": " << (r.ok() ? "" : r.error().message);
  }
  auto examples = load_builtin_lsystems("seed_examples.lsys");
  ASSERT_TRUE(examples.ok());
  EXPECT_EQ(examples->size(), 4u) << "several systems per file";
  EXPECT_FALSE(load_builtin_lsystems("nope.lsys").ok());
}

TEST(LSystemParse, FileOnDiskMatchesEmbedded) {
  auto disk = load_lsystems(std::string(SYLVA_VOXEL_DATA_DIR) + "/acacia.lsys");
  ASSERT_TRUE(disk.ok()) << disk.error().message;
  EXPECT_EQ(disk->front().axiom, load_builtin_lsystems("acacia.lsys")->front().axiom);
  auto missing = load_lsystems("/nonexistent/x.lsys");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::kNotFound);
}

struct BadCase {
  const char* name;
  const char* text;
  int line;
  int column;
  const char* says;
};

TEST(LSystemParse, MalformedFilesNameLineAndColumn) {
  const BadCase cases[] = {
      {"missing axiom", "45 45 0.8\nA > uA\n", 2, 3, "missing axiom"},
      {"missing axiom at end", "# c\n45 45 0.8\n", 3, 1, "missing axiom"},
      {"header then header", "45 45 0.8\n30 30 0.5\nF\n", 2, 1, "missing axiom"},
      {"bad angle", "45 abc 0.8\nF\n", 1, 4, "pitch_angle 'abc'"},
      {"two numbers", "45 45\nF\n", 1, 6, "expected 3 numbers"},
      {"four numbers", "45 45 0.8 1\nF\n", 1, 11, "expected 3 numbers"},
      {"shrink zero", "45 45 0\nF\n", 1, 7, "shrink_ratio"},
      {"angle too big", "  720 45 0.8\nF\n", 1, 3, "yaw_angle"},
      {"unknown byte", "45 45 0.8\nF\nA > u\xc3\xa4u\n", 3, 6, "unknown symbol"},
      {"control char", "45 45 0.8\nF\x01\n", 2, 2, "unknown symbol"},
      {"hash mid-line", "45 45 0.8\nF\nA > uu # grow\n", 3, 8, "'#'"},
      {"unbalanced open", "45 45 0.8\nF\nA > u[+u[-u]\n", 3, 6, "unbalanced '['"},
      {"unbalanced close", "45 45 0.8\nF\nA > u]u\n", 3, 6, "unbalanced ']'"},
      {"unbalanced axiom", "45 45 0.8\n  F[F\n", 2, 4, "unbalanced '['"},
      {"two letters", "45 45 0.8\nF\nAB > u\n", 3, 2, "single letter"},
      {"no letter", "45 45 0.8\nF\n > u\n", 3, 2, "no letter"},
      {"stray line", "45 45 0.8\nF\nA > u\nhello\n", 4, 1, "expected a rule"},
      {"second system broken", "45 45 0.8\nF\n10 10 1\nG\nG > [\n", 5, 5, "unbalanced '['"},
      {"empty", "# only a comment\n\n", 1, 1, "no L-system"},
  };
  for (const auto& c : cases) {
    auto r = parse_lsystems(c.text, "bad.lsys");
    ASSERT_FALSE(r.ok()) << c.name;
    EXPECT_EQ(r.error().code, ErrorCode::kParse) << c.name;
    const auto [line, col] = where(r.error());
    EXPECT_EQ(line, c.line) << c.name << ": " << r.error().message;
    EXPECT_EQ(col, c.column) << c.name << ": " << r.error().message;
    EXPECT_NE(r.error().message.find(c.says), std::string::npos) << c.name << ": " << r.error().message;
    EXPECT_EQ(r.error().message.rfind("bad.lsys:", 0), 0u) << r.error().message;
  }
}

TEST(LSystemParse, CommentsBlankLinesAndCrlf) {
  auto r = parse_lsystems("# a\r\n\r\n  45 45 0.8\r\n# b\r\nF\r\n\r\nF > FF\r\n", "x");
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->front().axiom, "F");
  EXPECT_EQ(r->front().rules.front().production, "FF");
}

TEST(LSystemDerive, KochIslandLengthAndDeterminism) {
  auto r = load_builtin_lsystems("seed_examples.lsys");
  ASSERT_TRUE(r.ok());
  const LSystem& koch = (*r)[0];
  // Each F becomes 8 F's and 7 turns: |F| = 4 * 8^n.
  for (int n = 0; n <= 3; ++n) {
    auto s = derive(koch, n, 1);
    ASSERT_TRUE(s.ok());
    EXPECT_EQ(std::count(s->begin(), s->end(), 'F'), 4 * (1 << (3 * n)));
  }
}

TEST(LSystemDerive, StochasticChoiceDependsOnlyOnSalt) {
  auto r = load_builtin_lsystems("acacia.lsys");
  ASSERT_TRUE(r.ok());
  const LSystem& s = r->front();
  const auto a1 = derive(s, 4, 7);
  const auto a2 = derive(s, 4, 7);
  ASSERT_TRUE(a1.ok() && a2.ok());
  EXPECT_EQ(*a1, *a2);
  int different = 0;
  for (std::uint64_t salt = 1; salt <= 20; ++salt) different += *derive(s, 4, salt) != *a1;
  EXPECT_GE(different, 15) << "different salts give different topologies";
  // Every rule of the letter A gets chosen over many salts (uniform choice, seed §4.4).
  std::set<std::string> firsts;
  for (std::uint64_t salt = 1; salt <= 200; ++salt) firsts.insert(derive(s, 1, salt)->substr(0, 6));
  EXPECT_EQ(firsts.size(), 6u);
}

TEST(LSystemDerive, ExplodingGrammarStopsAtTheCap) {
  auto r = parse_lsystems("30 30 0.7\nA\nA > AAAAAAAAAA\n", "bomb.lsys");
  ASSERT_TRUE(r.ok());
  ExpansionLimits limits;
  limits.max_symbols = 1'000'000;
  auto s = derive(r->front(), 12, 1, limits);  // 10^12 symbols uncapped
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kLimit);
  EXPECT_NE(s.error().message.find("bomb.lsys:1"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("max_symbols=1000000"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("derivation 7 of 12"), std::string::npos) << s.error().message;
  // It names the real knob, not a --set path that no scene has (issue 17).
  EXPECT_NE(s.error().message.find("voxel::ExpansionLimits::max_symbols"), std::string::npos) << s.error().message;
  EXPECT_EQ(s.error().message.find("voxel.lsystem"), std::string::npos) << s.error().message;
  // Below the cap it still works.
  EXPECT_TRUE(derive(r->front(), 5, 1, limits).ok());
}

}  // namespace
}  // namespace sylva::voxel
