#pragma once
// The editor's command language for `sylva-editor --script FILE` (GL-free parser, unit-tested in
// tests/script_test.cpp). One command per line; '#' starts a comment; words are separated by
// spaces; a word may be double-quoted to hold spaces ("my scene.json"). Commands:
//
//   load PATH                    open a scene file (relative paths: from the script's folder)
//   new                          an empty scene (sky only)
//   load_default                 the embedded default scene (no file: save needs a PATH)
//   add_module NAME              add a module section with default settings (undoable)
//   remove_module NAME           remove a module section (undoable)
//   set PATH VALUE | set PATH=VALUE   set a parameter (undoable), e.g. set grass.field.density 120
//   brush KEY=VALUE...           brush settings: op, radius, strength, falloff, target, use_target,
//                                spacing, noise_scale, seed, color=R,G,B (editor/brush.hpp)
//   stroke MAP X,Z [X,Z ...]     paint one stroke through world points on a map ("ground.height"),
//                                or on a colour map ("grass.tint": its _r, _g, _b maps towards
//                                brush color), one undo entry
//   undo [N] / redo [N]          N steps (default 1)
//   camera X Y Z [YAW PITCH [FOV]]   place the camera (degrees)
//   camera bookmark NAME         go to a bookmark of the scene
//   bookmark NAME                save the camera as a bookmark (undoable)
//   frames N                     render N frames (the scene simulates 1/30 s each)
//   debug VIEW on|off            wireframe, lod_colors, chunk_bounds, freeze_culling
//   screenshot PATH [WxH]        render the viewport and save it (PNG, EXR, ...)
//   screenshot_ui PATH           save the whole window with its panels (window mode only)
//   export_tree FOLDER           export the forest's first species (OBJT, glTF, slices; File >
//                                Export tree...; EditorSession::export_tree)
//   import_terrain PATH [bake OUT [hold]]   File > Import terrain... (terrain_import.hpp): read an
//                                elevation raster or a mesh and use it directly (one undo entry), or
//                                start baking the raster into the chunk file OUT on a worker thread
//                                (hold: the bake waits at its first progress report, for tests)
//   wait_import [MAX_FRAMES]     render frames until the bake is done (default 100000), then set
//                                terrain.baked_file; writes "import: ..." lines (progress, result)
//   cancel_import                cancel the running bake (no file is left at OUT, the scene unchanged)
//   save [PATH]                  save the scene and its edited maps (atomic), PATH = save as
//   expect PATH VALUE            fail unless the parameter's text equals VALUE (self-checking scripts)
//   expect_unsaved yes|no        fail unless the unsaved-changes state is as given
//   print TEXT...                write a line to the output
//   preview [KEY=VALUE...]       open the plant preview with these settings (species=NAME|FILE.lsys,
//                                system, seed, derivations, angle_variation; plant_preview.hpp) and
//                                write "preview <title>: N blocks (BLOCK n, ...), S symbols, D derivations"
//                                or "preview <title>: error: <file:line:column: message>"
//   print_stats MODULE           write "MODULE <its scene stats as JSON>" (plant_blocks, trees_per_species...)
//   copy_file FROM TO            copy a file over another (tests: rewrite a grammar or species file
//                                while the scene runs)
//   wait_reload FILE [MAX_FRAMES]  render frames until the editor's file watcher has reloaded FILE
//                                (again, since the last wait_reload of it); fails after MAX_FRAMES
//                                (default 600). Reload messages are written to the output as they come
//   wait_stream [MAX_FRAMES]     render frames until the streamed (baked) terrain has every chunk its
//                                view asks for (stats stream_pending and stream_misses_frame 0), so a
//                                screenshot is the settled picture, or until the budget holds what it can
//                                (stream_budget_limited 1; says so); fails after MAX_FRAMES (default 2000),
//                                or as soon as a chunk the view asked for cannot be read (corrupt
//                                file: the error names it; its parent stays drawn)
//   quit                         stop (unsaved changes are discarded: scripts are explicit)
//
// Parsing checks every line before anything runs: unknown commands, wrong argument counts and
// malformed numbers are errors "<file>:<line>: <message>". Running reports errors the same way.

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::editor {

struct ScriptCommand {
  int line = 0;                    // 1-based line in the script
  std::string name;                // "stroke"
  std::vector<std::string> args;   // the words after the name, unquoted
  std::vector<glm::dvec2> points;  // stroke: parsed X,Z points
  int count = 1;                   // undo/redo/frames/wait_reload: N
};

// Parses a whole script. `source` names it in messages.
Result<std::vector<ScriptCommand>> parse_script(std::string_view text, std::string_view source);

// "<source>:<line>: <message>".
std::string script_location(std::string_view source, int line);

// Splits a line into words (double quotes group, backslash escapes a quote inside them).
// Errors: an unterminated quote.
Result<std::vector<std::string>> split_words(std::string_view line);

// "12.5,-3" -> (12.5, -3). Errors name the text.
Result<glm::dvec2> parse_point(std::string_view text);
// "256x144" -> (256, 144): core/render_size.hpp bounds (sides 16..16384, at most 8192x8192 pixels).
Result<glm::ivec2> parse_size(std::string_view text);

}  // namespace sylva::editor
