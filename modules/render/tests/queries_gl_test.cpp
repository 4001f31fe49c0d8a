// Timer and statistics queries return plausible values: exact primitive and sample counts for
// known draws, GPU time that is positive and lies within the wall time around the work, results
// that arrive through the ring without waiting, and per-frame records from FrameProfiler.
// No test compares one duration with another or with a budget (a loaded machine makes any such
// bound fail now and then); how GPU time grows with the work is printed, not asserted.
#include "support/render_test_support.hpp"

#include <sylva/core/timer.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include <gtest/gtest.h>

#include <cstdio>

namespace sylva::render {
namespace {

constexpr int kW = 64;
constexpr int kH = 32;

class QueriesTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    // Full-screen quad as two triangles from gl_VertexID; u_iterations makes fragments costly.
    register_shader_source("rtest/quad.vert",
                           "#version 450 core\n"
                           "uniform float u_depth;\n"
                           "void main() {\n"
                           "  const vec2 p[6] = vec2[](vec2(-1,-1), vec2(1,-1), vec2(1,1),\n"
                           "                           vec2(-1,-1), vec2(1,1), vec2(-1,1));\n"
                           "  gl_Position = vec4(p[gl_VertexID % 6], u_depth, 1.0);\n"
                           "}\n");
    register_shader_source("rtest/costly.frag",
                           "#version 450 core\n"
                           "uniform int u_iterations;\n"
                           "out vec4 o_color;\n"
                           "void main() {\n"
                           "  vec2 z = gl_FragCoord.xy * 0.001;\n"
                           "  for (int i = 0; i < u_iterations; ++i) z = vec2(z.x * z.x - z.y * z.y, 2.0 * z.x * z.y) + 0.3;\n"
                           "  o_color = vec4(fract(z), 0.0, 1.0);\n"
                           "}\n");
    program_ = test::build_or_fail({"rtest/quad.vert", "rtest/costly.frag"});
    vao_ = VertexArray::create();
    fb_ = test::make_target(kW, kH);
  }

  void draw_quads(int quads, int iterations, float depth = 0.5f) {
    fb_.bind();
    program_.set("u_iterations", iterations);
    program_.set("u_depth", depth);
    program_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 6 * quads);
  }

  Program program_;
  VertexArray vao_;
  Framebuffer fb_;
};

TEST_F(QueriesTest, CountsPrimitivesAndSamplesExactly) {
  fb_.bind();
  fb_.clear({0, 0, 0, 1});
  glDisable(GL_DEPTH_TEST);
  PassQuery q = PassQuery::create(true);
  const Stopwatch wall;
  q.begin(7);
  draw_quads(3, 1);
  q.end();
  std::optional<PassQueryResult> r = q.wait_all();
  const double wall_ms = wall.elapsed_ms();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->frame, 7u);
  EXPECT_EQ(r->primitives, 6u);
  EXPECT_EQ(r->samples, 3u * kW * kH);
  // Both timestamps are taken between begin() and the result's arrival.
  EXPECT_GE(r->gpu_ms, 0.0);
  EXPECT_LE(r->gpu_ms, wall_ms);
}

TEST_F(QueriesTest, SamplesPassedRespectsDepthTest) {
  fb_.bind();
  fb_.clear({0, 0, 0, 1});
  apply_reversed_z_state();
  draw_quads(1, 1, 0.8f);  // near surface (reversed-Z: larger is nearer)
  PassQuery q = PassQuery::create(true);
  q.begin(1);
  draw_quads(1, 1, 0.2f);  // behind it: every fragment fails GL_GREATER
  q.end();
  std::optional<PassQueryResult> r = q.wait_all();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->samples, 0u);
  EXPECT_EQ(r->primitives, 2u);
}

TEST_F(QueriesTest, GpuTimeOfRealWorkIsPositiveAndWithinItsWallTime) {
  fb_.bind();
  glDisable(GL_DEPTH_TEST);
  PassQuery q = PassQuery::create(false);
  std::uint64_t frame = 0;
  auto measure = [&](int quads, int iterations) {
    const Stopwatch wall;
    q.begin(++frame);
    draw_quads(quads, iterations);
    q.end();
    std::optional<PassQueryResult> r = q.wait_all();
    const double wall_ms = wall.elapsed_ms();
    EXPECT_TRUE(r.has_value());
    if (!r) return 0.0;
    EXPECT_EQ(r->frame, frame);
    EXPECT_GE(r->gpu_ms, 0.0);
    EXPECT_LE(r->gpu_ms, wall_ms);
    return r->gpu_ms;
  };
  const double light = measure(1, 1);
  const double heavy = measure(20, 3000);  // ~10^8 loop iterations: never too short for the timer
  EXPECT_GT(heavy, 0.0) << "the timer query measured nothing";
  std::printf("GPU time: 1 quad x 1 iteration %.3f ms, 20 quads x 3000 iterations %.3f ms\n", light, heavy);
}

TEST_F(QueriesTest, RingDeliversResultsWithoutWaiting) {
  fb_.bind();
  glDisable(GL_DEPTH_TEST);
  PassQuery q = PassQuery::create(true);
  std::vector<std::uint64_t> frames_seen;
  for (std::uint64_t frame = 1; frame <= 20; ++frame) {
    q.begin(frame);
    draw_quads(1, 50);
    q.end();
    glFlush();
    for (const PassQueryResult& r : q.collect(false)) {
      frames_seen.push_back(r.frame);
      EXPECT_EQ(r.primitives, 2u);
      EXPECT_EQ(r.samples, static_cast<std::uint64_t>(kW * kH));
    }
  }
  for (const PassQueryResult& r : q.collect(true)) {
    frames_seen.push_back(r.frame);
    EXPECT_EQ(r.samples, static_cast<std::uint64_t>(kW * kH)) << "frame " << r.frame;
  }
  // Every frame's result arrives exactly once and in order (nothing dropped at this pace).
  ASSERT_EQ(frames_seen.size() + q.dropped(), 20u);
  for (std::size_t i = 1; i < frames_seen.size(); ++i) EXPECT_LT(frames_seen[i - 1], frames_seen[i]);
  EXPECT_FALSE(q.poll().has_value());  // nothing new
}

TEST_F(QueriesTest, FrameProfilerReportsPassesAndNestedScopes) {
  fb_.bind();
  glDisable(GL_DEPTH_TEST);
  FrameProfiler profiler;
  const Stopwatch wall;
  for (int frame = 0; frame < 12; ++frame) {
    profiler.begin_frame();
    profiler.begin("opaque");
    profiler.begin("opaque/terrain", false);  // nested: timestamps only
    draw_quads(2, 20);
    profiler.end("opaque/terrain");
    draw_quads(1, 1);
    profiler.end("opaque");
    profiler.add_cpu_counts("opaque/terrain", {.triangles = 4, .draw_calls = 1, .instances = 1});
    profiler.begin("transparent");
    profiler.end("transparent");
    profiler.end_frame();
  }
  // Results arrived without any wait while frames were running.
  ASSERT_TRUE(profiler.latest().has_value());
  EXPECT_LE(profiler.latest()->frame, 12u);
  std::optional<FrameStats> stats = profiler.flush();
  const double wall_ms = wall.elapsed_ms();
  ASSERT_TRUE(stats.has_value());
  EXPECT_EQ(stats->frame, 12u);
  const PassStats& opaque = stats->passes.at("opaque");
  const PassStats& terrain = stats->passes.at("opaque/terrain");
  EXPECT_EQ(opaque.primitives, 6u);
  EXPECT_EQ(opaque.samples, 3u * kW * kH);
  EXPECT_EQ(terrain.triangles, 4u);
  EXPECT_EQ(terrain.draw_calls, 1u);
  EXPECT_GT(opaque.gpu_ms, 0.0);
  EXPECT_LE(opaque.gpu_ms, wall_ms);
  // Nested timestamps lie inside the outer scope's (not a comparison of two measurements).
  EXPECT_LE(terrain.gpu_ms, opaque.gpu_ms * 1.001 + 1e-3);
  EXPECT_EQ(stats->passes.at("transparent").samples, 0u);
  // The frame total sums the top-level passes only.
  EXPECT_NEAR(stats->gpu_ms, opaque.gpu_ms + stats->passes.at("transparent").gpu_ms, 1e-9);
  EXPECT_GE(stats->cpu_ms, 0.0);
  EXPECT_LE(stats->cpu_ms, wall_ms);
}

TEST_F(QueriesTest, SynchronousModeMeasuresWallTime) {
  fb_.bind();
  glDisable(GL_DEPTH_TEST);
  FrameProfiler profiler;
  profiler.set_synchronous(true);
  const Stopwatch wall;
  for (int frame = 0; frame < 3; ++frame) {
    profiler.begin_frame();
    profiler.begin("light");
    draw_quads(1, 1);
    profiler.end("light");
    profiler.begin("heavy");
    draw_quads(20, 3000);
    profiler.end("heavy");
    profiler.end_frame();
  }
  std::optional<FrameStats> stats = profiler.flush();
  const double wall_ms = wall.elapsed_ms();
  ASSERT_TRUE(stats.has_value());
  // The scope's wall time (glFinish on both sides) contains its GPU timestamps, and the scopes
  // of one frame lie inside the whole run.
  for (const char* name : {"light", "heavy"}) {
    const PassStats& p = stats->passes.at(name);
    EXPECT_GE(p.sync_ms, p.gpu_ms - 1e-3) << name;
    EXPECT_GT(p.sync_ms, 0.0) << name << ": synchronous mode did not fill sync_ms";
  }
  EXPECT_LE(stats->passes.at("light").sync_ms + stats->passes.at("heavy").sync_ms, wall_ms);
  EXPECT_GT(stats->passes.at("heavy").gpu_ms, 0.0);
  EXPECT_EQ(stats->passes.at("heavy").samples, 20u * kW * kH);
}

TEST(PassStatsTest, Accumulates) {
  PassStats a{.gpu_ms = 1.0, .sync_ms = 0.5, .primitives = 2, .samples = 3, .triangles = 4, .draw_calls = 5, .instances = 6};
  a += a;
  EXPECT_EQ(a.gpu_ms, 2.0);
  EXPECT_EQ(a.sync_ms, 1.0);
  EXPECT_EQ(a.primitives, 4u);
  EXPECT_EQ(a.instances, 12u);
}

}  // namespace
}  // namespace sylva::render
