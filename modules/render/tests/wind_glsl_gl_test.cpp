// render/lib/noise.glsl and render/lib/wind.glsl against their CPU twins in sylva::core.
//
// A compute shader evaluates the hash, gradient noise, fBm, ridged fBm and the wind at thousands
// of points and writes them to storage buffers; the test compares every value with the CPU.
// Tolerances: the hash must match bit for bit; noise values (range [-1, 1]) within 1e-5; fBm
// within 2e-5; wind vectors within 1e-5 * max_speed (m/s). These allow for the driver fusing
// multiply-adds (llvmpipe does) and for a floor() landing on the other side of a lattice line
// after such a rounding difference, which the continuity of the noise keeps tiny.
#include <sylva/core/image.hpp>
#include <sylva/core/noise.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/testing.hpp>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <vector>

namespace sylva::render {
namespace {

constexpr const char* kComputeSource = R"(#version 450 core
layout(local_size_x = 64) in;
#include "render/lib/wind.glsl"

layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
layout(std430, binding = 2) writeonly buffer Hashes { uvec4 hashes[]; };
layout(std140, binding = 0) uniform SylvaWindBlock { SylvaWind u_wind; };

uniform uint u_count;
uniform uint u_seed;
uniform int u_octaves;
uniform float u_persistence;
uniform float u_lacunarity;
uniform float u_frequency;
uniform float u_ridge_gain;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  vec3 p = points[i].xyz;
  results[i * 3u + 0u] = vec4(sylva_wind(u_wind, p), 0.0);
  results[i * 3u + 1u] = vec4(sylva_noise1(p.x, u_seed), sylva_noise2(p.xy, u_seed), sylva_noise3(p, u_seed),
                              sylva_noise3(ivec3(int(i), -7, 65535), p, u_seed));
  results[i * 3u + 2u] = vec4(sylva_fbm2(p.xy, u_octaves, u_persistence, u_lacunarity, u_frequency, u_seed),
                              sylva_fbm3(p, u_octaves, u_persistence, u_lacunarity, u_frequency, u_seed),
                              sylva_ridged2(p.xy, u_octaves, u_persistence, u_lacunarity, u_frequency, u_seed, u_ridge_gain),
                              sylva_ridged3(p, u_octaves, u_persistence, u_lacunarity, u_frequency, u_seed, u_ridge_gain));
  hashes[i] = uvec4(sylva_pcg_hash(i), sylva_hash(floatBitsToUint(p.x), i),
                    sylva_hash(ivec2(int(i), -int(i)), u_seed), sylva_hash(ivec3(floor(p)), u_seed));
}
)";

struct GpuOutput {
  std::vector<glm::vec4> results;  // 3 per point
  std::vector<glm::uvec4> hashes;  // 1 per point
};

class WindGlsl : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    embedded::register_render_shaders();
    register_shader_source("wind_glsl_test/eval.comp", kComputeSource);
    Result<Program> p = Program::create({"wind_glsl_test/eval.comp"});
    ASSERT_TRUE(p.ok()) << p.error().describe();
    program_ = std::move(p).value();
  }

  GpuOutput run(const std::vector<glm::vec4>& points, const WindGpuParams& wind, std::uint32_t seed,
                const FbmSettings& fbm) {
    const auto count = static_cast<std::uint32_t>(points.size());
    const Buffer in = Buffer::immutable(std::span<const glm::vec4>(points));
    const Buffer out = Buffer::immutable(points.size() * 3 * sizeof(glm::vec4), nullptr);
    const Buffer hashes = Buffer::immutable(points.size() * sizeof(glm::uvec4), nullptr);
    const Buffer ubo = Buffer::immutable(sizeof(WindGpuParams), &wind);
    in.bind_base(GL_SHADER_STORAGE_BUFFER, 0);
    out.bind_base(GL_SHADER_STORAGE_BUFFER, 1);
    hashes.bind_base(GL_SHADER_STORAGE_BUFFER, 2);
    ubo.bind_base(GL_UNIFORM_BUFFER, 0);
    program_.set("u_count", count);
    program_.set("u_seed", seed);
    program_.set("u_octaves", fbm.octaves);
    program_.set("u_persistence", fbm.persistence);
    program_.set("u_lacunarity", fbm.lacunarity);
    program_.set("u_frequency", fbm.frequency);
    program_.set("u_ridge_gain", fbm.ridge_gain);
    program_.use();
    glDispatchCompute((count + 63u) / 64u, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    GpuOutput o;
    o.results.resize(points.size() * 3);
    o.hashes.resize(points.size());
    out.read(0, o.results.size() * sizeof(glm::vec4), o.results.data());
    hashes.read(0, o.hashes.size() * sizeof(glm::uvec4), o.hashes.data());
    glUseProgram(0);
    return o;
  }

  Program program_;
};

std::vector<glm::vec4> random_points(std::uint64_t seed, int n, float extent) {
  Pcg32 rng(seed);
  std::vector<glm::vec4> pts;
  for (int i = 0; i < n; ++i)
    pts.emplace_back(rng.uniform(-extent, extent), rng.uniform(-extent, extent), rng.uniform(-extent, extent), 0.0f);
  return pts;
}

TEST_F(WindGlsl, HashIsBitExactAndNoiseMatchesTheCpu) {
  std::vector<glm::vec4> pts = random_points(1, 4096, 1000.0f);
  // Lattice lines, negative zero, near-integers, far coordinates.
  for (float v : {0.0f, -0.0f, 1.0f, -1.0f, 0.99999994f, -1e-7f, 65535.5f, 65536.25f, -65536.75f, 1e5f, -3.1e5f})
    pts.emplace_back(v, -v * 0.5f, v + 0.25f, 0.0f);
  const std::uint32_t seed = 1234567u;
  FbmSettings fbm;
  fbm.octaves = 7;
  fbm.frequency = 0.02f;
  fbm.seed = seed;
  const GpuOutput gpu = run(pts, WindField().frame(0.0).gpu, seed, fbm);

  float worst_noise = 0.0f;
  float worst_fbm = 0.0f;
  int hash_mismatches = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::vec3 p(pts[i]);
    const auto idx = static_cast<std::uint32_t>(i);
    const glm::uvec4 h = gpu.hashes[i];
    const glm::uvec4 expected_h(pcg_hash(idx), hash_u32(std::bit_cast<std::uint32_t>(p.x), idx),
                                hash_i32(static_cast<std::int32_t>(idx), -static_cast<std::int32_t>(idx), seed),
                                hash_i32(static_cast<std::int32_t>(std::floor(p.x)), static_cast<std::int32_t>(std::floor(p.y)),
                                         static_cast<std::int32_t>(std::floor(p.z)), seed));
    hash_mismatches += h == expected_h ? 0 : 1;

    const glm::vec4 n = gpu.results[i * 3 + 1];
    const glm::vec4 expected_n(gradient_noise1(p.x, seed), gradient_noise2(glm::vec2(p), seed), gradient_noise3(p, seed),
                               gradient_noise3(glm::ivec3(static_cast<int>(i), -7, 65535), p, seed));
    for (int c = 0; c < 4; ++c) worst_noise = std::max(worst_noise, std::abs(n[c] - expected_n[c]));

    // fBm takes the seed from the settings; the shader passes u_seed, equal to fbm.seed.
    const glm::vec4 f = gpu.results[i * 3 + 2];
    const glm::vec4 expected_f(fbm2(glm::vec2(p), fbm), fbm3(p, fbm), ridged2(glm::vec2(p), fbm), ridged3(p, fbm));
    for (int c = 0; c < 4; ++c) worst_fbm = std::max(worst_fbm, std::abs(f[c] - expected_f[c]));
  }
  EXPECT_EQ(hash_mismatches, 0);
  EXPECT_LE(worst_noise, 1e-5f);
  EXPECT_LE(worst_fbm, 2e-5f);
  RecordProperty("max_noise_difference", std::to_string(worst_noise));
  RecordProperty("max_fbm_difference", std::to_string(worst_fbm));
  std::printf("noise.glsl vs CPU over %zu points: max |noise diff| %.3g, max |fbm diff| %.3g\n", pts.size(),
              static_cast<double>(worst_noise), static_cast<double>(worst_fbm));
}

struct WindCase {
  const char* name;
  WindSettings settings;
  double time;
  glm::dvec3 origin;
};

TEST_F(WindGlsl, WindMatchesTheCpuAtManyPointsTimesAndOrigins) {
  WindSettings breeze;
  WindSettings gusty;
  gusty.strength = 12.0f;
  gusty.gust_amplitude = 8.0f;
  gusty.gust_period = 2.0f;
  gusty.direction_deg = 123.0f;
  gusty.turbulence_octaves = 4;
  gusty.turbulence_scale = 2.5f;
  WindSettings hurricane;
  hurricane.strength = 100.0f;
  hurricane.gust_amplitude = 100.0f;
  hurricane.gust_period = 0.1f;
  hurricane.turbulence_amplitude = 100.0f;
  hurricane.turbulence_scale = 0.05f;
  hurricane.turbulence_vertical = 1.0f;
  hurricane.seed = 77u;
  const std::vector<WindCase> cases = {
      {"breeze t=0", breeze, 0.0, {0.0, 0.0, 0.0}},
      {"gusty t=1234.5 off-origin", gusty, 1234.5, {100.0, 3.0, -50.0}},
      {"gusty t=1e7 at 1e6 m", gusty, 1e7, {1e6, 20.0, -1e6}},
      {"hurricane t=5e6", hurricane, 5e6, {-3e5, 0.0, 7e5}},
  };
  const std::vector<glm::vec4> local = random_points(2, 4096, 200.0f);
  for (const WindCase& c : cases) {
    const WindField wind(c.settings);
    const WindFrame frame = wind.frame(c.time, c.origin);
    const GpuOutput gpu = run(local, frame.gpu, 0u, FbmSettings{});
    float worst = 0.0f;
    float worst_world = 0.0f;
    for (std::size_t i = 0; i < local.size(); ++i) {
      const glm::vec3 g(gpu.results[i * 3]);
      ASSERT_TRUE(std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z)) << c.name;
      const glm::vec3 cpu = WindField::evaluate(frame, glm::vec3(local[i]));
      worst = std::max(worst, glm::length(g - cpu));
      // And against the double-precision world evaluation (differs by float rounding of local).
      const glm::vec3 world = wind.evaluate(c.origin + glm::dvec3(glm::vec3(local[i])), c.time);
      worst_world = std::max(worst_world, glm::length(g - world) / wind.max_speed());
    }
    EXPECT_LE(worst, 1e-5f * wind.max_speed()) << c.name;
    EXPECT_LE(worst_world, 2e-3f) << c.name;
    std::printf("wind.glsl vs CPU, %s: max |dv| %.3g m/s (max speed %.1f m/s), vs world evaluation %.3g relative\n",
                c.name, static_cast<double>(worst), static_cast<double>(wind.max_speed()),
                static_cast<double>(worst_world));
  }
}

TEST_F(WindGlsl, FieldPicture) {
  // A 256x144 top-down view of the GPU wind (x, z components as red/green around the mean) and
  // of GPU fBm, written for a visual check.
  WindSettings s;
  s.strength = 4.0f;
  s.gust_amplitude = 3.0f;
  s.turbulence_amplitude = 2.0f;
  s.turbulence_scale = 8.0f;
  const WindField wind(s);
  std::vector<glm::vec4> pts;
  for (int y = 0; y < 144; ++y)
    for (int x = 0; x < 256; ++x) pts.emplace_back(x * 0.5f, 1.0f, y * 0.5f, 0.0f);
  FbmSettings fbm;
  fbm.frequency = 0.05f;
  const GpuOutput gpu = run(pts, wind.frame(10.0).gpu, 0u, fbm);
  Image img(256, 144, 3);
  double variance = 0.0;
  for (int y = 0; y < 144; ++y) {
    for (int x = 0; x < 256; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * 256 + static_cast<std::size_t>(x);
      const glm::vec3 v = glm::vec3(gpu.results[i * 3]) - wind.direction() * s.strength;
      img.at(x, y, 0) = std::clamp(0.5f + v.x / 8.0f, 0.0f, 1.0f);
      img.at(x, y, 1) = std::clamp(0.5f + v.z / 8.0f, 0.0f, 1.0f);
      img.at(x, y, 2) = 0.5f + 0.5f * gpu.results[i * 3 + 2].x;
      variance += static_cast<double>(v.x * v.x);
    }
  }
  EXPECT_GT(variance / (256.0 * 144.0), 0.05) << "the wind picture is flat";
  // Into the test temp folder, so running the test from a source checkout leaves no files.
  const std::string path = ::testing::TempDir() + "sylva_wind_glsl_field.png";
  const Status written = write_image(path, img, PixelFormat::kU8);
  EXPECT_TRUE(written.ok()) << written.error().describe();
  std::printf("wrote %s\n", path.c_str());
}

}  // namespace
}  // namespace sylva::render
