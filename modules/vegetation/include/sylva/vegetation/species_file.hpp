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
//     "animation": {"wind_scale": 0.5},  // optional: stiffer (< 1) or more supple (> 1) than
//                                        // the forest's animation
//     "leaf": {"color": "leaf.png",          // optional images instead of the procedural ones,
//              "normal": "leaf_n.png",       // relative to the species file (below)
//              "translucency": "leaf_t.png"},
//     "bark": {"color": "bark.png", "normal": "bark_n.png"},
//     "season": "season.png"
//   }
//
// Images (seed 000 §3.2 Fig. 3.15 a-b, §4.6 Fig. 4.8), read through core's read_image; colour
// images (leaf.color, bark.color, season) stored as 8 or 16-bit integers are sRGB and decoded to
// linear, float ones (EXR) are linear; normal and translucency maps are data. Sides 4 to 4096 px
// (the season image: one column 1 x 1..4096, or one row, taken as the column; errata 16), any
// aspect (stretched over the leaf card), resampled to the scene's texture size.
//   leaf.color         RGBA, required when "leaf" is given: the leaf's colour, alpha its outline
//                      (some texel above 0.5). The deviation from its mean colour becomes c_v
//                      (eq. 3.34); the mean is the seasonal colour c_s all year unless "season"
//                      gives one (with the look's budding and leaf fall).
//   leaf.normal        RGB(A): upper-side tangent-space normal * 0.5 + 0.5, A thickness; default flat.
//   leaf.translucency  1-4 channels: transmittance intensity rho_t; default the look's.
//   bark.color         RGB(A), required when "bark" is given; replaces "bark_color".
//   bark.normal        RGB(A): tangent-space normal (x around, y along), A height; default flat.
//   season             RGB(A) one column, top row = season 1: c_s (linear after decoding), alpha
//                      presence (< 0.5: no leaves, budding and leaf fall); RGB: leaves all year.
//
// `parameters` are TreeSpecies fields (generator.hpp) over the preset's values, with their names,
// ranges and nesting ("level1": {"count": 8}).
//
// Failure: every error starts with the species file's name and the JSON path, e.g.
// "oak.json: model.objt: no such file trees/oak.objt" (kNotFound), "oak.json:3:14: ..." for
// malformed JSON (kParse; NaN is not JSON), "oak.json: units: 1000000000 is above the maximum 1000"
// (kInvalidArgument), OBJT errors with the OBJT file and line; a file over 1 MiB (species) or
// 64 MiB (OBJT), a model taller or wider than 1 km after scaling are kLimit. Image errors name
// the key and the image: "oak.json: leaf.color: no such file leaf.png" (kNotFound),
// "oak.json: leaf.color: leaf.png has 3 channels; a leaf colour image needs an alpha channel for
// the outline (RGBA)" (kInvalidArgument), sizes (kLimit) and damage (kCorrupt) from read_image. Unknown keys and OBJT
// repairs are warnings "oak.json: ...", never silently dropped. Nothing is written.

#include <sylva/core/image.hpp>
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

// The images a species file names, as read and checked (see above); empty when not given.
struct SpeciesImages {
  Image leaf_color;         // RGBA linear
  Image leaf_normal;        // RGB(A)
  Image leaf_translucency;  // 1-4 channels
  Image bark_color;         // RGB(A) linear
  Image bark_normal;        // RGB(A)
  Image season;             // 1 x rows RGBA, linear rgb
  std::vector<std::filesystem::path> files;  // the resolved paths, in the order above
};

struct SpeciesFile {
  std::string name;
  TreeModel model;               // in metres (units applied), validated
  SpeciesPreset look = SpeciesPreset::kBroadleaf;
  std::uint32_t texture_seed = 1;
  glm::vec3 leaf_tint{1.0f};
  std::optional<glm::vec3> bark_color;
  std::filesystem::path objt_file;  // the resolved OBJT path; empty for a preset
  SpeciesTuning tuning;             // "lod" and "animation" (Forest::set_species_tuning)
  SpeciesImages images;             // "leaf", "bark", "season"
};

// Largest accepted sizes (bytes) and tree extent (metres).
inline constexpr std::uintmax_t kMaxSpeciesFileBytes = 1u << 20;
inline constexpr std::uintmax_t kMaxObjtFileBytes = 64u << 20;
inline constexpr float kMaxTreeExtent = 1000.0f;
// Sides of a species' leaf and bark images [px] (a season image: 1 to kMaxSpeciesImageSide rows).
inline constexpr int kMinSpeciesImageSide = 4;
inline constexpr int kMaxSpeciesImageSide = 4096;

// `text` is the file's JSON; relative paths resolve against `directory`; `source` names the file
// in messages. Warnings are appended to `warnings`.
Result<SpeciesFile> parse_species(std::string_view text, const std::filesystem::path& directory,
                                  std::string_view source, std::vector<std::string>& warnings);
// Reads `file` (kNotFound / kIo / kLimit naming it) and parses it; `source` is the file name.
Result<SpeciesFile> load_species_file(const std::filesystem::path& file, std::vector<std::string>& warnings);

// The species' textures (leaf and bark side: texture_size, a power of two): its images where the
// file names them (resampled), the look's procedural textures elsewhere, tinted and coloured as
// the file says.
Result<TreeTextureSet> make_species_textures(const SpeciesFile& species, int texture_size);

}  // namespace sylva::vegetation
