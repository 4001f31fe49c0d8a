// Scene files (modules/scene SceneDocument): JSON text -> document -> validation -> saved text,
// which must load again (the editor saves every scene it opened).
#include "support/fuzz_support.hpp"

#include <sylva/scene/scene_document.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using sylva::scene::SceneDocument;
  std::vector<std::string> warnings;
  auto document = SceneDocument::from_text(sylva::fuzz::as_text(data, size), "fuzz.json", warnings);
  if (!document.ok()) {
    sylva::fuzz::require_message(document.error());
    return 0;
  }
  const sylva::Status valid = document->validate();
  if (!valid.ok()) sylva::fuzz::require_message(valid.error());
  std::vector<std::string> reload_warnings;
  auto reloaded = SceneDocument::from_text(document->to_text(), "saved.json", reload_warnings);
  sylva::fuzz::require(reloaded.ok(), reloaded.ok() ? "" : "a loaded scene saves to text that does not load: " +
                                                              reloaded.error().message);
  return 0;
}
