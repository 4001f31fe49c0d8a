#pragma once
// Tree export (issue #16): any species, generated from a preset or loaded from a species file,
// written so other engines and tools can use it (README "Export"):
//
//   <stem>.objt                 the model in the seed's OBJT format with Sylva's extensions
//                               (seed 000 §4.3.1; objt.hpp save_objt's text)
//   <stem>.gltf + <stem>.bin    glTF 2.0: a root node <name> with two child nodes/meshes,
//                               "bark" (the LOD0 tubes of tree_mesh.hpp) and "leaves" (the leaf
//                               cards), POSITION / NORMAL / TANGENT / TEXCOORD_0 and uint32
//                               indices; metres, +Y up (the model's own frame, seed §4.3.1)
//   <stem>_bark_color.png       bark albedo (sRGB), <stem>_bark_normal.png (tangent space,
//   <stem>_leaf_color.png       x = u, y = v up in the image, the glTF convention); the leaves'
//   <stem>_leaf_normal.png      base colour is the upper side's colour deviation c_v plus the
//                               seasonal colour c_s at `season` (seed eq. 3.34), alpha the outline
//   <stem>_slices/              with a BakedTree: LOD1 and LOD2 slice layers (seed 000 §2.6,
//     slices.json               Fig. 3.16) as PNG pairs lod<L>_<k>_color.png (sRGB + coverage) and
//     lod<L>_<k>_normal.png     lod<L>_<k>_normal.png (slice-space normal, alpha leaf number), and a
//                               manifest with each slice's plane and rectangle (slice_bake.hpp)
//
// Materials: "bark" opaque, base colour + normal texture, samplers REPEAT; "leaves" alphaMode
// MASK, alphaCutoff 0.5, doubleSided, base colour with alpha + normal texture, CLAMP_TO_EDGE.
// Not exported: wind animation (branch records, bending constants), the leaves' lower side and
// translucency maps, the season texture (one season is baked into the leaf colour), the slices'
// depth and branch channels.
//
// File names: `stem` is the species name with every byte but ASCII letters, digits, '-' and '_'
// turned into '_' (runs collapsed, at most 64 bytes, "tree" when nothing is left); the name
// itself is kept in the glTF and manifest JSON (invalid UTF-8 replaced).
//
// Writing: every file goes through one core FileTransaction (file_transaction.hpp): all are
// written to temporaries first, then renamed into place with the .gltf last, so a failure (an
// unwritable folder, a read-only target, a full disk) leaves every earlier file as it was and
// never a half-written .gltf. The folder (and <stem>_slices/) are created when missing. Errors
// name the folder or file (kIo).

#include <sylva/core/result.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/slice_bake.hpp>
#include <sylva/vegetation/tree_mesh.hpp>
#include <sylva/vegetation/tree_model.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <glm/glm.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::vegetation {

// What is exported: the species' name, its model (metres) and its textures.
struct ExportTree {
  std::string name;
  TreeModel model;
  TreeTextureSet textures;
};

// A species file (species_file.hpp: model, units, images, look); warnings as load_species_file.
Result<ExportTree> export_tree_from_species_file(const std::filesystem::path& file, int texture_size,
                                                 std::vector<std::string>& warnings);
// A generator preset at `seed`, named after the preset ("broadleaf"; "broadleaf_<seed>" for
// seed != 1), with the preset's procedural textures.
Result<ExportTree> export_tree_from_preset(SpeciesPreset preset, std::uint32_t seed, int texture_size);

struct TreeExportOptions {
  bool objt = true;
  bool gltf = true;
  MeshSettings mesh;      // the LOD0 mesh (tree_mesh.hpp); a BakedTree must come from the same mesh
  float season = 0.55f;   // season coordinate of the exported leaf colour (0 = 1 January)
};

// The file stem for a species name (see above).
std::string export_file_stem(std::string_view name);

struct TreeExportReport {
  std::vector<std::filesystem::path> files;  // written, in the order they were renamed into place
  std::size_t bark_vertices = 0, bark_triangles = 0;
  std::size_t leaf_vertices = 0, leaf_triangles = 0;
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // of the exported positions [m]
  int slice_layers = 0;                          // slice images written (LOD1 + LOD2)
};

// Writes what `options` asks for, plus the slices when `slices` is given, into `folder`.
// kInvalidArgument for an invalid model or mesh settings, a non-finite season, nothing to write;
// kIo naming the folder or file when it cannot be created or written.
Result<TreeExportReport> export_tree(const ExportTree& tree, const std::filesystem::path& folder,
                                     const TreeExportOptions& options, const BakedTree* slices = nullptr);

// Bakes the tree's LOD1/LOD2 slices from its LOD0 mesh (options.mesh), as a forest does
// (slice_bake.hpp bake_tree_slices). Needs a current GL 4.5 context.
Result<BakedTree> bake_export_slices(const ExportTree& tree, const TreeExportOptions& options, int resolution,
                                     float margin_share);

}  // namespace sylva::vegetation
