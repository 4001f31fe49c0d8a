#include "ground_target.hpp"

#include "frame_finish.hpp"

#include <sylva/core/timer.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/vertex_array.hpp>

#include <fmt/format.h>

#include <cstddef>
#include <vector>

namespace sylva::render::embedded {
void register_bench_shaders();  // generated from apps/bench/shaders
}  // namespace sylva::render::embedded

namespace sylva::bench {

float builtin_ground_height(const BenchGroundSettings& s, double x, double z) {
  const glm::dvec2 p(x, z);
  const float hills = fbm2(p, s.noise);
  const float ridges = ridged2(p * 0.7, s.noise);
  return s.height * (0.5f * hills + 0.8f * ridges * ridges);
}

std::vector<CameraPath> ground_camera_paths() {
  std::vector<CameraPath> paths;
  paths.push_back({"flyover", "diagonal flight at about 420 m, looking ahead and down",
                   {{{-1500.0, 430.0, 1500.0}, -45.0f, -16.0f, 60.0f},
                    {{-600.0, 400.0, 650.0}, -52.0f, -14.0f, 60.0f},
                    {{250.0, 420.0, -150.0}, -38.0f, -17.0f, 60.0f},
                    {{1100.0, 440.0, -1000.0}, -45.0f, -15.0f, 60.0f}}});
  paths.push_back({"low_pass", "low over the ridges with the horizon in view: silhouettes and grazing angles",
                   {{{-1800.0, 330.0, 200.0}, -90.0f, -3.0f, 55.0f},
                    {{-700.0, 320.0, 120.0}, -95.0f, -4.0f, 55.0f},
                    {{400.0, 335.0, -60.0}, -85.0f, -3.0f, 55.0f}}});
  CameraPath orbit{"orbit", "full circle at 1800 m radius, 650 m up, looking at the centre", {}};
  for (int k = 0; k <= 8; ++k) {
    const double a = glm::radians(45.0 * k);
    orbit.keys.push_back({{1800.0 * std::sin(a), 650.0, 1800.0 * std::cos(a)}, static_cast<float>(45.0 * k), -19.0f,
                          60.0f});
  }
  paths.push_back(std::move(orbit));
  return paths;
}

namespace {

struct GroundVertex {
  glm::vec3 position;
  glm::vec3 normal;
};

class GroundTarget final : public BenchTarget {
 public:
  std::vector<ParamDescriptor> params() override { return describe_params(settings_); }

  Status prepare(glm::ivec2 size) override {
    SYLVA_TRY(validate_params(settings_));
    render::embedded::register_render_shaders();
    render::embedded::register_bench_shaders();
    auto program = render::Program::create({"bench/ground.vert", "bench/ground.frag"});
    if (!program.ok()) return program.error();
    program_ = std::move(*program);
    auto sky = render::SkyRenderer::create();
    if (!sky.ok()) return sky.error();
    sky_ = std::move(*sky);
    lighting_uniforms_ = render::LightingUniforms::create();
    size_ = size;

    const BenchGroundSettings& g = settings_.ground;
    const int n = g.resolution;
    const double spacing = static_cast<double>(g.size) / (n - 1);
    const double half = 0.5 * static_cast<double>(g.size);
    const double eps = 0.5;  // metres: normals from the full-detail surface, not from the grid
    std::vector<GroundVertex> vertices;
    vertices.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    float lo = 1e30f, hi = -1e30f;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const double x = -half + i * spacing, z = -half + j * spacing;
        const float y = builtin_ground_height(g, x, z);
        const float dx = builtin_ground_height(g, x + eps, z) - builtin_ground_height(g, x - eps, z);
        const float dz = builtin_ground_height(g, x, z + eps) - builtin_ground_height(g, x, z - eps);
        const glm::vec3 normal = glm::normalize(glm::vec3(-dx, static_cast<float>(2.0 * eps), -dz));
        vertices.push_back({glm::vec3(static_cast<float>(x), y, static_cast<float>(z)), normal});
        lo = std::min(lo, y);
        hi = std::max(hi, y);
      }
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(static_cast<std::size_t>(n - 1) * static_cast<std::size_t>(n - 1) * 6);
    for (int j = 0; j + 1 < n; ++j) {
      for (int i = 0; i + 1 < n; ++i) {
        const auto v = static_cast<std::uint32_t>(j * n + i);
        const auto w = static_cast<std::uint32_t>(n);
        indices.insert(indices.end(), {v, v + w, v + 1, v + 1, v + w, v + w + 1});  // CCW from above
      }
    }
    vertices_ = render::Buffer::immutable(std::span<const GroundVertex>(vertices));
    indices_ = render::Buffer::immutable(std::span<const std::uint32_t>(indices));
    vao_ = render::VertexArray::create();
    vao_.attribute(0, 0, 3, GL_FLOAT, offsetof(GroundVertex, position));
    vao_.attribute(1, 0, 3, GL_FLOAT, offsetof(GroundVertex, normal));
    vao_.vertex_buffer(0, vertices_, sizeof(GroundVertex));
    vao_.index_buffer(indices_);
    index_count_ = indices.size();
    snow_line_ = lo + 0.82f * (hi - lo);
    return {};
  }

  std::vector<CameraPathInfo> camera_paths() const override {
    std::vector<CameraPathInfo> out;
    for (const CameraPath& p : ground_camera_paths()) out.push_back({p.name, p.description});
    return out;
  }

  Result<CameraPose> camera_pose(const std::string& name, int frame, int frames) override {
    for (const CameraPath& p : ground_camera_paths()) {
      if (p.name == name) return p.frame(frame, frames);
    }
    return make_error(ErrorCode::kNotFound, fmt::format("builtin:ground has no camera path \"{}\"", name));
  }

  Status render(const FrameInput& input, const render::Framebuffer& target, FrameOutput& out) override {
    Stopwatch cpu;
    render::Camera camera;
    camera.set_position(input.pose.position);
    camera.set_yaw_pitch(glm::radians(input.pose.yaw_deg), glm::radians(input.pose.pitch_deg));
    camera.perspective().fov_y = glm::radians(input.pose.fov_deg);
    camera.perspective().near_plane = 0.5f;
    camera.set_aspect(size_.x, size_.y);
    const render::Lighting& lighting = settings_.lighting;

    profiler_.begin_frame();
    lighting_uniforms_.update(lighting, camera.position().y, input.time);
    lighting_uniforms_.bind();
    target.bind();
    render::apply_reversed_z_state();
    target.clear(glm::vec4(lighting.fog_color, 1.0f), 0.0f);

    render::PassStats ground;
    profiler_.begin("opaque");
    program_.use();
    program_.set("u_view_projection", camera.view_projection());
    program_.set("u_model", camera.relative_model(glm::dvec3(0.0)));
    program_.set("u_snow_line", snow_line_);
    vao_.bind();
    glEnable(GL_CULL_FACE);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
    glDisable(GL_CULL_FACE);
    profiler_.end("opaque");
    ground.draw_calls = 1;
    ground.instances = 1;
    ground.triangles = index_count_ / 3;
    profiler_.add_cpu_counts("opaque", ground);

    return finish_sky_frame(profiler_, sky_, camera, lighting, input.time, cpu, "builtin:ground", out);
  }

  std::vector<std::string> modules() const override { return {"render"}; }

 private:
  GroundTargetSettings settings_;
  render::Program program_;
  render::SkyRenderer sky_;
  render::LightingUniforms lighting_uniforms_;
  render::Buffer vertices_;
  render::Buffer indices_;
  render::VertexArray vao_;
  render::FrameProfiler profiler_;
  std::size_t index_count_ = 0;
  float snow_line_ = 0.0f;
  glm::ivec2 size_{256, 144};
};

}  // namespace

std::unique_ptr<BenchTarget> make_ground_target() { return std::make_unique<GroundTarget>(); }

}  // namespace sylva::bench
