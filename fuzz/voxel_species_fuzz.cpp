// Voxel species tables (modules/voxel species.hpp): JSON text -> species, grammars read from the
// shipped ones (data/*.lsys, embedded: nothing is read from disk) under small expansion limits.
// What parses must keep its promises: every species within the limits by its worst case, blocks
// from the palette, and real plants no larger than that worst case (the bound is checked against
// a derivation of each species, so a wrong bound is a crash here, not a memory blow-up later).
#include "support/fuzz_support.hpp"

#include <sylva/voxel/species.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::voxel;
  ExpansionLimits limits;
  limits.max_symbols = std::size_t{1} << 15;
  limits.max_parts = 4096;
  limits.max_depth = 256;
  const BlockPalette& palette = BlockPalette::standard();
  std::vector<std::string> warnings;
  auto table = parse_species_table(sylva::fuzz::as_text(data, size), "fuzz.json", {}, &read_builtin_grammar, palette, warnings, limits);
  for (const std::string& w : warnings) sylva::fuzz::require(!w.empty(), "an empty warning");
  if (!table.ok()) {
    sylva::fuzz::require_message(table.error());
    return 0;
  }
  for (const sylva::Error& e : table->rejected) sylva::fuzz::require_message(e);
  sylva::fuzz::require(table->species.size() <= kMaxSpecies, "more species than kMaxSpecies");
  // A few species are enough to reach every key; more only slows each input down.
  const std::size_t count = std::min<std::size_t>(table->species.size(), 3);
  for (std::size_t i = 0; i < count; ++i) {
    const SpeciesDef& def = table->species[i];
    sylva::fuzz::require(!def.name.empty(), "a species without a name");
    sylva::fuzz::require(def.worst_symbols <= static_cast<double>(limits.max_symbols) &&
                             def.worst_parts <= static_cast<double>(limits.max_parts),
                         "a species past the limits was accepted");
    for (BlockId b : def.blocks) sylva::fuzz::require(b < palette.size(), "a block id outside the palette");
    auto plant = generate_plant(def.lsystem, def.growth, 1);
    if (!plant.ok()) {
      sylva::fuzz::require_message(plant.error());
      continue;
    }
    sylva::fuzz::require(static_cast<double>(plant->symbol_count) <= def.worst_symbols &&
                             static_cast<double>(plant->part_count()) <= def.worst_parts,
                         fmt::format("{}: a plant of {} symbols and {} blocks beyond the worst case {} and {}", def.name,
                                     plant->symbol_count, plant->part_count(), def.worst_symbols, def.worst_parts));
  }
  return 0;
}
