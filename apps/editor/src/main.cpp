// sylva-editor: tune scenes, paint height and density maps, save them.
//   sylva-editor [scene.json] [--script FILE] [--headless] [--size WxH] [--help]
// With --script the commands run first (script.hpp); a script ending in `quit` exits with 0, a
// failing command exits with 1 and its "<file>:<line>:" message, a malformed script or bad
// arguments with 2. Headless (--headless, or no display) needs --script: there is nobody to
// click. In a window, the script runs visibly and the editor stays open unless it quits.
#include "editor_session.hpp"
#include "editor_ui.hpp"
#include "script_runner.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/render/readback.hpp>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

struct Options {
  std::optional<std::string> scene;
  std::optional<std::string> script;
  bool headless = false;
  glm::ivec2 size{1600, 900};
  bool help = false;
};

const char* kUsage =
    "usage: sylva-editor [scene.json] [options]\n"
    "  --script FILE   run editor commands from FILE (see apps/editor/src/script.hpp)\n"
    "  --headless      no window (needs --script); also chosen when there is no display\n"
    "  --size WxH      window size, or the viewport size when headless (default 1600x900)\n"
    "  --help          show this text\n"
    "Viewport: right drag looks (fly) or orbits, WASD/QE fly, middle drag pans (orbit), wheel zooms,\n"
    "left drag paints when Paint is on. Ctrl+Z / Ctrl+Y undo and redo, Ctrl+S saves.\n";

sylva::Result<Options> parse(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> sylva::Result<std::string> {
      if (i + 1 >= args.size()) return sylva::make_error(sylva::ErrorCode::kInvalidArgument, a + " needs a value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--headless") {
      o.headless = true;
    } else if (a == "--script") {
      auto v = value();
      if (!v.ok()) return v.error();
      o.script = *v;
    } else if (a == "--size") {
      auto v = value();
      if (!v.ok()) return v.error();
      auto s = sylva::editor::parse_size(*v);
      if (!s.ok()) return sylva::make_error(sylva::ErrorCode::kInvalidArgument, "--size: " + s.error().message);
      o.size = *s;
    } else if (a.rfind("-", 0) == 0) {
      return sylva::make_error(sylva::ErrorCode::kInvalidArgument, "unknown option \"" + a + "\" (see --help)");
    } else if (o.scene) {
      return sylva::make_error(sylva::ErrorCode::kInvalidArgument, "only one scene file may be given");
    } else {
      o.scene = a;
    }
  }
  return o;
}

int run_headless(const Options& o) {
  auto context = sylva::render::GlContext::create_headless();
  if (!context.ok()) {
    std::cerr << "sylva-editor: " << context.error().message << "\n";
    return 1;
  }
  auto session = sylva::editor::EditorSession::create(o.size);
  if (!session.ok()) {
    std::cerr << "sylva-editor: " << session.error().message << "\n";
    return 1;
  }
  if (o.scene) {
    sylva::Status loaded = (*session)->load(*o.scene);
    if (!loaded.ok()) {
      std::cerr << "sylva-editor: " << loaded.error().message << "\n";
      return 2;
    }
  }
  auto outcome = sylva::editor::run_script_file(**session, *o.script, std::cout);
  if (!outcome.ok()) {
    std::cerr << "sylva-editor: " << outcome.error().message << "\n";
    return outcome.error().code == sylva::ErrorCode::kParse ? 2 : 1;
  }
  return 0;
}

int run_window(const Options& o) {
  auto context = sylva::render::GlContext::create_window({.width = o.size.x, .height = o.size.y, .title = "Sylva editor"});
  if (!context.ok()) {
    std::cerr << "sylva-editor: " << context.error().message << "\n";
    return 1;
  }
  GLFWwindow* window = context->window();
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed; do not litter the working folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");

  int status = 0;
  {
    auto session = sylva::editor::EditorSession::create({o.size.x - 630, o.size.y - 20});
    if (!session.ok()) {
      std::cerr << "sylva-editor: " << session.error().message << "\n";
      status = 1;
    } else {
      sylva::editor::EditorSession& s = **session;
      // Like the player, the editor opens the embedded default scene when given none.
      sylva::Status loaded = o.scene ? s.load(*o.scene) : s.open_default();
      if (!loaded.ok()) std::cerr << "sylva-editor: " << loaded.error().message << "\n";
      sylva::editor::EditorUi ui(s, window);
      sylva::Stopwatch clock;
      auto draw_frame = [&](double dt) {
        context->poll_events();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ui.frame(dt);
        ImGui::Render();
        const glm::ivec2 fb = context->framebuffer_size();
        sylva::render::Framebuffer::bind_default(fb.x, fb.y);
        glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      };
      bool quit = false;
      if (o.script) {
        sylva::editor::ScriptHooks hooks;
        hooks.screenshot_ui = [&](const std::filesystem::path& file) -> sylva::Status {
          // Two frames so the panels have their final layout, then read the back buffer.
          for (int k = 0; k < 2; ++k) {
            draw_frame(1.0 / 30.0);
            if (k == 0) context->swap_buffers();
          }
          const glm::ivec2 fb = context->framebuffer_size();
          glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
          glReadBuffer(GL_BACK);
          auto image = sylva::render::read_bound_framebuffer(0, 0, fb.x, fb.y);
          context->swap_buffers();
          if (!image.ok()) return image.error();
          image->set_format(sylva::PixelFormat::kU8);
          return sylva::write_image(file, *image);
        };
        hooks.terrain_import = &ui.terrain_import();
        hooks.after_command = [&] {
          draw_frame(1.0 / 30.0);
          context->swap_buffers();
        };
        auto outcome = sylva::editor::run_script_file(s, *o.script, std::cout, hooks);
        if (!outcome.ok()) {
          std::cerr << "sylva-editor: " << outcome.error().message << "\n";
          status = outcome.error().code == sylva::ErrorCode::kParse ? 2 : 1;
          quit = true;
        } else {
          quit = outcome->quit;
        }
      }
      while (!quit) {
        if (context->should_close()) {
          glfwSetWindowShouldClose(window, GLFW_FALSE);
          ui.request_quit();
        }
        draw_frame(clock.lap_ms() * 1e-3);
        context->swap_buffers();
        quit = ui.quit_requested();
      }
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  auto options = parse(std::vector<std::string>(argv + 1, argv + argc));
  if (!options.ok()) {
    std::cerr << "sylva-editor: " << options.error().message << "\n";
    return 2;
  }
  if (options->help) {
    std::cout << kUsage;
    return 0;
  }
  // A script that is missing or malformed is a bad argument (exit 2), found before any window
  // or GL context is made.
  if (options->script) {
    auto script = sylva::editor::read_script(*options->script);
    if (!script.ok()) {
      std::cerr << "sylva-editor: " << script.error().message << "\n";
      return 2;
    }
  }
  const bool headless = options->headless || !sylva::render::display_available();
  if (headless) {
    if (!options->script) {
      std::cerr << "sylva-editor: no display (or --headless) and no --script: nothing to do\n";
      return 2;
    }
    return run_headless(*options);
  }
  return run_window(*options);
}
