// Species files (modules/vegetation species_file): JSON text -> species. What parses must be a
// tree the forest can take: its model passes validate() and fits the size limit; every error
// carries a message. Relative model paths resolve against the shipped scenes/species folder
// (SYLVA_FUZZ_SPECIES_DIR), so the seeds' OBJT references load real files; nothing is written.
#include "support/fuzz_support.hpp"

#include <sylva/vegetation/species_file.hpp>

#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::vegetation;
  std::vector<std::string> warnings;
  auto species = parse_species(sylva::fuzz::as_text(data, size), SYLVA_FUZZ_SPECIES_DIR, "fuzz.json", warnings);
  for (const std::string& w : warnings) sylva::fuzz::require(!w.empty(), "an empty warning");
  if (!species.ok()) {
    sylva::fuzz::require_message(species.error());
    return 0;
  }
  const sylva::Status valid = validate(species->model);
  sylva::fuzz::require(valid.ok(), valid.ok() ? "" : "a loaded species fails validate(): " + valid.error().message);
  return 0;
}
