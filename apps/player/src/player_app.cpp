#include "player_app.hpp"

#include "frame_recorder.hpp"
#include "output_checks.hpp"
#include "scene_loading.hpp"

#include <sylva/core/params_json.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/gl_debug.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/scene/frame_stats.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <filesystem>
#include <optional>

namespace sylva::player {
namespace {

// Headless runs advance the clock by a fixed step so results do not depend on the machine.
constexpr double kHeadlessStep = 1.0 / 30.0;

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

void list_modules(std::ostream& out) {
  out << "core        no-GL foundation (params, images, noise, wind, height fields)\n";
  out << "render      OpenGL 4.5 core (contexts, shaders, camera, queries, sky)\n";
  out << "scene       scene files, module assembly, frame loop\n";
  for (const scene::ModuleDescriptor* d : scene::compiled_modules()) {
    out << fmt::format("{:<11} {}\n", d->name, d->description);
  }
}

}  // namespace

int run_player(const PlayerOptions& options, std::ostream& out, std::ostream& err) {
  if (options.list_modules) {
    list_modules(out);
    return 0;
  }

  // Outputs first: a path that cannot be written fails now, not after the frames are rendered.
  if (Status writable = check_outputs(options); !writable.ok()) {
    err << "sylva-player: " << writable.error().message << "\n";
    return 1;
  }
  auto loaded = load_scene(options.scene_path, options.overrides);
  if (!loaded.ok()) {
    err << "sylva-player: " << loaded.error().message << "\n";
    return 2;
  }
  if (Status apart = check_outputs_are_not_inputs(options, loaded->document); !apart.ok()) {
    err << "sylva-player: " << apart.error().message << "\n";
    return 1;
  }
  for (const std::string& w : loaded->warnings) err << "sylva-player: warning: " << w << "\n";
  if (options.bookmark && loaded->document.bookmarks.count(*options.bookmark) == 0) {
    err << "sylva-player: --bookmark " << *options.bookmark << ": the scene has no such bookmark\n";
    return 2;
  }
  if (options.camera_path && loaded->document.camera_paths.count(*options.camera_path) == 0) {
    err << "sylva-player: --camera-path " << *options.camera_path << ": the scene has no such camera path\n";
    return 2;
  }

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

  const std::string scene_name = loaded->document.name;
  const std::size_t load_mark = render::gl_error_mark();
  auto created = scene::Scene::create(std::move(loaded->document));
  if (!created.ok()) {
    err << "sylva-player: " << created.error().message << "\n";
    return created.error().code == ErrorCode::kGl ? 1 : 2;
  }
  if (Status gl = render::check_frame_gl_errors(load_mark, "loading the scene"); !gl.ok()) {
    err << "sylva-player: " << gl.error().message << "\n";
    return 1;
  }
  scene::Scene& scene = **created;

  glm::ivec2 size = options.size;
  auto target = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA8}});
  if (!target.ok()) {
    err << "sylva-player: " << target.error().message << "\n";
    return 1;
  }

  const scene::CameraView start =
      options.bookmark ? scene.document().bookmarks.at(*options.bookmark) : scene.document().camera;
  render::Camera camera = scene.make_camera(start, size);
  render::FrameProfiler profiler;
  FrameRecorder recorder;
  recorder.set_scene_name(scene_name);
  recorder.set_settings({{"render", params_to_json(scene.document().render)},
                         {"sun", params_to_json(scene.document().sun)},
                         {"environment", params_to_json(scene.document().environment)}});
  const render::FlySettings fly;
  std::optional<glm::dvec2> last_cursor;

  const int frame_limit = options.frames.value_or(headless ? kDefaultHeadlessFrames : 0);
  int frames = 0;
  Stopwatch frame_clock;
  double time = 0.0;
  while (frame_limit == 0 || frames < frame_limit) {
    const std::size_t frame_mark = render::gl_error_mark();
    Stopwatch wall;  // the whole frame, to the swap (window) or glFinish (headless)
    const double dt = headless ? kHeadlessStep : frame_clock.lap_ms() * 1e-3;
    if (!headless) {
      context->poll_events();
      if (context->should_close() || glfwGetKey(context->window(), GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
      if (!options.camera_path) render::fly_step(camera, read_fly_input(context->window(), last_cursor), fly, dt);
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
    if (frames > 0) time += dt;
    if (options.camera_path) {
      auto view = scene.camera_path_view(*options.camera_path, time);
      if (view.ok()) camera = scene.make_camera(*view, size);
    }
    Stopwatch cpu;  // update and draw submission only
    scene.update(camera, time, static_cast<float>(frames > 0 ? dt : 0.0), size);
    scene.render(*target, profiler);
    const double cpu_ms = cpu.elapsed_ms();
    if (!headless) {
      glBlitNamedFramebuffer(target->read_id(), 0, 0, 0, size.x, size.y, 0, 0, size.x, size.y, GL_COLOR_BUFFER_BIT,
                             GL_NEAREST);
      context->swap_buffers();
    } else {
      // Headless frames have no swap to wait on: finish them, or the wall time would only be the
      // submission and a software rasteriser's work would fall outside every figure.
      glFinish();
    }
    // A GL error (out of memory included) means the picture is wrong: fail, write nothing.
    if (Status gl = render::check_frame_gl_errors(frame_mark, fmt::format("frame {}", frames)); !gl.ok()) {
      err << "sylva-player: " << gl.error().message << "\n";
      return 1;
    }
    recorder.add_frame_ms(cpu_ms, wall.elapsed_ms());
    recorder.add_update_ms(scene.update_ms());
    if (const auto& latest = profiler.latest()) recorder.add_gpu_frame(*latest);
    ++frames;
  }
  if (auto last = profiler.flush()) recorder.add_gpu_frame(*last);
  const nlohmann::json facts = scene.module_stats();
  for (const auto& [module, info] : facts.items()) recorder.set_module_info(module, info);
  recorder.set_memory(scene::memory_report());

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
