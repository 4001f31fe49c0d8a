#pragma once
// One hostile case: files written into a fresh folder, one shipped executable run in it, and
// what must come out (exit code, words of the message). The tables live in cases_*.cpp; adding
// an input kind is adding a row there.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sylva::hostile {

enum class Tool { kPlayer, kEditor, kBench };

struct InputFile {
  std::string name{};                    // relative to the case folder; ending in '/': a folder
  std::function<std::string()> bytes{};  // generated when the case runs
  // > 0: the file is then extended to this many bytes with a hole (sparse: no disk, no memory),
  // for "huge" inputs; it is checked unchanged by size and modification time, not read back.
  std::uintmax_t sparse_size = 0;
};

struct HostileCase {
  std::string name{};  // gtest name: letters, digits and '_'
  Tool tool = Tool::kPlayer;
  std::vector<InputFile> files{};
  // Command-line arguments, run in the case folder through the shell. "{scenes}" is replaced by
  // the shipped scenes folder. Fields have initializers so rows may leave them out. The player and editor get --headless; nothing else is added.
  std::string args{};
  int exit_code = 2;
  std::vector<std::string> words{};   // each must appear in the output (the user's path, the reason)
  std::vector<std::string> absent{};  // none may appear (e.g. an error that only comes from rendering)
  std::string needs_module{};         // skipped when the player is built without it
  // For exit code 0: a screenshot the run writes, which must hold a picture (not one flat colour).
  std::string picture{};
};

// The tables, one per kind of input (cases_*.cpp).
std::vector<HostileCase> scene_file_cases();
std::vector<HostileCase> map_image_cases();
std::vector<HostileCase> elevation_raster_cases();
std::vector<HostileCase> player_command_line_cases();
std::vector<HostileCase> output_path_cases();
std::vector<HostileCase> editor_script_cases();
std::vector<HostileCase> bench_cases();
std::vector<HostileCase> species_file_cases();
std::vector<HostileCase> plant_file_cases();

// A scene JSON of the built-in ground (small, fast) whose "maps" use `height_map` when given.
std::string ground_scene(const std::string& height_map = "");
// A scene with a ground and one `module` section whose density map is `density_map`.
std::string density_scene(const std::string& module, const std::string& density_map);

}  // namespace sylva::hostile
