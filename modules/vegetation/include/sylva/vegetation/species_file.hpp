#pragma once
// Species files (issue #16): a tree species as a JSON file a scene names, so a user's own OBJT
// model (seed 000 §4.3.1) or a tuned generator preset can stand in a forest. Format (README,
// "Species files"):
//
//   {
//     "name": "seed example",                       // shown in stats and messages; default: file stem
//     "model": {"objt": "trees/seed_example.objt"}, // relative to the species file, or:
//     "model": {"preset": "conifer", "seed": 3, "parameters": {"trunk_length": 12}},
//     "units": 1,             // metres per model unit, (0, 1000]
//     "objt": {"branch_radius": 0.03, "branch_taper": 0.2,   // rules for OBJT branches without w:
//              "leaf_width": 0.05, "leaf_length": 0.08,      // radius = branch_radius * d, tip =
//              "strict": false},                             // taper * base; leaf size in metres
//     "look": "broadleaf",    // procedural textures: leaf shape, bark, season palette (default:
//                             // the preset, broadleaf for OBJT)
//     "texture_seed": 1,
//     "leaf_tint": [1, 1, 1], // multiplies the seasonal leaf colour (linear, [0, 4])
//     "bark_color": [0.32, 0.24, 0.17],  // optional: the bark plates' linear albedo
//     "lod": {"v1": 20, "v2": 60},       // optional: this species' LOD thresholds (v1, v2 [m],
//                                        // s1, s2 [px]) instead of the forest's
//     "animation": {"wind_scale": 0.5}   // optional: stiffer (< 1) or more supple (> 1) than
//   }                                    // the forest's animation
//
// `parameters` are TreeSpecies fields (generator.hpp) over the preset's values, with their names,
// ranges and nesting ("level1": {"count": 8}).
//
// Failure: every error starts with the species file's name and the JSON path, e.g.
// "oak.json: model.objt: no such file trees/oak.objt" (kNotFound), "oak.json:3:14: ..." for
// malformed JSON (kParse; NaN is not JSON), "oak.json: units: 1000000000 is above the maximum 1000"
// (kInvalidArgument), OBJT errors with the OBJT file and line; a file over 1 MiB (species) or
// 64 MiB (OBJT), a model taller or wider than 1 km after scaling are kLimit. Unknown keys and OBJT
// repairs are warnings "oak.json: ...", never silently dropped. Nothing is written.

#include <sylva/core/result.hpp>
#include <sylva/vegetation/forest.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/tree_model.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::vegetation {

struct SpeciesFile {
  std::string name;
  TreeModel model;               // in metres (units applied), validated
  SpeciesPreset look = SpeciesPreset::kBroadleaf;
  std::uint32_t texture_seed = 1;
  glm::vec3 leaf_tint{1.0f};
  std::optional<glm::vec3> bark_color;
  std::filesystem::path objt_file;  // the resolved OBJT path; empty for a preset
  SpeciesTuning tuning;             // "lod" and "animation" (Forest::set_species_tuning)
};

// Largest accepted sizes (bytes) and tree extent (metres).
inline constexpr std::uintmax_t kMaxSpeciesFileBytes = 1u << 20;
inline constexpr std::uintmax_t kMaxObjtFileBytes = 64u << 20;
inline constexpr float kMaxTreeExtent = 1000.0f;

// `text` is the file's JSON; relative paths resolve against `directory`; `source` names the file
// in messages. Warnings are appended to `warnings`.
Result<SpeciesFile> parse_species(std::string_view text, const std::filesystem::path& directory,
                                  std::string_view source, std::vector<std::string>& warnings);
// Reads `file` (kNotFound / kIo / kLimit naming it) and parses it; `source` is the file name.
Result<SpeciesFile> load_species_file(const std::filesystem::path& file, std::vector<std::string>& warnings);

// The species' procedural textures (leaf and bark side: texture_size, a power of two), tinted and
// coloured as the file says.
Result<TreeTextureSet> make_species_textures(const SpeciesFile& species, int texture_size);

}  // namespace sylva::vegetation
