// Stability of the parameter system under hostile input. Each test names its invariant:
//  - FailedSetNeverModifies: a rejected set_param / params_from_json leaves every field as it was.
//  - AcceptedSetIsValid: whatever set_param accepts passes validate_params (range, finite).
//  - SetOfGetIsIdentity: set_string(get_string()) reproduces the exact bits of every value.
//  - FloatTextRoundTripIsBitExact / JsonRoundTripIsBitExact: text and JSON round trips of random
//    finite floats and doubles are lossless (shortest-decimal output never loses a bit).
//  - JsonRoundTripIsIdempotent: save(load(save(x))) == save(x), byte for byte.
//  - ExtremeValues: limits of every type load and save exactly; one past them is rejected.

#include "params_fixtures.hpp"

#include <sylva/core/params_json.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

namespace {

using fixture::Scene;
using json = nlohmann::json;

// Hostile text values: wrong types, non-finite, overflow, separators, empty, whitespace, junk.
const std::vector<std::string> kHostileTexts = {
    "", " ", "abc", "nan", "-nan", "inf", "-inf", "infinity", "1e400", "-1e400", "1e-400", "1e39", "-1e39",
    "99999999999", "-99999999999", "18446744073709551616", "-1", "2.5", "0x10", "1,2", "1,2,3,4,5", "[1,2",
    "[]", "()", ",", ",,", "1 2", "true", "yes", "maybe", "1e", "--1", "+-1", "1..2", "\xff\xfe",
    std::string("1\0" "2", 3), "1e308", "-1e308", "3.4028236e38", "4294967296", "9223372036854775808",
    "-9223372036854775809", "0", "64", "64.0000001", "0.0499999", "distance", "blades", "low", "high"};

struct FloatPair {
  float f = 0.f;
  double d = 0.0;
  template <class V> void visit(V& v) {
    v(f, "f");
    v(d, "d");
  }
};

struct FloatTriple {
  float f = 0.f;
  double d = 0.0;
  glm::vec3 v{0.f};
  template <class V> void visit(V& v_) {
    v_(f, "f");
    v_(d, "d");
    v_(v, "v");
  }
};

struct Limits {
  int i32 = 0;
  std::uint32_t u32 = 0;
  std::int64_t i64 = 0;
  std::uint64_t u64 = 0;
  float f = 0.f;
  double d = 0.0;
  template <class V> void visit(V& v) {
    v(i32, "i32");
    v(u32, "u32");
    v(i64, "i64");
    v(u64, "u64");
    v(f, "f");
    v(d, "d");
  }
  bool operator==(const Limits&) const = default;
};

// Random field values of the fixture within their ranges.
Scene random_valid_scene(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  std::uniform_real_distribution<float> signed_unit(-1.f, 1.f);
  Scene s;
  s.terrain.max_pixel_error = 0.05f + unit(rng) * 63.95f;
  s.terrain.world_scale = std::exp(std::uniform_real_distribution<double>(std::log(1e-3), std::log(1e4))(rng));
  s.terrain.chunk_dim = std::uniform_int_distribution<int>(3, 1025)(rng);
  s.terrain.seed = static_cast<std::uint32_t>(rng());
  s.terrain.offset = std::uniform_int_distribution<std::int64_t>(-1000000000000, 1000000000000)(rng);
  s.terrain.hash = rng();
  s.terrain.skirts = (rng() & 1) != 0;
  s.terrain.height_map = std::string(rng() % 20, static_cast<char>('a' + rng() % 26));
  s.terrain.criterion = (rng() & 1) ? fixture::Criterion::kDistance : fixture::Criterion::kScreenSpace;
  s.terrain.quality = (rng() & 1) ? fixture::Quality::kHigh : fixture::Quality::kLow;
  s.terrain.uv_scale = {unit(rng) * 100.f, unit(rng) * 100.f};
  s.terrain.sun_dir = {signed_unit(rng), signed_unit(rng), signed_unit(rng)};
  s.terrain.tint = {unit(rng), unit(rng), unit(rng), unit(rng)};
  s.terrain.tiles = {std::uniform_int_distribution<int>(1, 64)(rng), std::uniform_int_distribution<int>(1, 64)(rng)};
  std::uniform_real_distribution<double> far(-1e7, 1e7);
  s.terrain.origin = {far(rng), far(rng), far(rng)};
  s.terrain.grid = {static_cast<unsigned>(rng() % 1001), static_cast<unsigned>(rng() % 1001), static_cast<unsigned>(rng() % 1001)};
  s.terrain.lod.morph_fraction = unit(rng);
  s.terrain.lod.levels = std::uniform_int_distribution<int>(1, 24)(rng);
  s.grass.density = unit(rng) * 1e5f;
  s.grass.mode = static_cast<fixture::Grass::Mode>(rng() % 3);
  s.grass.name = std::string(1 + rng() % 32, 'g');
  return s;
}

TEST(ParamsStability, FailedSetNeverModifies_AcceptedSetIsValid) {
  std::mt19937_64 rng(1234);
  int rejected = 0;
  int accepted = 0;
  for (int round = 0; round < 4; ++round) {
    Scene s = random_valid_scene(rng);
    const auto params = sylva::describe_params(s);
    for (const sylva::ParamDescriptor& p : params) {
      for (const std::string& text : kHostileTexts) {
        const Scene before = s;
        sylva::Status st = p.set_string(text);
        if (st.ok()) {
          ++accepted;
          ASSERT_TRUE(sylva::validate_params(s).ok()) << p.path << "=" << text << " accepted an invalid value";
        } else {
          ++rejected;
          ASSERT_EQ(s, before) << p.path << "=" << text << " failed but modified the settings";
          ASSERT_TRUE(st.error().message.starts_with(p.path)) << st.error().message;
        }
      }
    }
  }
  EXPECT_GT(rejected, 1000);
  EXPECT_GT(accepted, 100);
}

TEST(ParamsStability, FailedJsonLoadNeverModifies) {
  std::mt19937_64 rng(99);
  const std::vector<json> hostile = {nullptr,  true, -1, 1e300, -1e300, 99999999999, 18446744073709551615ull,
                                     2.5,      "",   "x", json::array(), json::array({1, 2, 3, 4, 5}),
                                     json::array({"a", "b"}), json::object(), json::object({{"k", 1}}),
                                     std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
  Scene s = random_valid_scene(rng);
  const auto params = sylva::describe_params(s);
  const json good = sylva::params_to_json(s);
  int rejected = 0;
  for (const sylva::ParamDescriptor& p : params) {
    for (const json& bad : hostile) {
      // Replace one leaf of an otherwise valid document, and change a valid sibling too, so a
      // partial write would be visible.
      json doc = good;
      doc["grass"]["density"] = s.grass.density == 5.f ? 6.f : 5.f;
      json* node = &doc;
      std::string rest = p.path;
      for (auto dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
        node = &(*node)[rest.substr(0, dot)];
        rest = rest.substr(dot + 1);
      }
      (*node)[rest] = bad;
      const Scene before = s;
      std::vector<std::string> warnings;
      sylva::Status st = sylva::params_from_json(s, doc, warnings);
      if (!st.ok()) {
        ++rejected;
        ASSERT_EQ(s, before) << p.path << "=" << bad.dump() << " failed but modified the settings";
        ASSERT_TRUE(st.error().message.starts_with(p.path)) << st.error().message;
      } else {
        ASSERT_TRUE(sylva::validate_params(s).ok()) << p.path << "=" << bad.dump();
        s = before;
      }
      ASSERT_TRUE(warnings.empty());
    }
  }
  EXPECT_GT(rejected, 250);
}

TEST(ParamsStability, SetOfGetIsIdentity) {
  std::mt19937_64 rng(7);
  for (int round = 0; round < 200; ++round) {
    Scene s = random_valid_scene(rng);
    ASSERT_TRUE(sylva::validate_params(s).ok()) << sylva::validate_params(s).error().message;
    Scene copy;
    copy.grass.name = "something";
    const auto src = sylva::describe_params(s);
    const auto dst = sylva::describe_params(copy);
    for (std::size_t i = 0; i < src.size(); ++i) {
      sylva::Status st = dst[i].set_string(src[i].get_string());
      ASSERT_TRUE(st.ok()) << st.error().message;
    }
    ASSERT_EQ(copy, s);
  }
}

TEST(ParamsStability, FloatTextRoundTripIsBitExact) {
  // Random finite bit patterns cover subnormals, huge and tiny magnitudes and -0.
  std::mt19937_64 rng(42);
  FloatPair a;
  FloatPair b;
  const auto pa = sylva::describe_params(a);
  const auto pb = sylva::describe_params(b);
  int tested = 0;
  for (int i = 0; i < 100000; ++i) {
    a.f = std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
    a.d = std::bit_cast<double>(rng());
    if (!std::isfinite(a.f) || !std::isfinite(a.d)) continue;
    ++tested;
    ASSERT_TRUE(pb[0].set_string(pa[0].get_string()).ok()) << pa[0].get_string();
    ASSERT_TRUE(pb[1].set_string(pa[1].get_string()).ok()) << pa[1].get_string();
    ASSERT_EQ(std::bit_cast<std::uint32_t>(b.f), std::bit_cast<std::uint32_t>(a.f)) << pa[0].get_string();
    ASSERT_EQ(std::bit_cast<std::uint64_t>(b.d), std::bit_cast<std::uint64_t>(a.d)) << pa[1].get_string();
  }
  EXPECT_GT(tested, 95000);
}

TEST(ParamsStability, JsonRoundTripIsBitExact) {
  std::mt19937_64 rng(43);
  const auto random_float = [&] {
    while (true) {
      const float f = std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
      if (std::isfinite(f)) return f;
    }
  };
  for (int i = 0; i < 10000; ++i) {
    FloatTriple a;
    a.f = random_float();
    a.d = std::bit_cast<double>(rng());
    if (!std::isfinite(a.d)) a.d = 1.0;
    a.v = {random_float(), random_float(), random_float()};
    // Through text: what a saved file holds.
    auto parsed = sylva::parse_json_text(sylva::params_to_json(a).dump());
    ASSERT_TRUE(parsed.ok());
    FloatTriple b;
    std::vector<std::string> warnings;
    ASSERT_TRUE(sylva::params_from_json(b, *parsed, warnings).ok());
    ASSERT_EQ(std::bit_cast<std::uint32_t>(b.f), std::bit_cast<std::uint32_t>(a.f));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(b.d), std::bit_cast<std::uint64_t>(a.d));
    for (int c = 0; c < 3; ++c) ASSERT_EQ(std::bit_cast<std::uint32_t>(b.v[c]), std::bit_cast<std::uint32_t>(a.v[c]));
  }
}

TEST(ParamsStability, JsonRoundTripIsIdempotent) {
  std::mt19937_64 rng(5);
  for (int round = 0; round < 200; ++round) {
    const Scene s = random_valid_scene(rng);
    const std::string first = sylva::params_to_json(s).dump();
    Scene loaded;
    std::vector<std::string> warnings;
    ASSERT_TRUE(sylva::params_from_json(loaded, json::parse(first), warnings).ok());
    ASSERT_EQ(loaded, s);
    ASSERT_EQ(sylva::params_to_json(loaded).dump(), first);
  }
}

TEST(ParamsStability, ExtremeValues) {
  const auto check_limits = [](Limits lim) {
    auto parsed = sylva::parse_json_text(sylva::params_to_json(lim).dump());
    ASSERT_TRUE(parsed.ok());
    Limits back;
    std::vector<std::string> warnings;
    sylva::Status st = sylva::params_from_json(back, *parsed, warnings);
    ASSERT_TRUE(st.ok()) << st.error().message;
    EXPECT_EQ(back, lim);
    Limits by_text;
    const auto from = sylva::describe_params(lim);
    const auto to = sylva::describe_params(by_text);
    for (std::size_t i = 0; i < from.size(); ++i) ASSERT_TRUE(to[i].set_string(from[i].get_string()).ok()) << from[i].path;
    EXPECT_EQ(by_text, lim);
  };
  check_limits({std::numeric_limits<int>::max(), std::numeric_limits<std::uint32_t>::max(),
                std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::uint64_t>::max(),
                std::numeric_limits<float>::max(), std::numeric_limits<double>::max()});
  check_limits({std::numeric_limits<int>::min(), 0, std::numeric_limits<std::int64_t>::min(), 0,
                std::numeric_limits<float>::lowest(), std::numeric_limits<double>::lowest()});
  check_limits({0, 0, 0, 0, std::numeric_limits<float>::denorm_min(), std::numeric_limits<double>::denorm_min()});
  check_limits({0, 0, 0, 0, -0.f, -0.0});

  Limits lim;
  EXPECT_FALSE(sylva::set_param(lim, "i32", "2147483648").ok());
  EXPECT_FALSE(sylva::set_param(lim, "i32", "-2147483649").ok());
  EXPECT_FALSE(sylva::set_param(lim, "u32", "4294967296").ok());
  EXPECT_FALSE(sylva::set_param(lim, "i64", "9223372036854775808").ok());
  EXPECT_FALSE(sylva::set_param(lim, "i64", "-9223372036854775809").ok());
  EXPECT_FALSE(sylva::set_param(lim, "u64", "18446744073709551616").ok());
  EXPECT_FALSE(sylva::set_param(lim, "f", "3.5e38").ok());
  EXPECT_FALSE(sylva::set_param(lim, "d", "1.8e308").ok());
  EXPECT_EQ(lim, Limits{});
  // Values that round to a float's largest finite value are accepted (rounding, not overflow).
  EXPECT_TRUE(sylva::set_param(lim, "f", "3.4028235e38").ok());
  EXPECT_EQ(lim.f, std::numeric_limits<float>::max());
}

}  // namespace
