#pragma once
// The command line of sylva-bake (offline baking, DESIGN.md §1 apps/bake):
//   sylva-bake terrain SOURCE --out FILE.sylvaterrain [--tiles I/N] [--overview-side S] [--set terrain.KEY=VALUE]... [--quiet]
//   sylva-bake merge SHARE... --out FILE.sylvaterrain [--quiet]
//   sylva-bake tree SPECIES.json|--preset NAME [--seed N] --out DIR [--format gltf|objt|both] [--slices] [--quiet]
// SOURCE is any elevation raster core/elevation_raster.hpp reads (GDAL: GeoTIFF, SRTM .hgt,
// ASCII grids; OpenImageIO: PNG/EXR/TIFF height maps). KEY is terrain.tree.* (ChunkTreeSettings)
// or terrain.elevation.* (ElevationReadOptions). With --tiles I/N (0 <= I < N) the bake writes
// share I of N to --out; `merge` joins the N shares into a file byte-identical to a one-process
// bake. `tree` exports a species (a species file, or a generator preset at a seed) as OBJT and/or
// glTF 2.0 with its textures, and with --slices its baked LOD1/LOD2 impostor layers
// (modules/vegetation/include/sylva/vegetation/tree_export.hpp; README "Export").

#include <sylva/core/elevation_raster.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/settings.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::bake {

// The `terrain` section --set addresses.
struct TerrainBakeSettings {
  ElevationReadOptions elevation;
  terrain::ChunkTreeSettings tree;
  template <class V>
  void visit(V& v) {
    v(elevation, "elevation");
    v(tree, "tree");
  }
};

// `tree`: what to export and how.
struct TreeCommand {
  std::filesystem::path species;  // a species file, or
  std::string preset;             // a generator preset name (broadleaf, conifer, birch, shrub)
  std::uint32_t seed = 1;         // the preset's seed
  bool objt = true;               // --format objt|both
  bool gltf = true;               // --format gltf|both
  bool slices = false;            // --slices: bake LOD1/LOD2 (headless GL) and write their layers
};

struct BakeCommand {
  enum class Kind { kHelp, kTerrain, kMerge, kTree } kind = Kind::kHelp;
  std::filesystem::path source;               // kTerrain
  std::vector<std::filesystem::path> shares;  // kMerge
  TreeCommand tree;                           // kTree (out is the folder)
  std::filesystem::path out;
  TerrainBakeSettings settings;
  int share = 0, shares_total = 1;            // --tiles I/N
  bool tiled = false;                         // --tiles given: write a share (even for 0/1)
  std::uint32_t overview_side = 4097;         // --overview-side S: the ground overview's limit, S x S
  bool quiet = false;                         // no progress lines
};

// Errors (kInvalidArgument): unknown command or option, missing SOURCE/--out, a bad --tiles or
// --set (the message names the parameter and its range); for `tree` an unknown --preset (the
// names are listed), a bad --seed or --format, both or neither of SPECIES.json and --preset,
// --seed without --preset.
Result<BakeCommand> parse_bake_args(const std::vector<std::string>& args);
std::string bake_usage();

}  // namespace sylva::bake
