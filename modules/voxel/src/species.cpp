// Species tables (species.hpp): the scalar keys of a species go through the params reflection
// (core params_json), so types, ranges and unknown keys get the same path-named messages as a
// scene file; "blocks" and "biomes" are objects keyed by output digit and biome name, read here.

#include <sylva/voxel/species.hpp>

#include "embedded_data.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/params_json.hpp>

#include <fmt/format.h>
#include <glm/vec2.hpp>

#include <algorithm>
#include <system_error>

namespace sylva::voxel {
namespace {

namespace fs = std::filesystem;

// Everything of a species but "blocks" and "biomes".
struct SpeciesHead {
  std::string name;
  std::string grammar;
  int system = 0;
  glm::ivec2 derivations{2, 4};
  glm::vec2 size{0.6f, 1.0f};
  float angle_variation = 0.2f;

  template <class V>
  void visit(V& v) {
    v(name, "name", {.max = 64, .help = "Species name (unique in the table)"});
    v(grammar, "grammar", {.max = 4096, .help = "L-system file in the seed's format, relative to the species file (seed 004 §4.5.1)"});
    v(system, "system", {.min = 0, .max = 1023, .help = "0-based index of the system in the grammar file"});
    v(derivations, "derivations", {.min = 0, .max = 32, .help = "Fewest and most derivation steps: the growth stages (seed 004 §4.6.1)"});
    v(size, "size", {.min = 0.01, .max = 16.0, .unit = "blocks", .help = "Start block size at the fewest and the most derivations (seed 004 §4.6.1)"});
    v(angle_variation, "angle_variation", {.min = 0.0, .max = 1.0, .help = "Turn jitter as a fraction of the grammar's angle (seed 004 §4.5.4, default 0.2)"});
  }
};

struct HabitatJson {
  int spacing = 8;
  float chance = 0.5f;

  template <class V>
  void visit(V& v) {
    v(spacing, "spacing", {.min = 1, .max = 4096, .unit = "blocks", .help = "Cell size of the jittered placement grid"});
    v(chance, "chance", {.min = 0.0, .max = 1.0, .help = "Chance that a grid cell holds a plant (times flora_density)"});
  }
};

Error fail(ErrorCode code, std::string_view source, std::string_view what) {
  return make_error(code, fmt::format("{}: {}", source, what));
}

std::string biome_names() {
  std::string out;
  for (const auto& n : enum_names(Biome{})) out += fmt::format("{}{}", out.empty() ? "" : ", ", n.name);
  return out;
}

// One species entry; an error leaves it out of the table.
Result<SpeciesDef> parse_species(const nlohmann::json& entry, const std::string& path, std::string_view source,
                                 const fs::path& directory, GrammarReader reader, const BlockPalette& palette,
                                 std::vector<std::string>& warnings, const ExpansionLimits& limits) {
  if (!entry.is_object()) return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}: must be an object", path));
  for (const char* key : {"name", "grammar"}) {
    if (!entry.contains(key)) return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}.{}: missing", path, key));
  }
  nlohmann::json head_json = entry;
  head_json.erase("blocks");
  head_json.erase("biomes");
  SpeciesHead head;
  std::vector<std::string> local;
  Status s = params_from_json(head, head_json, local, path);
  for (const std::string& w : local) warnings.push_back(fmt::format("{}: {}", source, w));
  if (!s.ok()) return fail(s.error().code, source, s.error().message);
  if (head.name.empty()) return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}.name: empty", path));
  if (head.derivations.x > head.derivations.y) {
    return fail(ErrorCode::kInvalidArgument, source,
                fmt::format("{}.derivations: the fewest ({}) is above the most ({})", path, head.derivations.x, head.derivations.y));
  }

  SpeciesDef def;
  def.name = head.name;
  def.grammar = head.grammar;
  def.system = head.system;
  def.growth.min_derivations = head.derivations.x;
  def.growth.max_derivations = head.derivations.y;
  def.growth.size_at_min = head.size.x;
  def.growth.size_at_max = head.size.y;
  def.growth.angle_variation = head.angle_variation;
  def.growth.limits = limits;

  auto systems = reader(directory, head.grammar);
  if (!systems.ok()) return fail(systems.error().code, source, fmt::format("{}.grammar: {}", path, systems.error().message));
  if (static_cast<std::size_t>(head.system) >= systems->size()) {
    return fail(ErrorCode::kNotFound, source,
                fmt::format("{}.system: {} holds {} system(s), no #{}", path, head.grammar, systems->size(), head.system));
  }
  def.lsystem = std::move((*systems)[static_cast<std::size_t>(head.system)]);

  // Limits before anything is derived (seed §4.7 caches every variant of every species).
  const auto [symbols, parts] = worst_case_growth(def.lsystem, def.growth.max_derivations);
  def.worst_symbols = symbols;
  def.worst_parts = parts;
  if (symbols > static_cast<double>(limits.max_symbols)) {
    return fail(ErrorCode::kLimit, source,
                fmt::format("{}.derivations: {} may grow to {:.3g} symbols in {} derivations, above the limit of {}; lower the most derivations",
                            path, def.lsystem.where(), symbols, def.growth.max_derivations, limits.max_symbols));
  }
  if (parts > static_cast<double>(limits.max_parts)) {
    return fail(ErrorCode::kLimit, source,
                fmt::format("{}.derivations: {} may lay {:.3g} blocks in {} derivations, above the limit of {} a plant; lower the most derivations",
                            path, def.lsystem.where(), parts, def.growth.max_derivations, limits.max_parts));
  }

  // Output arrays -> blocks (seed §4.5.4).
  def.blocks.fill(kAir);
  const auto blocks = entry.find("blocks");
  if (blocks == entry.end() || !blocks->is_object()) {
    return fail(ErrorCode::kInvalidArgument, source, fmt::format(R"({}.blocks: must be an object of outputs "0"-"9" to block names)", path));
  }
  for (const auto& [key, value] : blocks->items()) {
    if (key.size() != 1 || key[0] < '0' || key[0] > '9') {
      return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}.blocks.{}: not an output (0-9)", path, key));
    }
    if (!value.is_string()) return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}.blocks.{}: must be a block name", path, key));
    const std::string name = value.get<std::string>();
    auto id = palette.find(name);
    if (!id.ok() || *id == kAir) {
      return fail(ErrorCode::kNotFound, source, fmt::format("{}.blocks.{}: no block '{}' in the palette", path, key, name.substr(0, 64)));
    }
    def.blocks[static_cast<std::size_t>(key[0] - '0')] = *id;
  }
  // Outputs the grammar switches to (output 0 is where every plant starts) but that lay nothing.
  std::array<bool, kPlantOutputs> used{};
  used[0] = true;
  auto mark = [&used](std::string_view text) {
    for (char c : text) {
      if (c >= '0' && c <= '9') used[static_cast<std::size_t>(c - '0')] = true;
    }
  };
  mark(def.lsystem.axiom);
  for (const LSystemRule& r : def.lsystem.rules) mark(r.production);
  for (int o = 0; o < kPlantOutputs; ++o) {
    if (used[static_cast<std::size_t>(o)] && def.blocks[static_cast<std::size_t>(o)] == kAir) {
      warnings.push_back(fmt::format("{}: {}.blocks.{}: {} lays blocks on output {} but it has no block; they are left out", source,
                                     path, o, def.lsystem.where(), o));
    }
  }

  // Where it grows.
  if (const auto biomes = entry.find("biomes"); biomes != entry.end()) {
    if (!biomes->is_object()) {
      return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}.biomes: must be an object of biome names", path));
    }
    for (const auto& [key, value] : biomes->items()) {
      const std::string here = fmt::format("{}.biomes.{}", path, key);
      const auto names = enum_names(Biome{});
      const std::string& biome = key;  // clang 15 cannot capture a structured binding
      const auto it = std::find_if(names.begin(), names.end(), [&biome](const auto& n) { return biome == n.name; });
      if (it == names.end()) {
        return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}: no such biome (one of {})", here, biome_names()));
      }
      if (!value.is_object()) return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}: must be an object (spacing, chance)", here));
      HabitatJson h;
      s = params_from_json(h, value, local, here);
      for (const std::string& w : local) warnings.push_back(fmt::format("{}: {}", source, w));
      local.clear();
      if (!s.ok()) return fail(s.error().code, source, s.error().message);
      def.habitats.push_back({it->value, h.spacing, h.chance});
    }
  }
  return def;
}

}  // namespace

std::optional<SpeciesIndex> SpeciesTable::find(std::string_view name) const {
  for (std::size_t i = 0; i < species.size(); ++i) {
    if (species[i].name == name) return static_cast<SpeciesIndex>(i);
  }
  return std::nullopt;
}

std::pair<double, double> worst_case_growth(const LSystem& system, int derivations) {
  // counts[c]: occurrences of symbol c; rows[l]: per symbol, the most any rule of letter l writes.
  std::array<double, 128> counts{};
  for (char c : system.axiom) counts[static_cast<unsigned char>(c) & 127u] += 1.0;
  std::vector<std::array<double, 128>> rows(128);
  std::array<bool, 128> has_rules{};
  for (const LSystemRule& r : system.rules) {
    const std::size_t l = static_cast<unsigned char>(r.letter) & 127u;
    std::array<double, 128> one{};
    for (char c : r.production) one[static_cast<unsigned char>(c) & 127u] += 1.0;
    for (std::size_t c = 0; c < 128; ++c) rows[l][c] = std::max(rows[l][c], one[c]);
    has_rules[l] = true;
  }
  auto total = [](const std::array<double, 128>& a) {
    double t = 0.0;
    for (double v : a) t += v;
    return t;
  };
  auto laid = [](const std::array<double, 128>& a) { return a['U'] + a['u'] + a['F'] + a['f']; };
  double symbols = total(counts);
  double parts = laid(counts);
  for (int d = 0; d < derivations && symbols < 1e30; ++d) {
    std::array<double, 128> next{};
    for (std::size_t l = 0; l < 128; ++l) {
      if (counts[l] == 0.0) continue;
      if (!has_rules[l]) {
        next[l] += counts[l];
        continue;
      }
      for (std::size_t c = 0; c < 128; ++c) next[c] += counts[l] * rows[l][c];
    }
    counts = next;
    symbols = std::max(symbols, total(counts));  // derive() caps every step, not only the last
    parts = std::max(parts, laid(counts));  // a plant may take fewer derivations
  }
  return {symbols, parts};
}

Result<SpeciesTable> parse_species_table(std::string_view text, std::string_view source, const fs::path& directory,
                                         GrammarReader reader, const BlockPalette& palette,
                                         std::vector<std::string>& warnings, const ExpansionLimits& limits) {
  Result<nlohmann::json> json = parse_json_text(text, source);
  if (!json.ok()) return json.error();
  if (!json->is_object()) return fail(ErrorCode::kInvalidArgument, source, R"(must be a JSON object {"species": [...]})");
  for (const auto& [key, value] : json->items()) {
    (void)value;
    if (key != "species") warnings.push_back(fmt::format("{}: {}: unknown key (ignored)", source, key));
  }
  const auto list = json->find("species");
  if (list == json->end() || !list->is_array()) {
    return fail(ErrorCode::kInvalidArgument, source, "species: missing or not an array of species");
  }
  if (list->size() > kMaxSpecies) {
    return fail(ErrorCode::kLimit, source, fmt::format("species: {} entries, above the limit of {}", list->size(), kMaxSpecies));
  }
  SpeciesTable table;
  table.source = std::string(source);
  table.palette = &palette;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string path = fmt::format("species[{}]", i);
    auto def = parse_species((*list)[i], path, source, directory, reader, palette, warnings, limits);
    if (def.ok() && table.find(def->name)) {
      def = fail(ErrorCode::kInvalidArgument, source, fmt::format("{}.name: '{}' is already a species", path, def->name));
    }
    if (!def.ok()) {
      table.rejected.push_back(def.error());
      continue;
    }
    table.species.push_back(std::move(*def));
  }
  return table;
}

Result<std::vector<LSystem>> read_grammar_file(const fs::path& directory, std::string_view relative) {
  if (relative.empty()) return make_error(ErrorCode::kInvalidArgument, "empty grammar path");
  const fs::path path = fs::path(relative).is_absolute() ? fs::path(relative) : directory / fs::path(relative);
  std::error_code ec;
  if (!fs::exists(path, ec)) return make_error(ErrorCode::kNotFound, fmt::format("{}: no such file", relative));
  if (!fs::is_regular_file(path, ec)) return make_error(ErrorCode::kIo, fmt::format("{}: not a file", relative));
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec || bytes > kMaxSpeciesFileBytes) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: {} bytes, above the limit of {} MiB", relative, bytes, kMaxSpeciesFileBytes >> 20));
  }
  Result<std::string> text = read_file(path);
  if (!text.ok()) return text.error();
  return parse_lsystems(*text, relative);
}

Result<std::vector<LSystem>> read_builtin_grammar(const fs::path&, std::string_view relative) {
  return load_builtin_lsystems(relative);
}

Result<SpeciesTable> load_species_table(const fs::path& path, const BlockPalette& palette, std::vector<std::string>& warnings,
                                        const ExpansionLimits& limits) {
  const std::string source = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) return fail(ErrorCode::kNotFound, source, "no such file");
  if (!fs::is_regular_file(path, ec)) return fail(ErrorCode::kIo, source, "not a file");
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec || bytes > kMaxSpeciesFileBytes) {
    return fail(ErrorCode::kLimit, source, fmt::format("{} bytes, above the limit of {} MiB", bytes, kMaxSpeciesFileBytes >> 20));
  }
  Result<std::string> text = read_file(path);
  if (!text.ok()) return text.error();
  return parse_species_table(*text, source, path.parent_path(), &read_grammar_file, palette, warnings, limits);
}

Result<SpeciesTable> builtin_species_table(const BlockPalette& palette) {
  constexpr std::string_view kFile = "species.json";
  const auto text = detail::embedded_file(kFile);
  if (!text) return make_error(ErrorCode::kNotFound, "no built-in species.json");
  std::vector<std::string> warnings;
  return parse_species_table(*text, kFile, {}, &read_builtin_grammar, palette, warnings);
}

}  // namespace sylva::voxel
