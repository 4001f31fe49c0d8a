// OBJT tree models (modules/vegetation objt): text -> model, which must pass validate() and
// survive format_objt -> parse_objt (what the editor and bake tools write back).
#include "support/fuzz_support.hpp"

#include <sylva/vegetation/objt.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::vegetation;
  ObjtReadOptions options;
  options.source_name = "fuzz.objt";
  auto model = parse_objt(sylva::fuzz::as_text(data, size), options);
  if (!model.ok()) {
    sylva::fuzz::require_message(model.error());
    return 0;
  }
  const sylva::Status valid = validate(*model);
  sylva::fuzz::require(valid.ok(), valid.ok() ? "" : "a parsed model fails validate(): " + valid.error().message);
  options.source_name = "formatted.objt";
  auto again = parse_objt(format_objt(*model), options);
  sylva::fuzz::require(again.ok(), again.ok() ? "" : "a formatted model does not parse: " + again.error().message);
  return 0;
}
