// Scene JSON files through sylva-player: broken syntax, lying versions, wrong types and values,
// nesting deep enough to overflow a recursive parser, junk, and paths that are not files.

#include "hostile_bytes.hpp"
#include "hostile_case.hpp"

namespace sylva::hostile {

namespace {
const std::string kRun = "scene.json --size 32x18 --frames 1";
InputFile scene(std::string bytes) {
  return {"scene.json", [bytes] { return bytes; }};
}
}  // namespace

std::vector<HostileCase> scene_file_cases() {
  return {
      {.name = "SceneTruncated", .files = {scene(truncated(ground_scene(), 40))}, .args = kRun,
       .words = {"scene.json:1:", "syntax error"}},
      {.name = "SceneBinaryJunk", .files = {{"scene.json", [] { return junk(300); }}}, .args = kRun,
       .words = {"scene.json:1:1", "syntax error"}},
      {.name = "SceneEmpty", .files = {scene("")}, .args = kRun, .words = {"scene.json", "unexpected end of input"}},
      // The issue's crash: 70,000 levels overflowed the loader's stack (a 140 KB file).
      {.name = "SceneNested70000Deep", .files = {{"scene.json", [] { return nested_json(70'000); }}}, .args = kRun,
       .words = {"scene.json:1:", "nested deeper than"}},
      {.name = "SceneNestedInsideASection",
       .files = {{"scene.json", [] { return R"({"sylva_scene": 1, "ground": {"noise": )" + nested_json(5'000) + "}}"; }}},
       .args = kRun, .words = {"scene.json:1:", "nested deeper than"}},
      {.name = "SceneNaNLiteral", .files = {scene(R"({"sylva_scene": 1, "ground": {"height": NaN}})")}, .args = kRun,
       .words = {"scene.json:1:", "syntax error"}},
      {.name = "SceneNumberOverflow", .files = {scene(R"({"sylva_scene": 1, "ground": {"height": 1e999}})")},
       .args = kRun, .words = {"scene.json", "1e999"}},
      {.name = "SceneWrongType", .files = {scene(R"({"sylva_scene": 1, "ground": {"resolution": "big"}})")},
       .args = kRun, .words = {"scene.json", "ground.resolution", "big"}},
      {.name = "SceneValueAboveRange", .files = {scene(R"({"sylva_scene": 1, "ground": {"resolution": 1000000000}})")},
       .args = kRun, .words = {"scene.json", "ground.resolution", "1000000000"}},
      {.name = "SceneNegativeSize", .files = {scene(R"({"sylva_scene": 1, "ground": {"size": -100.0}})")},
       .args = kRun, .words = {"scene.json", "ground.size"}},
      {.name = "SceneFutureVersion", .files = {scene(R"({"sylva_scene": 99})")}, .args = kRun,
       .words = {"scene.json", "sylva_scene", "99"}},
      {.name = "SceneNotAnObject", .files = {scene("[1, 2, 3]")}, .args = kRun, .words = {"scene.json"}},
      {.name = "SceneSectionNotAnObject", .files = {scene(R"({"sylva_scene": 1, "ground": 7})")}, .args = kRun,
       .words = {"scene.json", "ground"}},
      {.name = "SceneInvalidUtf8", .files = {scene("{\"sylva_scene\": 1, \"name\": \"\xff\xfe\"}")}, .args = kRun,
       .words = {"scene.json:1:", "UTF-8"}},
      {.name = "SceneCameraFarAway",
       .files = {scene(R"({"sylva_scene": 1, "camera": {"position": [1e300, 1e300, 1e300]}, "ground": {}})")},
       .args = kRun, .words = {"scene.json", "camera.position"}},
      {.name = "SceneIsAFolder", .files = {{"scene.json/", {}}}, .args = kRun, .words = {"scene.json", "is a folder"}},
      {.name = "SceneMissing", .args = "nothere.json --size 32x18 --frames 1", .words = {"nothere.json", "no such file"}},
  };
}

}  // namespace sylva::hostile
