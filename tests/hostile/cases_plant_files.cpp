// The plant files of issue #16 besides tree species (cases_species_files.cpp), through
// sylva-player: a voxel world's species table (`voxel.flora.species_file`) and its .lsys grammars,
// its block palette (`voxel.blocks.palette_file`) with image textures, and grass's control
// texture (`grass.maps.control`), tint image (`grass.maps.tint`) and mesh (`grass.mesh.file`).
// Truncated, junk, wrong types, missing, huge, NaN/Inf samples, 1x1 and 16384^2 images (a header
// that claims the size: refused from the header, nothing decoded), grammars that explode and
// files naming themselves. The voxel world keeps playing (a bad species is left out, a bad table
// or palette falls back to the shipped one, with a warning naming the file and the JSON path or
// grammar line); a bad grass file leaves the grass section out with a warning naming the key and
// the file, and the rest of the scene opens.

#include "hostile_bytes.hpp"
#include "hostile_case.hpp"

#include <sylva/core/atomic_file.hpp>

#include <limits>
#include <stdexcept>

namespace sylva::hostile {

namespace {

const std::string kRun = "scene.json --size 32x18 --frames 1";

std::function<std::string()> text(std::string s) {
  return [s] { return s; };
}

// A one-chunk-radius voxel world (seed 3) whose flora and blocks sections are `flora`, `blocks`.
std::string voxel_scene(const std::string& flora, const std::string& blocks = "{}") {
  return R"({"sylva_scene": 1, "name": "hostile", "camera": {"position": [16, 95, 16], "yaw_deg": 0, "pitch_deg": -60, "fov_deg": 60},
            "render": {"msaa_samples": 1, "shadows": {"enabled": false}},
            "voxel": {"radius_chunks": 1, "threads": 2, "worldgen": {"seed": 3, "variants_per_species": 1}, "flora": )" +
         flora + R"(, "blocks": )" + blocks + "}}\n";
}

// A grammar that grows a column of blocks, doubled per derivation (seed 004 §4.5.1 format).
const std::string kPillar = "# a pillar\n0 0 1\nU\nU > UU\n";

// A species table: the good pillar species first, then `bad` (a JSON object) when given.
std::string species_table(const std::string& bad) {
  const std::string pillar =
      R"({"name": "pillar", "grammar": "pillar.lsys", "derivations": [3, 3], "size": [1, 1], "blocks": {"0": "glowstone"},
          "biomes": {"plains": {"spacing": 5, "chance": 1}, "savanna": {"spacing": 5, "chance": 1}}})";
  return R"({"species": [)" + pillar + (bad.empty() ? "" : ", " + bad) + "]}\n";
}
std::string species_with_grammar(const std::string& grammar, const std::string& derivations = "[3, 3]") {
  return R"({"name": "bad", "grammar": ")" + grammar + R"(", "derivations": )" + derivations +
         R"(, "size": [1, 1], "blocks": {"0": "oak_log"}, "biomes": {"plains": {"spacing": 5, "chance": 1}}})";
}

// The world plays (exit 0, a picture) with `plants.json` (and the files `beside` it); the
// message names the species file's key, the file and `words`.
HostileCase voxel_species(std::string name, std::function<std::string()> table, std::vector<std::string> words,
                          std::vector<InputFile> beside = {}) {
  words.insert(words.begin(), {"voxel.flora.species_file", "plants.json"});
  std::vector<InputFile> files = {{"scene.json", [] { return voxel_scene(R"({"species_file": "plants.json"})"); }},
                                  {"pillar.lsys", text(kPillar)}};
  if (table) files.push_back({"plants.json", std::move(table)});  // none: the missing file
  for (InputFile& f : beside) files.push_back(std::move(f));
  return {.name = std::move(name), .files = std::move(files), .args = kRun + " --screenshot shot.png", .exit_code = 0,
          .words = std::move(words), .needs_module = "voxel", .picture = "shot.png"};
}

// One bad species beside the good pillar: left out with a warning, the others stay.
HostileCase voxel_species_left_out(std::string name, const std::string& bad, std::vector<std::string> words,
                                   std::vector<InputFile> beside = {}) {
  words.push_back("the species is left out");
  return voxel_species(std::move(name), [bad] { return species_table(bad); }, std::move(words), std::move(beside));
}

// A palette with one image-textured block; the world plays with the standard palette.
HostileCase voxel_palette(std::string name, std::function<std::string()> palette, std::vector<std::string> words,
                          std::vector<InputFile> beside = {}) {
  words.insert(words.begin(), {"voxel.blocks.palette_file", "blocks.json"});
  words.push_back("the standard palette is used");
  std::vector<InputFile> files = {{"scene.json", [] { return voxel_scene("{}", R"({"palette_file": "blocks.json"})"); }}};
  if (palette) files.push_back({"blocks.json", std::move(palette)});  // none: the missing file
  for (InputFile& f : beside) files.push_back(std::move(f));
  return {.name = std::move(name), .files = std::move(files), .args = kRun + " --screenshot shot.png", .exit_code = 0,
          .words = std::move(words), .needs_module = "voxel", .picture = "shot.png"};
}
// The shipped palette (modules/voxel/data/palette.json) with stone's texture (blocks[0]) `texture`:
// the only fault of the palette is the row's.
std::function<std::string()> palette_with_texture(const std::string& texture) {
  return [texture] {
    auto shipped = read_file(std::string(SYLVA_SCENES_DIR) + "/../modules/voxel/data/palette.json");
    if (!shipped.ok()) throw std::runtime_error(shipped.error().message);
    const std::string stone = R"({"name": "stone", "texture": "stone")";
    const std::size_t at = shipped->find(stone);
    if (at == std::string::npos) throw std::runtime_error("palette.json: no stone block to replace");
    return shipped->replace(at, stone.size(), R"({"name": "stone", "texture": ")" + texture + R"(")");
  };
}

// A small meadow whose grass section holds `grass` (JSON members); the scene opens without its
// grass (exit 0, a picture of the ground) with a warning naming `key`, the file and `words`.
HostileCase grass_file(std::string name, const std::string& grass, const std::string& key, std::string file,
                       std::function<std::string()> bytes, std::vector<std::string> words, std::vector<InputFile> beside = {}) {
  words.insert(words.begin(), {key, file});
  std::vector<InputFile> files = {
      {"scene.json", text(R"({"sylva_scene": 1, "name": "hostile", "ground": {"size": 100.0, "resolution": 33, "height": 10.0},
                             "grass": {"field": {"density": 20}, )" + grass + "}}\n")}};
  if (bytes) files.push_back({std::move(file), std::move(bytes)});  // none: the missing file
  for (InputFile& f : beside) files.push_back(std::move(f));
  words.push_back("the grass section is left out");
  return {.name = std::move(name), .files = std::move(files), .args = kRun + " --screenshot shot.png", .exit_code = 0,
          .words = std::move(words), .needs_module = "grass", .picture = "shot.png"};
}
HostileCase control_map(std::string name, std::string file, std::function<std::string()> bytes, std::vector<std::string> words) {
  return grass_file(std::move(name), R"("maps": {"control": ")" + file + R"("})", "grass.maps.control", file, std::move(bytes),
                    std::move(words));
}
HostileCase tint_map(std::string name, std::string file, std::function<std::string()> bytes, std::vector<std::string> words) {
  return grass_file(std::move(name), R"("maps": {"tint": ")" + file + R"("})", "grass.maps.tint", file, std::move(bytes),
                    std::move(words));
}
HostileCase grass_mesh(std::string name, std::string file, std::function<std::string()> bytes, std::vector<std::string> words) {
  return grass_file(std::move(name), R"("surface": "mesh", "mesh": {"file": ")" + file + R"("})", "grass.mesh.file", file,
                    std::move(bytes), std::move(words));
}
// Grass on a one-triangle mesh with UVs whose density is the image `file` over its UVs.
HostileCase uv_density_map(std::string name, std::string file, std::function<std::string()> bytes, std::vector<std::string> words) {
  return grass_file(std::move(name),
                    R"("surface": "mesh", "mesh": {"file": "m.obj", "density_source": "uv_map", "density_file": ")" + file + R"("})",
                    "grass.mesh.density_file", file, std::move(bytes), std::move(words),
                    {{"m.obj", text("v 0 0 0\nv 4 0 0\nv 0 0 4\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")}});
}

std::vector<float> every_third(float bad, int n = 64) {
  std::vector<float> v(static_cast<std::size_t>(n), 0.5f);
  for (std::size_t i = 0; i < v.size(); i += 3) v[i] = bad;
  return v;
}
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

std::vector<HostileCase> plant_file_cases() {
  return {
      // Voxel species tables: the whole table fails, the shipped species stand in.
      voxel_species("VoxelSpeciesTableMissing", nullptr, {"no such file", "the shipped species are used"}),
      voxel_species("VoxelSpeciesTableJunk", [] { return junk(3000); }, {"plants.json:1:", "the shipped species are used"}),
      voxel_species("VoxelSpeciesTableTruncated", [] { return truncated(species_table(""), 60); },
                    {"plants.json:", "the shipped species are used"}),
      voxel_species("VoxelSpeciesTableNotAnObject", text("[1, 2]"), {"the shipped species are used"}),
      voxel_species("VoxelSpeciesTableTooBig", [] { return std::string(5u << 20, ' '); }, {"MiB", "the shipped species are used"}),
      voxel_species("VoxelSpeciesTableNaN", text(R"({"species": [{"name": "x", "derivations": [NaN, 3]}]})"),
                    {"plants.json:1:", "the shipped species are used"}),
      // One bad species: left out, the pillar stays.
      voxel_species_left_out("VoxelSpeciesGrammarMissing", species_with_grammar("gone.lsys"), {"species[1].grammar", "gone.lsys"}),
      voxel_species_left_out("VoxelSpeciesGrammarJunk", species_with_grammar("junk.lsys"), {"species[1].grammar", "junk.lsys"},
                             {{"junk.lsys", [] { return junk(2000); }}}),
      voxel_species_left_out("VoxelSpeciesGrammarTruncated", species_with_grammar("cut.lsys"), {"species[1].grammar", "cut.lsys"},
                             {{"cut.lsys", text("0 0")}}),
      voxel_species_left_out("VoxelSpeciesGrammarNaNAngles", species_with_grammar("nan.lsys"), {"species[1].grammar", "nan.lsys:1"},
                             {{"nan.lsys", text("nan nan nan\nU\nU > UU\n")}}),
      voxel_species_left_out("VoxelSpeciesGrammarOf100MiB", species_with_grammar("big.lsys"), {"species[1].grammar", "big.lsys", "MiB"},
                             {{"big.lsys", text(kPillar), std::uintmax_t{100} << 20}}),
      voxel_species_left_out("VoxelSpeciesGrammarIsTheTable", species_with_grammar("plants.json"),
                             {"species[1].grammar", "plants.json:1"}),
      // Ten-fold growth per derivation for 30 derivations: 10^30 symbols, refused before deriving.
      voxel_species_left_out("VoxelSpeciesGrammarExplodes", species_with_grammar("boom.lsys", "[30, 30]"), {"species[1]", "boom.lsys"},
                             {{"boom.lsys", text("0 0 1\nU\nU > UUUUUUUUUU\n")}}),
      voxel_species_left_out("VoxelSpeciesDerivationsWrongType", species_with_grammar("pillar.lsys", R"("many")"),
                             {"species[1].derivations"}),
      voxel_species_left_out("VoxelSpeciesDerivationsHuge", species_with_grammar("pillar.lsys", "[3, 1e300]"),
                             {"species[1].derivations"}),
      // The editor's path: a script names a junk species table and a missing palette on a world
      // that plays; the warnings reach the editor's messages and the world still draws.
      {.name = "EditorSetsAJunkVoxelSpeciesTableAndAMissingPalette",
       .tool = Tool::kEditor,
       .files = {{"s.txt", text("load scene.json\nset voxel.flora.species_file junk.json\nset voxel.blocks.palette_file gone.json\n"
                                "frames 1\nscreenshot shot.png 32x18\nquit\n")},
                 {"scene.json", [] { return voxel_scene("{}"); }},
                 {"junk.json", [] { return junk(3000); }}},
       .args = "--script s.txt --size 32x18",
       .exit_code = 0,
       .words = {"voxel.flora.species_file", "junk.json:1:", "the shipped species are used", "voxel.blocks.palette_file",
                 "gone.json", "the standard palette is used"},
       .needs_module = "voxel",
       .picture = "shot.png"},
      // Block palettes: the whole palette fails, the standard one stands in.
      voxel_palette("VoxelPaletteMissing", nullptr, {"no such file"}),
      voxel_palette("VoxelPaletteJunk", [] { return junk(3000); }, {"blocks.json:1:"}),
      voxel_palette("VoxelPaletteTruncated", [] { return truncated(R"({"blocks": [{"name": "stone", "texture": "stone"}]})", 25); },
                    {"blocks.json:1:"}),
      voxel_palette("VoxelPaletteTooBig", [] { return std::string(5u << 20, ' '); }, {"MiB"}),
      voxel_palette("VoxelPaletteTextureMissing", palette_with_texture("brick.png"), {"blocks[0].texture", "brick.png"}),
      voxel_palette("VoxelPaletteTextureTruncated", palette_with_texture("brick.png"), {"blocks[0].texture", "brick.png"},
                    {{"brick.png", [] { return truncated(png_solid(64, 64, 4, "\xa0\x30\x20\xff"), 50); }}}),
      voxel_palette("VoxelPaletteTexture16384Squared", palette_with_texture("brick.png"),
                    {"blocks[0].texture", "brick.png", "16384x16384", "limit of 4096"},
                    {{"brick.png", [] { return png_lying_header(16'384, 16'384, 8, 6); }}}),
      voxel_palette("VoxelPaletteTextureNaN", palette_with_texture("brick.exr"), {"blocks[0].texture", "brick.exr", "NaN"},
                    {{"brick.exr", [] { return float_image(".exr", 8, 8, every_third(kNaN)); }}}),
      voxel_palette("VoxelPaletteTextureIsThePalette", palette_with_texture("blocks.json"), {"blocks[0].texture", "blocks.json"}),
      // A 1x1 texture is a legal (flat) texture: the palette loads and the world plays.
      {.name = "VoxelPaletteTextureOnePixel",
       .files = {{"scene.json", [] { return voxel_scene("{}", R"({"palette_file": "blocks.json"})"); }},
                 {"blocks.json", palette_with_texture("brick.png")},
                 {"brick.png", [] { return png_solid(1, 1, 4, "\xa0\x30\x20\xff"); }}},
       .args = kRun + " --screenshot shot.png", .exit_code = 0, .absent = {"voxel.blocks.palette_file"},
       .needs_module = "voxel", .picture = "shot.png"},
      // Grass control texture (seed 001: R density, G height, B terrain) and tint image.
      control_map("GrassControlMissing", "c.png", nullptr, {"no such file"}),
      control_map("GrassControlTruncated", "c.png", [] { return truncated(png_solid(64, 64, 3, "\x80\x80\x80"), 60); }, {}),
      control_map("GrassControlIsJson", "c.png", text(R"({"not": "an image"})"), {}),
      control_map("GrassControlGrey", "c.png", [] { return png_solid(8, 8, 1, "\x80"); }, {"1 channel", "needs 2"}),
      control_map("GrassControlNaN", "c.exr", [] { return float_image(".exr", 8, 8, every_third(kNaN)); }, {"NaN"}),
      // 16384^2: a real one-colour grey PNG (1.2 MB) decoded as 1 GiB of floats before its channel
      // count was checked; now it is refused from its header (and so is an RGB header's claim).
      control_map("GrassControl16384SquaredGrey", "c.png", [] { return png_solid(16'384, 16'384, 1, "\x80"); },
                  {"16384x16384", "limit"}),
      control_map("GrassControl16384SquaredRgb", "c.png", [] { return png_lying_header(16'384, 16'384, 8, 2); },
                  {"16384x16384", "limit"}),
      tint_map("GrassTintMissing", "t.png", nullptr, {"no such file"}),
      tint_map("GrassTintGrey", "t.png", [] { return png_solid(8, 8, 1, "\x80"); }, {"1 channel", "needs 3"}),
      tint_map("GrassTintInfinity", "t.tif", [] { return float_image(".tif", 8, 8, every_third(kInf)); }, {"Inf"}),
      tint_map("GrassTint16384Squared", "t.png", [] { return png_lying_header(16'384, 16'384, 8, 2); }, {"16384x16384", "limit"}),
      // Grass on a mesh.
      grass_mesh("GrassMeshMissing", "m.obj", nullptr, {"no such file"}),
      grass_mesh("GrassMeshJunk", "m.obj", [] { return junk(4000); }, {}),
      grass_mesh("GrassMeshTruncated", "m.obj", text("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2"), {}),
      grass_mesh("GrassMeshNaNVertex", "m.obj", text("v nan 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n"), {"m.obj:1"}),
      grass_mesh("GrassMeshFaceOutOfRange", "m.obj", text("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 99999999999\n"), {"m.obj:4"}),
      grass_mesh("GrassMeshIsAnImage", "m.obj", [] { return png_solid(8, 8, 3, "\x80\x80\x80"); }, {}),
      grass_mesh("GrassMeshUnknownFormat", "m.xyz", text("v 0 0 0\n"), {}),
      // A 2 GiB OBJ (a triangle, then a hole): refused by its size, unread.
      [] {
        HostileCase c = grass_mesh("GrassMeshObjOf2GiB", "m.obj", text("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n"),
                                   {"2048 MiB", "limit"});
        c.files.back().sparse_size = std::uintmax_t{2} << 30;
        return c;
      }(),
      // A glTF whose accessor claims 10^9 vertices over a 36-byte view: refused from the claim.
      grass_mesh("GrassMeshGltfClaimsABillionVertices", "m.gltf",
                 text(R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
                    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
                    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/AAABAAIAAAA="}],
                    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
                    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 1000000000, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
                                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})"),
                 {"accessors[0]", "1000000000"}),
      // Its density image over the UVs (grass.mesh.density_source "uv_map").
      uv_density_map("GrassUvDensityMissing", "d.png", nullptr, {"no such file"}),
      uv_density_map("GrassUvDensityNaN", "d.exr", [] { return float_image(".exr", 8, 8, every_third(kNaN)); }, {"NaN"}),
      uv_density_map("GrassUvDensityTruncated", "d.png", [] { return truncated(png_solid(64, 64, 1, "\x80"), 60); }, {}),
      uv_density_map("GrassUvDensity16384SquaredGrey", "d.png", [] { return png_solid(16'384, 16'384, 1, "\x80"); },
                     {"16384x16384", "limit"}),
  };
}

}  // namespace sylva::hostile
