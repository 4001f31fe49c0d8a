// Species files and the OBJT models they name (issue #16) through sylva-player: junk, truncated,
// wrong types, NaN, huge numbers and files, a species naming itself, missing files. A bad species
// is left out with a warning naming the slot, the file and the JSON path, and the scene still
// plays with the good one; a scene whose every species fails is refused with that message.

#include "hostile_bytes.hpp"
#include "hostile_case.hpp"

#include <limits>

namespace sylva::hostile {

namespace {

const std::string kRun = "scene.json --size 32x18 --frames 1";

// Seed 000 §4.3.1's plain layout: a trunk and one branch.
std::string seed_objt() {
  return "name = \"hostile\"\nB 0 {\n l 0\n d 5\n z 0 0 0\n k 0 5 0\n r 1 0 0\n s 0 0 -1\n t 0 1 0\n p -1\n x 0\n}\n"
         "B 1 {\n l 1\n d 2\n z 0 3 0\n k 2 3 0\n r 0 1 0\n s 0 0 1\n t 1 0 0\n p 0\n x 0.6\n}\n";
}

// A vegetation scene whose slot 0 is a good species (good.json) and slot 1 `bad` (when given).
std::string species_scene(const std::string& bad) {
  std::string slots = R"("0": {"file": "good.json"})";
  if (!bad.empty()) slots += R"(, "1": {"file": ")" + bad + R"("})";
  return R"({"sylva_scene": 1, "name": "hostile", "camera": {"position": [0, 4, 30], "yaw_deg": 0, "pitch_deg": 0, "fov_deg": 40},
            "ground": {"size": 100.0, "resolution": 33, "generator": "flat"},
            "vegetation": {"area_min": [-1, -1], "area_max": [1, 1], "layout": "grid", "trees_per_hectare": 1, "leaf_texture_size": 32,
                           "forest": {"lod": {"enabled": false}}, "species_files": {)" +
         slots + "}}}\n";
}

// The good species and `bad.json` (with `bytes`, and the files `beside` it) beside it; the scene
// plays (exit 0, a picture) and the message names the bad file and `words`.
HostileCase bad_species(std::string name, std::function<std::string()> bytes, std::vector<std::string> words,
                        std::vector<InputFile> beside = {}) {
  words.insert(words.begin(), {"vegetation.species_files.1.file", "bad.json", "left out"});
  std::vector<InputFile> files = {{"scene.json", [] { return species_scene("bad.json"); }},
                                  {"good.json", [] { return std::string(R"({"name": "good", "model": {"objt": "tree.objt"}})"); }},
                                  {"tree.objt", seed_objt},
                                  {"bad.json", std::move(bytes)}};
  for (InputFile& f : beside) files.push_back(std::move(f));
  return {.name = std::move(name),
          .files = std::move(files),
          .args = kRun + " --screenshot shot.png",
          .exit_code = 0,
          .words = std::move(words),
          .needs_module = "vegetation",
          .picture = "shot.png"};
}

std::function<std::string()> text(std::string s) {
  return [s] { return s; };
}

// A species of the shrub preset whose `images` (the JSON members "leaf", "bark", "season") name
// the image files of a row.
std::function<std::string()> with_images(const std::string& images) {
  return text(R"({"model": {"preset": "shrub"}, )" + images + "}");
}
std::string rgba_png(std::uint32_t side) { return png_solid(side, side, 4, std::string("\x30\x80\x20\xff", 4)); }
std::vector<float> nan_every_third(int n) {
  std::vector<float> v(static_cast<std::size_t>(n), 0.5f);
  for (std::size_t i = 0; i < v.size(); i += 3) v[i] = std::numeric_limits<float>::quiet_NaN();
  return v;
}

// The editor's path: a script sets a species slot on a scene that plays with the good species.
HostileCase editor_sets(std::string name, std::string commands, int exit_code, std::vector<std::string> words) {
  return {.name = std::move(name),
          .tool = Tool::kEditor,
          .files = {{"s.txt", text("load scene.json\n" + commands + "frames 1\nscreenshot shot.png 32x18\nquit\n")},
                    {"scene.json", [] { return species_scene(""); }},
                    {"good.json", text(R"({"name": "good", "model": {"objt": "tree.objt"}})")},
                    {"tree.objt", seed_objt},
                    {"bad.json", text(R"({"model": {"objt": "tree.objt"}, "units": -2})")}},
          .args = "--script s.txt --size 32x18",
          .exit_code = exit_code,
          .words = std::move(words),
          .needs_module = "vegetation",
          .picture = exit_code == 0 ? "shot.png" : ""};
}

}  // namespace

std::vector<HostileCase> species_file_cases() {
  std::vector<HostileCase> cases = {
      bad_species("SpeciesBinaryJunk", [] { return junk(3000); }, {"bad.json:1:"}),
      bad_species("SpeciesEmptyFile", text(""), {"bad.json:1:"}),
      bad_species("SpeciesTruncated", text(R"({"model": {"objt": "tree.o)"), {"bad.json:1:"}),
      bad_species("SpeciesNotAnObject", text("[1, 2, 3]"), {"must be a JSON object"}),
      bad_species("SpeciesWithoutModel", text(R"({"units": 2})"), {"model: missing"}),
      bad_species("SpeciesUnitsWrongType", text(R"({"model": {"objt": "tree.objt"}, "units": "big"})"), {"units"}),
      bad_species("SpeciesUnitsNaN", text(R"({"model": {"objt": "tree.objt"}, "units": NaN})"), {"bad.json:1:"}),
      bad_species("SpeciesUnitsHuge", text(R"({"model": {"objt": "tree.objt"}, "units": 1e300})"), {"units"}),
      bad_species("SpeciesTreeTooLarge", text(R"({"model": {"objt": "tree.objt"}, "units": 900})"), {"units", "1000 m limit"}),
      bad_species("SpeciesTintNegative", text(R"({"model": {"objt": "tree.objt"}, "leaf_tint": [-1, 1, 1]})"), {"leaf_tint"}),
      bad_species("SpeciesNamesItself", text(R"({"model": {"objt": "bad.json"}})"), {"model.objt", "bad.json:1"}),
      bad_species("SpeciesObjtMissing", text(R"({"model": {"objt": "trees/oak.objt"}})"),
                  {"model.objt: no such file trees/oak.objt"}),
      bad_species("SpeciesObjtIsAFolder", text(R"({"model": {"objt": "."}})"), {"model.objt", "not a file"}),
      bad_species("SpeciesPresetUnknown", text(R"({"model": {"preset": "palm"}})"), {"model.preset"}),
      bad_species("SpeciesParameterHuge", text(R"({"model": {"preset": "birch", "parameters": {"trunk_length": 1e9}}})"),
                  {"model.parameters.trunk_length"}),
      bad_species("SpeciesTooBig", [] { return std::string(3u << 20, ' '); }, {"MiB limit"}),
      bad_species("SpeciesObjtOf100MiB", text(R"({"model": {"objt": "big.objt"}})"), {"model.objt", "big.objt", "64 MiB limit"},
                  {{"big.objt", seed_objt, std::uintmax_t{100} << 20}}),
      // Leaf, bark and season images (issue #16): each refused naming the species file, the JSON
      // path and the image, by its header where the size is the problem (nothing decoded).
      bad_species("SpeciesLeafImageMissing", with_images(R"("leaf": {"color": "gone.png"})"), {"leaf.color: no such file gone.png"}),
      bad_species("SpeciesLeafImageTruncated", with_images(R"("leaf": {"color": "leaf.png"})"), {"leaf.color", "leaf.png"},
                  {{"leaf.png", [] { return truncated(rgba_png(64), 50); }}}),
      bad_species("SpeciesLeafImageIsJson", with_images(R"("leaf": {"color": "leaf.png"})"), {"leaf.color", "leaf.png"},
                  {{"leaf.png", text(R"({"not": "an image"})")}}),
      bad_species("SpeciesLeafImageWrongType", with_images(R"("leaf": {"color": 5})"), {"leaf.color"}),
      bad_species("SpeciesLeafImageWithoutAlpha", with_images(R"("leaf": {"color": "leaf.png"})"),
                  {"leaf.color", "leaf.png has 3 channels", "RGBA"},
                  {{"leaf.png", [] { return png_solid(8, 8, 3, "\x30\x80\x20"); }}}),
      bad_species("SpeciesLeafImageOnePixel", with_images(R"("leaf": {"color": "leaf.png"})"),
                  {"leaf.color", "leaf.png is 1x1", "minimum"}, {{"leaf.png", [] { return rgba_png(1); }}}),
      bad_species("SpeciesLeafImage16384Squared", with_images(R"("leaf": {"color": "leaf.png"})"),
                  {"leaf.color", "leaf.png", "16384x16384", "limit of 4096"},
                  {{"leaf.png", [] { return png_lying_header(16'384, 16'384, 8, 6); }}}),
      bad_species("SpeciesLeafImageNaN", with_images(R"("leaf": {"color": "leaf.exr"})"), {"leaf.color", "leaf.exr", "NaN"},
                  {{"leaf.exr", [] { return float_image(".exr", 8, 8, nan_every_third(64)); }}}),
      bad_species("SpeciesLeafNormalIsTheSpeciesFile", with_images(R"("leaf": {"color": "leaf.png", "normal": "bad.json"})"),
                  {"leaf.normal", "bad.json"}, {{"leaf.png", [] { return rgba_png(8); }}}),
      bad_species("SpeciesBarkImageInfinity", with_images(R"("bark": {"color": "bark.tif"})"), {"bark.color", "bark.tif", "Inf"},
                  {{"bark.tif", [] {
                      std::vector<float> v(64, 0.5f);
                      v[9] = std::numeric_limits<float>::infinity();
                      return float_image(".tif", 8, 8, v);
                    }}}),
      bad_species("SpeciesBarkImageIsAFolder", with_images(R"("bark": {"color": "bark/"})"), {"bark.color", "not a file"},
                  {{"bark/", {}}}),
      bad_species("SpeciesSeasonImageNotAColumn", with_images(R"("season": "season.png")"), {"season", "season.png is 8x8", "one column"},
                  {{"season.png", [] { return png_solid(8, 8, 3, "\x30\x80\x20"); }}}),
      bad_species("SpeciesSeasonImage16384Tall", with_images(R"("season": "season.png")"), {"season", "season.png", "1x16384"},
                  {{"season.png", [] { return png_lying_header(1, 16'384, 8, 2); }}}),
      {.name = "SpeciesObjtJunk",
       .files = {{"scene.json", [] { return species_scene("bad.json"); }},
                 {"good.json", text(R"({"model": {"objt": "tree.objt"}})")},
                 {"tree.objt", seed_objt},
                 {"bad.json", text(R"({"model": {"objt": "junk.objt"}})")},
                 {"junk.objt", [] { return junk(5000); }}},
       .args = kRun,
       .exit_code = 0,
       .words = {"vegetation.species_files.1.file", "bad.json: model.objt: junk.objt:", "left out"},
       .needs_module = "vegetation"},
      {.name = "SpeciesEveryOneFails",
       .files = {{"scene.json", [] { return species_scene(""); }}, {"good.json", text(R"({"model": {"objt": "gone.objt"}})")}},
       .args = kRun,
       .exit_code = 2,
       .words = {"good.json: model.objt: no such file gone.objt", "no species left"},
       .needs_module = "vegetation"},
      editor_sets("EditorSetsABrokenSpecies", "set vegetation.species_files.1.file bad.json\nexpect vegetation.species_files.1.file bad.json\n",
                  0, {"vegetation.species_files.1.file", "bad.json: units", "left out"}),
      editor_sets("EditorSetsTheOnlySpeciesMissing", "set vegetation.species_files.0.file gone.json\n", 1,
                  {"s.txt:2", "gone.json", "no such file", "no species left"}),
  };
  return cases;
}

}  // namespace sylva::hostile
