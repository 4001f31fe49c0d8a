// Map images (ground height, grass and tree density) through sylva-player: headers that lie
// about the size, truncated and junk data, NaN/Inf samples, every format the tools read (PNG,
// PGM, PFM, EXR, TIFF), and the 16384^2 height map that ran the GPU buffer out of memory.

#include "hostile_bytes.hpp"
#include "hostile_case.hpp"

#include <cmath>
#include <limits>

namespace sylva::hostile {

namespace {

const std::string kRun = "scene.json --size 32x18 --frames 1";
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A case whose scene uses `map` (written with `bytes`) as the ground's height map.
HostileCase height_map(std::string name, std::string map, std::function<std::string()> bytes, std::vector<std::string> words,
                       int exit_code = 2) {
  return {.name = std::move(name), .files = {{"scene.json", [map] { return ground_scene(map); }}, {map, std::move(bytes)}},
          .args = kRun, .exit_code = exit_code, .words = std::move(words)};
}

// Adds a screenshot that must hold a picture (for cases that exit 0).
HostileCase playable(HostileCase c) {
  c.args += " --screenshot shot.png";
  c.picture = "shot.png";
  return c;
}

std::string ramp_row(std::uint32_t width, std::uint32_t y) {
  std::string row(width, '\0');
  for (std::uint32_t x = 0; x < width; ++x) row[x] = static_cast<char>((x + y) & 0xffu);
  return row;
}
std::string small_png() {
  return png_gray8(64, 64, [](std::uint32_t y) { return ramp_row(64, y); });
}
std::vector<float> with_every_third(float bad) {
  std::vector<float> v(64, 0.5f);
  for (std::size_t i = 0; i < v.size(); i += 3) v[i] = bad;
  return v;
}
std::vector<float> ramp(int n) {
  std::vector<float> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = static_cast<float>(i) / static_cast<float>(n);
  return v;
}

}  // namespace

std::vector<HostileCase> map_image_cases() {
  std::vector<HostileCase> cases = {
      height_map("PngHeaderClaims100000Squared", "h.png", [] { return png_lying_header(100'000, 100'000); },
                 {"ground.maps.height", "h.png", "100000x100000"}),
      // Within the per-side limit, but 16 GiB as floats: refused from the header, not allocated.
      height_map("PngHeaderClaims16GiB", "h.png", [] { return png_lying_header(32'768, 32'768, 16, 6); },
                 {"ground.maps.height", "h.png", "above the limit"}),
      height_map("PngTruncated", "h.png", [] { return truncated(small_png(), 60); }, {"ground.maps.height", "h.png"}),
      height_map("PngDataShorterThanHeader", "h.png", [] { return png_lying_header(3000, 3000); },
                 {"ground.maps.height", "h.png"}),
      height_map("PngBadChecksum", "h.png",
                 [] {
                   std::string bytes = small_png();
                   bytes[40] = static_cast<char>(bytes[40] ^ 0x5a);  // inside IDAT: its CRC no longer matches
                   return bytes;
                 },
                 {"ground.maps.height", "h.png"}),
      height_map("PngBinaryJunk", "h.png", [] { return junk(2000); }, {"ground.maps.height", "h.png", "cannot open"}),
      height_map("PngEmptyFile", "h.png", [] { return std::string(); }, {"ground.maps.height", "h.png"}),
      height_map("PgmHeaderClaims100000Squared", "h.pgm", [] { return pgm("100000", "100000", "255", junk(64)); },
                 {"ground.maps.height", "h.pgm", "100000x100000"}),
      height_map("PgmNegativeWidth", "h.pgm", [] { return pgm("-4", "4", "255", junk(16)); },
                 {"ground.maps.height", "h.pgm"}),
      height_map("PgmShortData", "h.pgm", [] { return pgm("64", "64", "255", junk(10)); },
                 {"ground.maps.height", "h.pgm"}),
      height_map("PfmNaN", "h.pfm", [] { return pfm(8, 8, with_every_third(kNaN)); },
                 {"ground.maps.height", "h.pfm", "NaN"}),
      height_map("ExrNaN", "h.exr", [] { return float_image(".exr", 8, 8, with_every_third(kNaN)); },
                 {"ground.maps.height", "h.exr", "NaN"}),
      height_map("ExrTruncated", "h.exr", [] { return truncated(float_image(".exr", 64, 64, ramp(64 * 64)), 300); },
                 {"ground.maps.height", "h.exr"}),
      height_map("TiffInfinity", "h.tif", [] { return float_image(".tif", 8, 8, with_every_third(kInf)); },
                 {"ground.maps.height", "h.tif", "Inf"}),
      height_map("TiffHeaderClaims100000Squared", "h.tif", [] { return tiff_lying_header(100'000, 100'000); },
                 {"ground.maps.height", "h.tif", "100000x100000"}),
      height_map("TiffStripShorterThanHeader", "h.tif", [] { return tiff_lying_header(2048, 2048, 16); },
                 {"ground.maps.height", "h.tif"}),
      height_map("TiffBinaryJunk", "h.tif", [] { return "II*" + std::string(1, '\0') + junk(200); },
                 {"ground.maps.height", "h.tif"}),
      height_map("UnknownImageFormat", "h.xyz", [] { return junk(100); }, {"ground.maps.height", "h.xyz"}),
      // The 16384^2 height map ran the ground's GPU buffer out of memory and exited 0.
      height_map("Png16384SquaredHeightMap", "big.png",
                 [] { return png_gray8(16'384, 16'384, [](std::uint32_t y) { return ramp_row(16'384, y); }); },
                 {"ground", "big.png", "16384x16384"}),
      {.name = "MapIsAFolder", .files = {{"scene.json", [] { return ground_scene("h.png"); }}, {"h.png/", {}}},
       .args = kRun, .words = {"ground.maps.height", "h.png", "is a folder"}},
      {.name = "MapMissing", .files = {{"scene.json", [] { return ground_scene("h.png"); }}}, .args = kRun,
       .words = {"ground.maps.height", "h.png", "no such file"}},
      {.name = "GrassDensityNaN",
       .files = {{"scene.json", [] { return density_scene("grass", "d.pfm"); }},
                 {"d.pfm", [] { return pfm(8, 8, with_every_third(kNaN)); }}},
       .args = kRun + " --screenshot shot.png", .exit_code = 0,
       .words = {"grass.maps.density", "d.pfm", "NaN", "the grass section is left out"}, .needs_module = "grass",
       .picture = "shot.png"},
      {.name = "TreeDensityHeaderClaims100000Squared",
       .files = {{"scene.json", [] { return density_scene("vegetation", "d.png"); }},
                 {"d.png", [] { return png_lying_header(100'000, 100'000); }}},
       .args = kRun, .words = {"vegetation.maps.density", "d.png", "100000x100000"}, .needs_module = "vegetation"},
      height_map("PngOnePixelHeightMap", "h.png", [] { return png_gray8(1, 1, [](std::uint32_t) { return std::string(1, '\x80'); }); },
                 {"ground.maps.height", "h.png", "2x2"}),
  };
  // Files that are legal (or read as legal: OpenImageIO takes a PGM maxval of 0 as 1) must
  // play, and draw a picture rather than garbage.
  cases.push_back(playable(height_map("PngTwoByTwoHeightMap", "h.png",
                                      [] { return png_gray8(2, 2, [](std::uint32_t y) { return ramp_row(2, y); }); }, {}, 0)));
  cases.push_back(playable(height_map("PgmMaxvalZero", "h.pgm", [] { return pgm("4", "4", "0", junk(16)); }, {}, 0)));
  return cases;
}

}  // namespace sylva::hostile
