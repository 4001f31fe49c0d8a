#include "support/render_test_support.hpp"

#include <sylva/core/log.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva::render::test {

std::filesystem::path output_dir() {
  // Beside the test executable (not the working directory, which may be the source tree).
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path base = ec ? std::filesystem::current_path() : exe.parent_path();
  std::filesystem::path dir = base / "test_output" / "render";
  std::filesystem::create_directories(dir, ec);
  return dir;
}

void save_for_inspection(const Image& image, std::string_view name) {
  const std::filesystem::path path = output_dir() / (std::string(name) + ".png");
  Status s = write_image(path, image, PixelFormat::kU8);
  if (!s.ok()) log_warn("could not save {}: {}", path.string(), s.error().describe());
}

Framebuffer make_target(int width, int height, int samples) {
  Result<Framebuffer> fb = Framebuffer::create({.width = width, .height = height, .samples = samples});
  EXPECT_TRUE(fb.ok()) << (fb.ok() ? "" : fb.error().describe());
  if (!fb.ok()) return {};
  return std::move(fb).value();
}

Program build_or_fail(std::initializer_list<std::string_view> stages, const ShaderDefines& defines) {
  Result<Program> p = Program::create(stages, defines);
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().describe());
  if (!p.ok()) return {};
  return std::move(p).value();
}

float max_abs_diff(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() != b.channels()) {
    return std::numeric_limits<float>::infinity();
  }
  float m = 0.0f;
  for (std::size_t i = 0; i < a.data().size(); ++i) m = std::max(m, std::abs(a.data()[i] - b.data()[i]));
  return m;
}

int count_color(const Image& image, float r, float g, float b, float tolerance) {
  int n = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (std::abs(image.at(x, y, 0) - r) <= tolerance && std::abs(image.at(x, y, 1) - g) <= tolerance &&
          std::abs(image.at(x, y, 2) - b) <= tolerance) {
        ++n;
      }
    }
  }
  return n;
}

}  // namespace sylva::render::test
