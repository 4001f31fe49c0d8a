#pragma once
// Test support for GL tests of every module (header-only; include it only from test code,
// which links GoogleTest). Pattern:
//
//   #include <sylva/render/testing.hpp>
//   using MyTest = sylva::render::GlTest;
//   TEST_F(MyTest, DrawsSomething) { ... }
//
// One headless EGL context is created per test executable (the first GlTest to run creates it;
// creation failure fails every GL test with the EGL message). GL error recording is on during
// each test; TearDown drains glGetError and fails the test naming every GL error that the
// debug output or glGetError reported while it ran.

#include <sylva/render/gl_context.hpp>
#include <sylva/render/gl_debug.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace sylva::render {

// The process-wide headless test context (created on first call, kept until exit).
// Returns null and sets `error` when EGL could not give a 4.5 core context.
GlContext* shared_test_context(std::string* error = nullptr);

// Restores the default GL state Sylva expects between tests: reversed-Z clip control and depth
// function, no blending, default framebuffer bindings, unpack/pack alignment 1.
void reset_test_gl_state();

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    context_ = shared_test_context(&error);
    ASSERT_NE(context_, nullptr) << "no headless GL 4.5 context: " << error;
    context_->make_current();
    reset_test_gl_state();
    set_gl_error_recording(true);
    (void)take_gl_errors();
  }

  void TearDown() override {
    if (context_ == nullptr) return;
    (void)check_gl_errors("end of test");
    const std::vector<std::string> errors = take_gl_errors();
    set_gl_error_recording(false);
    std::string all;
    for (const std::string& e : errors) all += "\n  " + e;
    EXPECT_TRUE(errors.empty()) << errors.size() << " GL error(s) during the test:" << all;
  }

  // Errors recorded so far in this test (clears them); for tests that provoke GL errors on
  // purpose and check them.
  std::vector<std::string> take_errors() { return take_gl_errors(); }

  GlContext* context_ = nullptr;
};

}  // namespace sylva::render
