// sylva-bench command lines: sweeps of unknown paths and NaN values, sizes and frame counts out
// of range, scenes that cannot load, and --out folders that cannot be written (checked before
// anything is rendered).

#include "hostile_bytes.hpp"
#include "hostile_case.hpp"

namespace sylva::hostile {

namespace {
const std::string kSweep = "scene.json --sweep ground.height=5,10 --frames 1 --warmup 0 --size 32x18 ";
HostileCase bench(std::string name, std::string line, int exit_code, std::vector<std::string> words,
                  std::string scene = ground_scene()) {
  return {.name = std::move(name), .tool = Tool::kBench, .files = {{"scene.json", [scene] { return scene; }}},
          .args = std::move(line), .exit_code = exit_code, .words = std::move(words)};
}
}  // namespace

std::vector<HostileCase> bench_cases() {
  return {
      bench("BenchSweepUnknownPath", "scene.json --sweep nope.path=1,2 --out out", 2, {"--sweep", "nope.path"}),
      bench("BenchSweepNaN", "scene.json --sweep ground.height=nan,2 --out out", 2, {"ground.height", "nan"}),
      bench("BenchSweepNoValues", "scene.json --sweep ground.height= --out out", 2, {"--sweep", "ground.height"}),
      bench("BenchReferenceUnknownPath", kSweep + "--reference nope.path=1 --out out", 2, {"--reference", "nope.path"}),
      bench("BenchSizeTiny", "scene.json --sweep ground.height=5,10 --size 1x1 --out out", 2, {"--size", "1x1"}),
      bench("BenchFramesZero", "scene.json --sweep ground.height=5,10 --frames 0 --out out", 2, {"--frames", "0"}),
      bench("BenchNoOut", "scene.json --sweep ground.height=5,10", 2, {"--out"}),
      bench("BenchCameraPathMissing", kSweep + "--camera-path nope --out out", 2, {"nope"}),
      bench("BenchSceneMissing", "nothere.json --sweep ground.height=5,10 --out out", 2, {"nothere.json"}),
      bench("BenchSceneNested70000Deep", kSweep + "--out out", 2, {"scene.json", "nested deeper than"}, nested_json(70'000)),
      bench("BenchOutIsTheScene", kSweep + "--out scene.json", 1, {"scene.json"}),
      bench("BenchOutUnderAFile", kSweep + "--out scene.json/results", 1, {"scene.json/results"}),
      bench("BenchOutUnwritable", kSweep + "--out /proc/sylva_hostile", 1, {"/proc/sylva_hostile"}),
      // --suite species with the user's files (issue 16): a junk species file fails its load and
      // forest rows naming it (exit 1), a grammar that would explode is left out of the grammar
      // rows; the shipped species and the pillar still measure.
      {.name = "BenchSpeciesSuiteJunkSpeciesAndExplodingGrammar",
       .tool = Tool::kBench,
       .files = {{"junk.json", [] { return junk(2000); }},
                 {"plants.json", [] {
                    return std::string(R"({"species": [)"
                                       R"({"name": "boom", "grammar": "boom.lsys", "derivations": [30, 30], "size": [1, 1], "blocks": {"0": "oak_log"}, "biomes": {"plains": {"spacing": 5, "chance": 1}}},)"
                                       R"({"name": "pillar", "grammar": "pillar.lsys", "derivations": [3, 3], "size": [1, 1], "blocks": {"0": "glowstone"}, "biomes": {"plains": {"spacing": 5, "chance": 1}}}]})");
                  }},
                 {"boom.lsys", [] { return std::string("0 0 1\nU\nU > UUUUUUUUUU\n"); }},
                 {"pillar.lsys", [] { return std::string("0 0 1\nU\nU > UU\n"); }}},
       .args = "--suite species --size 32x18 --frames 1 --warmup 0 --set render.shadows.enabled=false "
               "--set vegetation.species_files.1.file=junk.json --set voxel.flora.species_file=plants.json --out out",
       .exit_code = 1,
       .words = {"vegetation.species_files.0.file", "junk.json:1:", "junk.json: vegetation.species_files: no species left",
                 "species[0].derivations: boom.lsys:1", "left out",
                 "grammar: pillar (pillar.lsys #0) plants=1000"}},
  };
}

}  // namespace sylva::hostile
