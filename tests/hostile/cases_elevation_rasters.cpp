// Elevation rasters read through GDAL (ground "elevation": {"file": ...}): ASCII grids whose
// header lies about the size, holds NaN or is cut short, SRTM .hgt files of the wrong length,
// junk GeoTIFFs. The message names the scene key and the file; nodata holes are filled.
// Mesh terrains (model_terrain.file, seed 002 §4): a 2 GiB OBJ or IV is refused by its size,
// unread; a binary file named .obj is refused with its bytes quoted escaped (\x89PNG), not raw.

#include "hostile_bytes.hpp"
#include "hostile_case.hpp"

namespace sylva::hostile {

namespace {

HostileCase elevation(std::string name, std::string file, std::function<std::string()> bytes, std::vector<std::string> words) {
  const std::string scene = R"({"sylva_scene": 1, "ground": {"elevation": {"file": ")" + file + R"("}}})" "\n";
  words.insert(words.begin(), {"ground.elevation.file", file});
  return {.name = std::move(name), .files = {{"scene.json", [scene] { return scene; }}, {file, std::move(bytes)}},
          .args = "scene.json --size 32x18 --frames 1", .words = std::move(words)};
}

HostileCase model_mesh(std::string name, std::string file, std::function<std::string()> bytes, std::vector<std::string> words) {
  const std::string scene = R"({"sylva_scene": 1, "model_terrain": {"file": ")" + file + R"("}})" "\n";
  words.insert(words.begin(), {"model_terrain.file", file});
  return {.name = std::move(name), .files = {{"scene.json", [scene] { return scene; }}, {file, std::move(bytes)}},
          .args = "scene.json --size 32x18 --frames 1", .words = std::move(words), .needs_module = "model_terrain"};
}

// An ESRI ASCII grid with the given header values and body.
std::string ascii_grid(const std::string& ncols, const std::string& nrows, const std::string& body) {
  return "ncols " + ncols + "\nnrows " + nrows + "\nxllcorner 0\nyllcorner 0\ncellsize 10\n" + body;
}

}  // namespace

std::vector<HostileCase> elevation_raster_cases() {
  std::vector<HostileCase> cases = {
      elevation("AsciiGridClaims100000Squared", "dem.asc", [] { return ascii_grid("100000", "100000", "1 2 3 4\n"); }, {}),
      elevation("AsciiGridCutShort", "dem.asc", [] { return ascii_grid("64", "64", "1 2 3 4 5 6\n"); }, {}),
      elevation("AsciiGridNegativeSize", "dem.asc", [] { return ascii_grid("-3", "3", "1 2 3\n"); }, {}),
      elevation("HgtWrongLength", "N45E006.hgt", [] { return junk(1000); }, {}),
      elevation("GeoTiffJunk", "dem.tif", [] { return "II*" + std::string(1, '\0') + junk(300); }, {}),
      elevation("ElevationEmptyFile", "dem.tif", [] { return std::string(); }, {}),
  };
  // Nodata samples are filled (with a warning naming the count) and the ground still draws.
  // (GDAL's ASCII grid reader takes a literal "nan" as 0, silently: see the issue 17 report.)
  HostileCase holes = elevation("AsciiGridNodataFilled", "dem.asc", [] {
    return ascii_grid("3", "3", "NODATA_value -9999\n1 -9999 3\n4 5 -9999\n7 8 9\n");
  }, {"filled 2"});
  holes.words.erase(holes.words.begin());  // a run that plays names the file, not the key
  holes.exit_code = 0;
  holes.args += " --screenshot shot.png";
  holes.picture = "shot.png";
  cases.push_back(holes);
  for (const char* file : {"m.obj", "m.iv"}) {
    HostileCase huge = model_mesh(std::string("ModelTerrainMeshOf2GiB") + (file[2] == 'o' ? "Obj" : "Iv"), file,
                                  [] { return std::string("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n"); }, {"2048 MiB", "limit"});
    huge.files.back().sparse_size = std::uintmax_t{2} << 30;
    cases.push_back(huge);
  }
  cases.push_back(model_mesh("ModelTerrainObjIsAPng", "m.obj", [] { return png_solid(8, 8, 3, "\x80\x80\x80"); },
                             {"\\x89PNG", "no faces"}));
  return cases;
}

}  // namespace sylva::hostile
