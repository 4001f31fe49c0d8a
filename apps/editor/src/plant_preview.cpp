#include "plant_preview.hpp"

#include <sylva/core/atomic_file.hpp>

#if SYLVA_EDITOR_PLANT_PREVIEW
#include <sylva/voxel/palette_file.hpp>
#include <sylva/voxel/species.hpp>
#endif

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <optional>

namespace sylva::editor {

std::string PlantPreview::summary() const {
  if (!error.empty()) return fmt::format("{}: error: {}", title, error);
  std::string counts;
  for (const auto& [name, n] : block_counts) counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", name, n);
  return fmt::format("{}: {} blocks ({}), {} symbols, {} derivations", title, blocks.size(), counts, symbols, derivations);
}

#if !SYLVA_EDITOR_PLANT_PREVIEW

std::vector<std::string> preview_species(scene::Scene&) { return {}; }

PlantPreview build_plant_preview(scene::Scene&, const PlantPreviewSettings& settings) {
  PlantPreview p;
  p.title = settings.species;
  p.error = "the editor was built without the voxel module (no plant preview)";
  return p;
}

#else

namespace {

std::string param(scene::Scene& scene, const char* path) {
  auto v = scene.get_param(path);
  return v.ok() ? *v : std::string();
}

bool names_grammar_file(const std::string& species) { return species.ends_with(".lsys"); }

// The scene's palette (the standard one when it names none or its file fails: the module's policy).
std::optional<voxel::BlockPalette> scene_palette(scene::Scene& scene) {
  const std::string file = param(scene, "voxel.blocks.palette_file");
  if (file.empty()) return std::nullopt;
  std::vector<std::string> warnings;
  auto palette = voxel::load_palette(scene.document().resolve(file), warnings);
  if (!palette.ok()) return std::nullopt;
  return std::move(*palette);
}

// The species names in a table file, in file order, read as plain JSON (a species the table
// leaves out is still listed, so its error can be shown).
std::vector<std::string> names_in(const std::filesystem::path& file) {
  std::vector<std::string> out;
  auto text = read_file(file);
  if (!text.ok()) return out;
  const nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("species") || !j["species"].is_array()) return out;
  for (const nlohmann::json& s : j["species"]) out.push_back(s.is_object() && s.contains("name") && s["name"].is_string() ? s["name"].get<std::string>() : "");
  return out;
}

void grow(const voxel::LSystem& system, voxel::LSystemExecutorSettings growth, const PlantPreviewSettings& s, PlantPreview& p) {
  growth.min_derivations = growth.max_derivations = s.derivations;
  growth.angle_variation = s.angle_variation;
  auto model = voxel::generate_plant(system, growth, s.seed);
  if (!model.ok()) {
    p.error = model.error().message;
    return;
  }
  p.symbols = model->symbol_count;
  p.derivations = model->derivations;
  p.bounds_min = model->bounds_min;
  p.bounds_max = model->bounds_max;
  for (int o = 0; o < voxel::kPlantOutputs; ++o) {
    const std::string& block = p.output_blocks[static_cast<std::size_t>(o)];
    if (block.empty()) continue;
    for (const voxel::PlantPart& part : model->outputs[static_cast<std::size_t>(o)]) {
      p.blocks.push_back({part.position, part.size, o});
      ++p.block_counts[block];
    }
  }
}

}  // namespace

std::vector<std::string> preview_species(scene::Scene& scene) {
  if (!scene.document().has_module("voxel")) return {};
  const std::string file = param(scene, "voxel.flora.species_file");
  if (!file.empty()) return names_in(scene.document().resolve(file));
  std::vector<std::string> out;
  auto table = voxel::builtin_species_table();
  if (table.ok()) {
    for (const voxel::SpeciesDef& d : table->species) out.push_back(d.name);
  }
  return out;
}

PlantPreview build_plant_preview(scene::Scene& scene, const PlantPreviewSettings& settings) {
  PlantPreview p;
  if (Status valid = validate_params(settings, "preview"); !valid.ok()) {
    p.title = settings.species;
    p.error = valid.error().message;
    return p;
  }
  if (names_grammar_file(settings.species)) {
    const std::filesystem::path file = scene.document().resolve(settings.species);
    p.title = settings.species;
    auto systems = voxel::load_lsystems(file);
    if (!systems.ok()) {
      p.error = systems.error().message;
      return p;
    }
    if (settings.system >= static_cast<int>(systems->size())) {
      p.error = fmt::format("{}: no system {} (the file holds {})", file.string(), settings.system, systems->size());
      return p;
    }
    for (int o = 0; o < voxel::kPlantOutputs; ++o) p.output_blocks[static_cast<std::size_t>(o)] = fmt::format("output {}", o);
    grow((*systems)[static_cast<std::size_t>(settings.system)], {}, settings, p);
    return p;
  }
  if (!scene.document().has_module("voxel")) {
    p.title = settings.species;
    p.error = "the scene has no voxel section (name a .lsys file instead)";
    return p;
  }
  const std::optional<voxel::BlockPalette> user_palette = scene_palette(scene);
  const voxel::BlockPalette& palette = user_palette ? *user_palette : voxel::BlockPalette::standard();
  const std::string file = param(scene, "voxel.flora.species_file");
  p.title = fmt::format("{} ({})", settings.species, file.empty() ? "shipped species" : file);
  std::vector<std::string> warnings;
  auto table = file.empty() ? voxel::builtin_species_table(palette)
                            : voxel::load_species_table(scene.document().resolve(file), palette, warnings);
  if (!table.ok()) {
    p.error = table.error().message;
    return p;
  }
  if (auto index = table->find(settings.species)) {
    const voxel::SpeciesDef& def = table->species[*index];
    for (int o = 0; o < voxel::kPlantOutputs; ++o) {
      const voxel::BlockId id = def.blocks[static_cast<std::size_t>(o)];
      if (id != voxel::kAir) p.output_blocks[static_cast<std::size_t>(o)] = palette[id].name;
    }
    grow(def.lsystem, def.growth, settings, p);
    return p;
  }
  // Left out of the table: its own error (the messages name "species[i]").
  const std::vector<std::string> names = file.empty() ? std::vector<std::string>{} : names_in(scene.document().resolve(file));
  for (std::size_t i = 0; i < names.size() && p.error.empty(); ++i) {
    if (names[i] != settings.species) continue;
    for (const Error& e : table->rejected) {
      if (e.message.find(fmt::format("species[{}]", i)) != std::string::npos) p.error = e.message;
    }
  }
  if (p.error.empty()) p.error = fmt::format("no species \"{}\" in {}", settings.species, file.empty() ? "the shipped species" : file);
  return p;
}

#endif

}  // namespace sylva::editor
