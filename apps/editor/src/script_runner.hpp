#pragma once
// Runs parsed editor commands (script.hpp) on an EditorSession: the --script mode, which makes
// the editor testable headless and under xvfb-run. Errors are "<script>:<line>: <command>: <what>"
// and stop the run; `quit` stops it successfully. Relative paths are taken from the script's
// folder.

#include "editor_session.hpp"
#include "script.hpp"

#include <filesystem>
#include <functional>
#include <ostream>
#include <vector>

namespace sylva::editor {

class TerrainImport;

struct ScriptHooks {
  // screenshot_ui PATH: the whole window with its panels (null in headless runs: an error).
  std::function<Status(const std::filesystem::path&)> screenshot_ui;
  // Called after every command (the window mode redraws the UI so a viewer sees the script run).
  std::function<void()> after_command;
  // The window's File > Import terrain... state (null: the run has its own), so a script's
  // import_terrain shows in the window with its progress bar.
  TerrainImport* terrain_import = nullptr;
};

struct ScriptOutcome {
  bool quit = false;       // the script ended with `quit`
  int commands_run = 0;
};

// Runs the commands in order. Before the first one, every screenshot path is checked (folder,
// file, format): a path that cannot be written fails "<source>:<line>: screenshot: <path>: ..."
// before anything is loaded or rendered.
Result<ScriptOutcome> run_script(EditorSession& session, const std::vector<ScriptCommand>& commands,
                                 const std::string& source, const std::filesystem::path& base_dir, std::ostream& out,
                                 const ScriptHooks& hooks = {});

// Reads and parses a script file: the file's errors (missing, a folder) or the parse errors.
Result<std::vector<ScriptCommand>> read_script(const std::filesystem::path& file);

// Reads, parses and runs a script file.
Result<ScriptOutcome> run_script_file(EditorSession& session, const std::filesystem::path& file, std::ostream& out,
                                      const ScriptHooks& hooks = {});

}  // namespace sylva::editor
