#include "player_app.hpp"

#include "frame_recorder.hpp"
#include "ground_scene.hpp"
#include "scene_loading.hpp"

#include <sylva/core/timer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <filesystem>
#include <optional>

namespace sylva::player {
namespace {

// The modules compiled into this player (the lean preset leaves some out).
std::vector<std::string> built_modules() {
  return {"core", "render"};
}

// Reads WASD / mouse from the window into a fly-camera step (right mouse button looks).
render::FlyInput read_fly_input(GLFWwindow* window, std::optional<glm::dvec2>& last_cursor) {
  render::FlyInput input;
  auto down = [window](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
  input.forward = down(GLFW_KEY_W);
  input.back = down(GLFW_KEY_S);
  input.left = down(GLFW_KEY_A);
  input.right = down(GLFW_KEY_D);
  input.up = down(GLFW_KEY_E);
  input.down = down(GLFW_KEY_Q);
  input.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
  glm::dvec2 cursor;
  glfwGetCursorPos(window, &cursor.x, &cursor.y);
  input.look = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  if (last_cursor && input.look) input.mouse_delta = glm::vec2(cursor - *last_cursor);
  last_cursor = cursor;
  return input;
}

struct Renderers {
  GroundRenderer ground;
  render::SkyRenderer sky;
  render::LightingUniforms lighting;
};

Result<Renderers> create_renderers(const GroundSceneSettings& settings) {
  render::embedded::register_render_shaders();
  auto ground = GroundRenderer::create(settings.ground);
  if (!ground.ok()) return ground.error();
  auto sky = render::SkyRenderer::create();
  if (!sky.ok()) return sky.error();
  return Renderers{std::move(*ground), std::move(*sky), render::LightingUniforms::create()};
}

void render_frame(Renderers& r, const render::Framebuffer& target, const render::Camera& camera,
                  const render::Lighting& lighting, double time, render::FrameProfiler& profiler) {
  profiler.begin_frame();
  r.lighting.update(lighting, camera.position().y, time);
  r.lighting.bind();
  target.bind();
  render::apply_reversed_z_state();
  target.clear(glm::vec4(lighting.fog_color, 1.0f), 0.0f);
  profiler.begin("opaque");
  render::PassStats ground_counts;
  r.ground.draw(camera, ground_counts);
  profiler.end("opaque");
  profiler.add_cpu_counts("opaque", ground_counts);
  profiler.begin("sky");
  r.sky.draw(camera, lighting);
  profiler.end("sky");
  profiler.add_cpu_counts("sky", render::PassStats{.draw_calls = 1});
  profiler.end_frame();
}

}  // namespace

int run_player(const PlayerOptions& options, std::ostream& out, std::ostream& err) {
  if (options.list_modules) {
    for (const std::string& m : built_modules()) out << m << "\n";
    return 0;
  }

  auto scene = load_scene(options.scene_path, options.overrides);
  if (!scene.ok()) {
    err << "sylva-player: " << scene.error().message << "\n";
    return 2;
  }
  for (const std::string& w : scene->warnings) err << "sylva-player: warning: " << w << "\n";

  // Window when asked and possible; otherwise headless, and say why.
  bool headless = options.headless;
  if (!headless && !render::display_available()) {
    out << "sylva-player: no display found, rendering headless\n";
    headless = true;
  }
  auto context = headless ? render::GlContext::create_headless()
                          : render::GlContext::create_window({.width = options.size.x, .height = options.size.y,
                                                              .title = "Sylva player"});
  if (!context.ok()) {
    err << "sylva-player: " << context.error().message << "\n";
    return 1;
  }

  auto renderers = create_renderers(scene->settings);
  if (!renderers.ok()) {
    err << "sylva-player: " << renderers.error().message << "\n";
    return 1;
  }

  glm::ivec2 size = options.size;
  auto target = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA8}});
  if (!target.ok()) {
    err << "sylva-player: " << target.error().message << "\n";
    return 1;
  }

  render::Camera camera = make_camera(scene->settings.camera, size);
  const render::Lighting lighting = make_lighting(scene->settings.sun);
  render::FrameProfiler profiler;
  FrameRecorder recorder;
  recorder.set_module_info("ground", {{"triangles", renderers->ground.triangle_count()},
                                      {"resolution", scene->settings.ground.resolution}});
  const render::FlySettings fly;
  std::optional<glm::dvec2> last_cursor;

  const int frame_limit = options.frames.value_or(headless ? kDefaultHeadlessFrames : 0);
  int frames = 0;
  Stopwatch frame_clock;
  double time = 0.0;
  while (frame_limit == 0 || frames < frame_limit) {
    Stopwatch cpu;
    const double dt = frame_clock.lap_ms() * 1e-3;
    if (!headless) {
      context->poll_events();
      if (context->should_close() || glfwGetKey(context->window(), GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
      render::fly_step(camera, read_fly_input(context->window(), last_cursor), fly, dt);
      const glm::ivec2 fb = context->framebuffer_size();
      if (fb.x > 0 && fb.y > 0 && fb != size) {
        auto resized = render::Framebuffer::create({.width = fb.x, .height = fb.y, .color_formats = {GL_RGBA8}});
        if (resized.ok()) {
          size = fb;
          target = std::move(resized);
          camera.set_aspect(size.x, size.y);
        }
      }
    }
    time += dt;
    render_frame(*renderers, *target, camera, lighting, time, profiler);
    if (!headless) {
      glBlitNamedFramebuffer(target->read_id(), 0, 0, 0, size.x, size.y, 0, 0, size.x, size.y, GL_COLOR_BUFFER_BIT,
                             GL_NEAREST);
      context->swap_buffers();
    }
    recorder.add_cpu_ms(cpu.elapsed_ms());
    if (const auto& latest = profiler.latest()) recorder.add_gpu_frame(*latest);
    ++frames;
  }
  if (auto last = profiler.flush()) recorder.add_gpu_frame(*last);

  int status = 0;
  if (options.screenshot_path) {
    Status saved = render::save_screenshot(*target, *options.screenshot_path);
    if (!saved.ok()) {
      err << "sylva-player: " << saved.error().message << "\n";
      status = 1;
    } else {
      out << "sylva-player: wrote " << std::filesystem::absolute(*options.screenshot_path).string() << "\n";
    }
  }
  if (options.stats_path) {
    Status saved = recorder.write(*options.stats_path, frames, size);
    if (!saved.ok()) {
      err << "sylva-player: " << saved.error().message << "\n";
      status = 1;
    } else {
      out << "sylva-player: wrote " << std::filesystem::absolute(*options.stats_path).string() << "\n";
    }
  }
  return status;
}

}  // namespace sylva::player
