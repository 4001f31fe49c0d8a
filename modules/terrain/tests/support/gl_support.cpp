#include "support/gl_support.hpp"

#include <sylva/render/readback.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace sylva::terrain::testing {

GlTarget GlTarget::create(int width, int height) {
  GlTarget t;
  render::FramebufferDesc desc;
  desc.width = width;
  desc.height = height;
  desc.color_formats = {GL_RGBA8};
  t.target = render::Framebuffer::create(desc).value();
  t.lighting_ubo = render::LightingUniforms::create();
  return t;
}

Image GlTarget::render(render::Drawable& terrain, const render::Camera& camera, const glm::vec4& clear) {
  target.bind();
  render::apply_reversed_z_state();
  target.clear(clear, 0.0f);
  lighting_ubo.update(lighting, camera.position().y, 0.0);
  lighting_ubo.bind();
  render::FrameContext ctx{camera, 0.0, 0.0f, wind, lighting, target.size(), 0};
  terrain.update(ctx);
  render::PassStats stats;
  terrain.draw(render::Pass::kOpaque, ctx, stats);
  return render::read_color(target).value();
}

BruteForceField BruteForceField::create(const HeightField& field) {
  BruteForceField b;
  b.field_ = &field;
  render::register_shader_source("terrain_test/brute.vert",
                                 "#version 450 core\nlayout(location = 0) in vec3 a_rel;\nuniform mat4 u_vp;\n"
                                 "void main() { gl_Position = u_vp * vec4(a_rel, 1.0); }\n");
  render::register_shader_source("terrain_test/brute.frag",
                                 "#version 450 core\nout vec4 o_color;\nvoid main() { o_color = vec4(0.0, 1.0, 0.0, 1.0); }\n");
  b.program_ = render::Program::create({"terrain_test/brute.vert", "terrain_test/brute.frag"}).value();
  const int c = field.columns(), r = field.rows();
  std::vector<std::uint32_t> idx;
  for (int j = 0; j + 1 < r; ++j) {
    for (int i = 0; i + 1 < c; ++i) {
      const std::uint32_t a = static_cast<std::uint32_t>(j * c + i), bx = a + 1, az = a + static_cast<std::uint32_t>(c),
                          d = az + 1;
      if (((i + j) & 1) == 0) {  // main diagonal (i, j)-(i+1, j+1)
        idx.insert(idx.end(), {a, bx, d, a, d, az});
      } else {
        idx.insert(idx.end(), {a, bx, az, bx, d, az});
      }
    }
  }
  b.index_count_ = idx.size();
  b.indices_ = render::Buffer::immutable(std::span<const std::uint32_t>(idx));
  b.vertices_ = render::Buffer::dynamic(static_cast<std::size_t>(c) * r * sizeof(glm::vec3));
  b.vao_ = render::VertexArray::create();
  b.vao_.attribute(0, 0, 3, GL_FLOAT, 0);
  b.vao_.vertex_buffer(0, b.vertices_, sizeof(glm::vec3));
  b.vao_.index_buffer(b.indices_);
  return b;
}

Image BruteForceField::render(GlTarget& target, const render::Camera& camera, const glm::vec4& clear) {
  const HeightField& f = *field_;
  rel_.resize(static_cast<std::size_t>(f.columns()) * f.rows());
  for (int j = 0; j < f.rows(); ++j) {
    for (int i = 0; i < f.columns(); ++i) {
      const glm::dvec3 w(f.origin().x + i * f.spacing(), f.sample(i, j), f.origin().y + j * f.spacing());
      rel_[static_cast<std::size_t>(j) * f.columns() + i] = glm::vec3(w - camera.position());
    }
  }
  vertices_.upload(std::span<const glm::vec3>(rel_));
  vao_.vertex_buffer(0, vertices_, sizeof(glm::vec3));
  target.target.bind();
  render::apply_reversed_z_state();
  target.target.clear(clear, 0.0f);
  glDisable(GL_CULL_FACE);
  program_.use();
  program_.set("u_vp", camera.view_projection());
  vao_.bind();
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  return render::read_color(target.target).value();
}

double full_resolution_height(const HeightField& field, double x, double z) {
  const int c = field.columns(), r = field.rows();
  x = std::clamp(x, 0.0, static_cast<double>(c - 1));
  z = std::clamp(z, 0.0, static_cast<double>(r - 1));
  const int cx = std::min(static_cast<int>(std::floor(x)), std::max(c - 2, 0));
  const int cz = std::min(static_cast<int>(std::floor(z)), std::max(r - 2, 0));
  if (c < 2 || r < 2) return field.sample(0, 0);
  const double fx = x - cx, fz = z - cz;
  const double h00 = field.sample(cx, cz), h10 = field.sample(cx + 1, cz), h01 = field.sample(cx, cz + 1),
               h11 = field.sample(cx + 1, cz + 1);
  if (((cx + cz) & 1) == 0) {
    return fx >= fz ? h00 + (h10 - h00) * fx + (h11 - h10) * fz : h00 + (h11 - h01) * fx + (h01 - h00) * fz;
  }
  return fx + fz <= 1.0 ? h00 + (h10 - h00) * fx + (h01 - h00) * fz
                        : h11 + (h01 - h11) * (1.0 - fx) + (h10 - h11) * (1.0 - fz);
}

bool is_color(const Image& image, int x, int y, const glm::vec4& color) {
  for (int c = 0; c < std::min(image.channels(), 3); ++c) {
    if (std::fabs(image.at(x, y, c) - color[c]) > 1.5f / 255.0f) return false;
  }
  return true;
}

std::vector<std::uint8_t> erode(const std::vector<std::uint8_t>& mask, int width, int height, int radius) {
  std::vector<std::uint8_t> out(mask.size(), 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      bool all = true;
      for (int dy = -radius; dy <= radius && all; ++dy) {
        for (int dx = -radius; dx <= radius && all; ++dx) {
          const int xx = x + dx, yy = y + dy;
          // Outside the frame counts as outside the mask: the reference silhouette may pass just
          // beyond the border, so the frame's outer `radius` pixels are not known to be inside.
          all = xx >= 0 && yy >= 0 && xx < width && yy < height && mask[static_cast<std::size_t>(yy) * width + xx] != 0;
        }
      }
      out[static_cast<std::size_t>(y) * width + x] = all ? 1 : 0;
    }
  }
  return out;
}

void save_png(const Image& image, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::current_path() / "terrain_gl_out";
  std::filesystem::create_directories(dir);
  (void)write_image(dir / (name + ".png"), image, PixelFormat::kU8);
}

}  // namespace sylva::terrain::testing
