// Parameter overrides (modules/core params, `--set path=value` on every command line): each
// input line is one assignment applied to the default scene's registry, or a path to read back.
#include "support/fuzz_support.hpp"

#include <sylva/core/params.hpp>
#include <sylva/scene/scene_document.hpp>

namespace {

const sylva::scene::SceneDocument& default_document() {
  static const sylva::scene::SceneDocument document = [] {
    std::vector<std::string> warnings;
    auto parsed = sylva::scene::default_scene(warnings);
    sylva::fuzz::require(parsed.ok(), "the embedded default scene does not load");
    return std::move(*parsed);
  }();
  return document;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sylva::scene::SceneDocument document = default_document();
  const sylva::ParamRegistry params = document.params();
  std::vector<std::string> lines = sylva::fuzz::split_lines(sylva::fuzz::as_text(data, size));
  // A command line holds a handful of overrides; each unknown path costs a "did you mean" search
  // over every parameter name, so more lines would only slow the fuzzer down.
  lines.resize(std::min<std::size_t>(lines.size(), 8));
  for (const std::string& line : lines) {
    if (line.find('=') == std::string::npos) {
      auto value = params.get(line);
      if (!value.ok()) sylva::fuzz::require_message(value.error());
      continue;
    }
    auto assignment = sylva::parse_param_assignment(line);
    if (!assignment.ok()) {
      sylva::fuzz::require_message(assignment.error());
      continue;
    }
    const sylva::Status set = params.set(assignment->first, assignment->second);
    if (!set.ok()) {
      sylva::fuzz::require_message(set.error());
      continue;
    }
    // A value that was accepted reads back and is accepted again unchanged.
    auto read = params.get(assignment->first);
    sylva::fuzz::require(read.ok() && params.set(assignment->first, *read).ok(),
                         "an accepted value does not read back and set again: " + line);
  }
  const sylva::Status valid = document.validate();
  if (!valid.ok()) sylva::fuzz::require_message(valid.error());
  return 0;
}
