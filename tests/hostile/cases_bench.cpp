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
  };
}

}  // namespace sylva::hostile
