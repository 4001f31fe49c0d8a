#pragma once
// The command line of sylva-bake (offline baking, DESIGN.md §1 apps/bake):
//   sylva-bake terrain SOURCE --out FILE.sylvaterrain [--tiles I/N] [--set terrain.KEY=VALUE]... [--quiet]
//   sylva-bake merge SHARE... --out FILE.sylvaterrain [--quiet]
// SOURCE is any elevation raster core/elevation_raster.hpp reads (GDAL: GeoTIFF, SRTM .hgt,
// ASCII grids; OpenImageIO: PNG/EXR/TIFF height maps). KEY is terrain.tree.* (ChunkTreeSettings)
// or terrain.elevation.* (ElevationReadOptions). With --tiles I/N (0 <= I < N) the bake writes
// share I of N to --out; `merge` joins the N shares into a file byte-identical to a one-process
// bake.

#include <sylva/core/elevation_raster.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/settings.hpp>

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

struct BakeCommand {
  enum class Kind { kHelp, kTerrain, kMerge } kind = Kind::kHelp;
  std::filesystem::path source;               // kTerrain
  std::vector<std::filesystem::path> shares;  // kMerge
  std::filesystem::path out;
  TerrainBakeSettings settings;
  int share = 0, shares_total = 1;            // --tiles I/N
  bool tiled = false;                         // --tiles given: write a share (even for 0/1)
  bool quiet = false;                         // no progress lines
};

// Errors (kInvalidArgument): unknown command or option, missing SOURCE/--out, a bad --tiles or
// --set (the message names the parameter and its range).
Result<BakeCommand> parse_bake_args(const std::vector<std::string>& args);
std::string bake_usage();

}  // namespace sylva::bake
