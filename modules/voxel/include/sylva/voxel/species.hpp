#pragma once
// The plant species of a voxel world as data (issue #16; seed 004 §4.5.4, §4.6.1, §4.7): a JSON
// file lists per species its grammar (a `.lsys` file in the seed's format, §4.5.1), the growth
// range (derivations and start block size, §4.6.1), the block each output array 0-9 lays
// (§4.5.4: "textures are defined in the procedural generator, per array") and where it grows
// (biome, grid spacing and chance). The shipped species are such a file (data/species.json, with
// the shipped grammars), embedded into the binary like the grammars and read by the same code as
// a user's file: nothing about a species is compiled in.
//
//   {"species": [
//     {"name": "acacia", "grammar": "acacia.lsys", "system": 0,
//      "derivations": [5, 7], "size": [1.0, 1.2], "angle_variation": 0.2,
//      "blocks": {"0": "acacia_log", "1": "acacia_leaves"},
//      "biomes": {"savanna": {"spacing": 14, "chance": 0.4}}}]}
//
// "grammar" is relative to the JSON file; "system" is the 0-based index of the system in it (the
// seed's format has no names, a file holds several systems one after another). An output without
// a block lays nothing (a warning when the grammar switches to it). Numbers are checked through
// the params reflection (messages start with the JSON path, e.g. "species[2].derivations").
//
// Errors and what is left out: a file that cannot be read or is not a species table fails as a
// whole (the message names the file and, for malformed JSON, line:column). A species with a bad
// entry (unknown block or biome, a grammar that does not parse, names a missing system, or may
// grow past the limits) is left out and its error, naming the file, the JSON path (e.g.
// "species[2].blocks.3") or the grammar's file:line:column, goes to `rejected`; the caller picks
// the policy (the scene warns and keeps the others, the tests and the fuzz target require none).
//
// Limits are checked before anything is derived: the worst case over the stochastic rules of the
// derived length and of the blocks laid at the most derivations (each letter rewritten by the
// element-wise largest of its rules) must stay within ExpansionLimits (2^21 symbols, 200 000
// blocks a plant), so a grammar that would explode is refused with the numbers, never expanded.

#include <sylva/core/result.hpp>
#include <sylva/voxel/block.hpp>
#include <sylva/voxel/flora.hpp>
#include <sylva/voxel/lsystem.hpp>
#include <sylva/voxel/plant.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::voxel {

// Most species one table may hold (PlantInstance::species is 16 bits).
inline constexpr std::size_t kMaxSpecies = 1024;
// Largest species JSON and grammar file read.
inline constexpr std::uintmax_t kMaxSpeciesFileBytes = std::uintmax_t{4} << 20;

// Where a species grows: one candidate per cell of a jittered grid of `spacing` blocks, kept with
// probability `chance` (times WorldGenSettings::flora_density).
struct SpeciesHabitat {
  Biome biome = Biome::kPlains;
  int spacing = 8;
  float chance = 0.5f;
};

struct SpeciesDef {
  std::string name;
  std::string grammar;  // as written in the file
  int system = 0;
  LSystem lsystem;
  // min/max_derivations, size_at_min/max and angle_variation from the file.
  LSystemExecutorSettings growth;
  std::array<BlockId, kPlantOutputs> blocks{};  // kAir: the output lays nothing
  std::vector<SpeciesHabitat> habitats;         // in file order

  // Upper bounds of one plant at max_derivations (see above).
  double worst_symbols = 0.0;
  double worst_parts = 0.0;
};

struct SpeciesTable {
  std::string source;  // the file (or "species.json" for the shipped table)
  std::vector<SpeciesDef> species;
  std::vector<Error> rejected;          // species left out, one error each
  const BlockPalette* palette = nullptr;  // the block ids above are this palette's

  std::optional<SpeciesIndex> find(std::string_view name) const;
};

// Reads the grammar file `relative` (as written in the species file); errors name it.
using GrammarReader = Result<std::vector<LSystem>> (*)(const std::filesystem::path& directory, std::string_view relative);

// Parses a species table. `source` names the JSON in messages; grammars are read through
// `reader` relative to `directory`. `warnings` gets the unknown keys and unused outputs.
Result<SpeciesTable> parse_species_table(std::string_view text, std::string_view source, const std::filesystem::path& directory,
                                         GrammarReader reader, const BlockPalette& palette,
                                         std::vector<std::string>& warnings, const ExpansionLimits& limits = {});
// A file on disk (size checked before reading); grammars relative to its folder.
Result<SpeciesTable> load_species_table(const std::filesystem::path& path, const BlockPalette& palette,
                                        std::vector<std::string>& warnings, const ExpansionLimits& limits = {});
// The shipped table (data/species.json with the shipped grammars, both embedded). With another
// palette than the standard one, species whose blocks it lacks are in `rejected`.
Result<SpeciesTable> builtin_species_table(const BlockPalette& palette = BlockPalette::standard());

// Reads a grammar from disk (size checked first); errors name `relative`.
Result<std::vector<LSystem>> read_grammar_file(const std::filesystem::path& directory, std::string_view relative);
// Reads one of the embedded grammar files (data/*.lsys) by name.
Result<std::vector<LSystem>> read_builtin_grammar(const std::filesystem::path& directory, std::string_view relative);

// Worst case over the stochastic choices of (derived length, blocks laid) after `derivations`
// steps, computed on letter counts without deriving.
std::pair<double, double> worst_case_growth(const LSystem& system, int derivations);

}  // namespace sylva::voxel
