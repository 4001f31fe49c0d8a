// Species files (species_file.hpp): the JSON is read through the params reflection (core
// params_json) wherever it can be, so types, ranges and unknown keys get the same messages as a
// scene file; only the two shapes of "model" are told apart here.

#include <sylva/vegetation/species_file.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/vegetation/objt.hpp>
#include <sylva/vegetation/textures.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <system_error>

namespace sylva::vegetation {
namespace {

namespace fs = std::filesystem;

// Rules for OBJT files without the Sylva extensions (objt.hpp defaults).
struct ObjtRules {
  float branch_radius = 0.03f;  // base radius / length
  float branch_taper = 0.2f;    // tip radius / base radius
  float leaf_width = 0.05f;     // [m]
  float leaf_length = 0.08f;    // [m]
  bool strict = false;

  template <class V>
  void visit(V& v) {
    v(branch_radius, "branch_radius", {.min = 0.0, .max = 1.0, .help = "Base radius of a branch without w, relative to its length"});
    v(branch_taper, "branch_taper", {.min = 0.0, .max = 1.0, .help = "Tip radius / base radius of a branch without w"});
    v(leaf_width, "leaf_width", {.min = 1e-4, .max = 10.0, .unit = "m", .help = "Width of a leaf without w"});
    v(leaf_length, "leaf_length", {.min = 1e-4, .max = 10.0, .unit = "m", .help = "Length of a leaf without w"});
    v(strict, "strict", {.help = "Refuse what the OBJT loader would repair with a warning"});
  }
};

// "leaf" and "bark": image paths relative to the species file (species_file.hpp).
struct LeafImageKeys {
  std::string color;
  std::string normal;
  std::string translucency;

  template <class V>
  void visit(V& v) {
    v(color, "color", {.max = 4096, .help = "Leaf colour with the outline in alpha (RGBA image)"});
    v(normal, "normal", {.max = 4096, .help = "Leaf normal map (RGB, A thickness)"});
    v(translucency, "translucency", {.max = 4096, .help = "Leaf transmittance intensity image"});
  }
};

struct BarkImageKeys {
  std::string color;
  std::string normal;

  template <class V>
  void visit(V& v) {
    v(color, "color", {.max = 4096, .help = "Bark colour image (RGB)"});
    v(normal, "normal", {.max = 4096, .help = "Bark normal map (RGB, A height)"});
  }
};

// Everything but "model".
struct SpeciesTop {
  std::string name;
  float units = 1.0f;
  ObjtRules objt;
  SpeciesPreset look = SpeciesPreset::kBroadleaf;
  std::uint32_t texture_seed = 1;
  glm::vec3 leaf_tint{1.0f};
  glm::vec3 bark_color{0.32f, 0.24f, 0.17f};
  LeafImageKeys leaf;
  BarkImageKeys bark;
  std::string season;

  template <class V>
  void visit(V& v) {
    v(name, "name", {.max = 64, .help = "Species name"});
    v(units, "units", {.min = 1e-6, .max = 1000.0, .unit = "m", .help = "Metres per model unit"});
    v(objt, "objt");
    v(look, "look", {.help = "Procedural textures: broadleaf, conifer, birch or shrub"});
    v(texture_seed, "texture_seed", {.min = 0.0, .max = 4294967295.0, .help = "Seed of the procedural textures"});
    v(leaf_tint, "leaf_tint", {.min = 0.0, .max = 4.0, .help = "Multiplies the seasonal leaf colour"});
    v(bark_color, "bark_color", {.min = 0.0, .max = 1.0, .help = "Linear albedo of the bark plates"});
    v(leaf, "leaf");
    v(bark, "bark");
    v(season, "season", {.max = 4096, .help = "Season colour image: one column, top = season 1 (seed §4.6)"});
  }
};

Error fail(ErrorCode code, std::string_view source, std::string_view what) {
  return make_error(code, fmt::format("{}: {}", source, what));
}

void add_warnings(std::vector<std::string>& out, std::vector<std::string>& local, std::string_view source) {
  for (const std::string& w : local) out.push_back(fmt::format("{}: {}", source, w));
  local.clear();
}

// "lod": thresholds only (the bake settings are the forest's: one bake per species and forest).
struct LodOverride {
  LodSettings lod;
  template <class V>
  void visit(V& v) {
    v(lod.v1, "v1", {.min = 0.0, .max = 1.0e7, .unit = "m", .help = "Distance where LOD0 turns into LOD1"});
    v(lod.v2, "v2", {.min = 0.0, .max = 1.0e7, .unit = "m", .help = "Distance where LOD1 turns into LOD2"});
    v(lod.s1, "s1", {.min = 0.0, .max = 1.0e5, .unit = "px", .help = "Projected height below which LOD1 is used"});
    v(lod.s2, "s2", {.min = 0.0, .max = 1.0e5, .unit = "px", .help = "Projected height below which LOD2 is used"});
  }
};

struct AnimationOverride {
  float wind_scale = 1.0f;
  template <class V>
  void visit(V& v) {
    v(wind_scale, "wind_scale", {.min = 0.0, .max = 100.0, .help = "Multiplies the forest's wind for this species"});
  }
};

// The species' "lod" and "animation" objects: only the keys given change the forest's values.
Result<SpeciesTuning> read_tuning(const nlohmann::json& json, std::string_view source, std::vector<std::string>& warnings) {
  SpeciesTuning tuning;
  std::vector<std::string> local;
  if (const auto it = json.find("lod"); it != json.end()) {
    if (!it->is_object()) return fail(ErrorCode::kInvalidArgument, source, "lod: must be an object (v1, v2, s1, s2)");
    LodOverride o;
    Status s = params_from_json(o, *it, local, "lod");
    add_warnings(warnings, local, source);
    if (!s.ok()) return fail(s.error().code, source, s.error().message);
    if (it->contains("v1")) tuning.v1 = o.lod.v1;
    if (it->contains("v2")) tuning.v2 = o.lod.v2;
    if (it->contains("s1")) tuning.s1 = o.lod.s1;
    if (it->contains("s2")) tuning.s2 = o.lod.s2;
  }
  if (const auto it = json.find("animation"); it != json.end()) {
    if (!it->is_object()) return fail(ErrorCode::kInvalidArgument, source, "animation: must be an object (wind_scale)");
    AnimationOverride o;
    Status s = params_from_json(o, *it, local, "animation");
    add_warnings(warnings, local, source);
    if (!s.ok()) return fail(s.error().code, source, s.error().message);
    tuning.wind_scale = o.wind_scale;
  }
  return tuning;
}

struct ObjtModel {
  std::string objt;
  template <class V>
  void visit(V& v) {
    v(objt, "objt", {.max = 4096, .help = "OBJT file, relative to the species file"});
  }
};

struct PresetModel {
  SpeciesPreset preset = SpeciesPreset::kBroadleaf;
  std::uint32_t seed = 1;
  template <class V>
  void visit(V& v) {
    v(preset, "preset", {.help = "Generator preset"});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Generator seed"});
  }
};

Result<TreeModel> load_objt_model(const nlohmann::json& model, const SpeciesTop& top, const fs::path& directory,
                                  std::string_view source, std::vector<std::string>& warnings) {
  ObjtModel om;
  std::vector<std::string> local;
  Status s = params_from_json(om, model, local, "model");
  add_warnings(warnings, local, source);
  if (!s.ok()) return fail(s.error().code, source, s.error().message);
  if (om.objt.empty()) return fail(ErrorCode::kInvalidArgument, source, "model.objt: empty path");
  const fs::path path = fs::path(om.objt).is_absolute() ? fs::path(om.objt) : directory / om.objt;
  std::error_code ec;
  if (!fs::exists(path, ec)) return fail(ErrorCode::kNotFound, source, fmt::format("model.objt: no such file {}", om.objt));
  if (!fs::is_regular_file(path, ec)) return fail(ErrorCode::kIo, source, fmt::format("model.objt: {} is not a file", om.objt));
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec || bytes > kMaxObjtFileBytes)
    return fail(ErrorCode::kLimit, source, fmt::format("model.objt: {} is {} bytes, above the {} MiB limit", om.objt, bytes, kMaxObjtFileBytes >> 20));
  Result<std::string> text = read_file(path);
  if (!text.ok()) return fail(text.error().code, source, fmt::format("model.objt: {}", text.error().message));
  ObjtReadOptions options;
  options.source_name = om.objt;
  options.strict = top.objt.strict;
  options.warnings = &local;
  options.default_radius_ratio = top.objt.branch_radius;
  options.default_taper = top.objt.branch_taper;
  // The leaf rule is in metres; the file's numbers are in its own units until scaled.
  options.default_leaf_width = top.objt.leaf_width / top.units;
  options.default_leaf_length = top.objt.leaf_length / top.units;
  Result<TreeModel> parsed = parse_objt(*text, options);
  add_warnings(warnings, local, source);
  if (!parsed.ok()) return fail(parsed.error().code, source, fmt::format("model.objt: {}", parsed.error().message));
  return parsed;
}

Result<TreeModel> generate_preset_model(const nlohmann::json& model, std::string_view source, std::vector<std::string>& warnings,
                                        SpeciesPreset& preset) {
  nlohmann::json head = model;
  head.erase("parameters");
  PresetModel pm;
  std::vector<std::string> local;
  Status s = params_from_json(pm, head, local, "model");
  add_warnings(warnings, local, source);
  if (!s.ok()) return fail(s.error().code, source, s.error().message);
  preset = pm.preset;
  TreeSpecies species = species_preset(pm.preset, pm.seed);
  if (const auto p = model.find("parameters"); p != model.end()) {
    if (!p->is_object()) return fail(ErrorCode::kInvalidArgument, source, "model.parameters: must be an object of generator parameters");
    s = params_from_json(species, *p, local, "model.parameters");
    add_warnings(warnings, local, source);
    if (!s.ok()) return fail(s.error().code, source, s.error().message);
  }
  Result<TreeModel> generated = generate_tree(species);
  if (!generated.ok()) return fail(generated.error().code, source, fmt::format("model.parameters: {}", generated.error().message));
  return generated;
}

// Images (species_file.hpp): what each key accepts.
enum class ImageRole { kLeafColor, kLeafNormal, kLeafTranslucency, kBarkColor, kBarkNormal, kSeason };

bool is_colour(ImageRole role) {
  return role == ImageRole::kLeafColor || role == ImageRole::kBarkColor || role == ImageRole::kSeason;
}

// IEC 61966-2-1 decoding.
float srgb_to_linear(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

Result<Image> read_species_image(const std::string& rel, ImageRole role, std::string_view key, const fs::path& directory,
                                 std::string_view source, std::vector<fs::path>& files) {
  if (rel.empty()) return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}: empty path", key));
  const fs::path path = fs::path(rel).is_absolute() ? fs::path(rel) : directory / rel;
  std::error_code ec;
  if (!fs::exists(path, ec)) return fail(ErrorCode::kNotFound, source, fmt::format("{}: no such file {}", key, rel));
  if (!fs::is_regular_file(path, ec)) return fail(ErrorCode::kIo, source, fmt::format("{}: {} is not a file", key, rel));
  ImageReadOptions options;
  options.max_side = kMaxSpeciesImageSide;
  options.max_bytes = static_cast<std::uint64_t>(kMaxSpeciesImageSide) * kMaxSpeciesImageSide * 4u * sizeof(float);
  options.allow_non_finite = false;
  Result<Image> read = read_image(path, options);
  if (!read.ok()) return fail(read.error().code, source, fmt::format("{}: {}", key, read.error().message));
  Image img = std::move(read).value();
  const int w = img.width(), h = img.height(), channels = img.channels();
  const std::string has = fmt::format("{} has {} channel{}", rel, channels, channels == 1 ? "" : "s");
  if (role == ImageRole::kSeason) {
    if (w != 1 && h != 1)
      return fail(ErrorCode::kInvalidArgument, source,
                  fmt::format("{}: {} is {}x{}; a season image is one column (1 x rows, top = season 1) or one row", key, rel, w, h));
  } else if (w < kMinSpeciesImageSide || h < kMinSpeciesImageSide) {
    return fail(ErrorCode::kLimit, source,
                fmt::format("{}: {} is {}x{}, below the {}x{} minimum", key, rel, w, h, kMinSpeciesImageSide, kMinSpeciesImageSide));
  }
  switch (role) {
    case ImageRole::kLeafColor:
      if (channels != 4)
        return fail(ErrorCode::kInvalidArgument, source,
                    fmt::format("{}: {}; a leaf colour image needs an alpha channel for the outline (RGBA)", key, has));
      break;
    case ImageRole::kLeafNormal:
    case ImageRole::kBarkNormal:
      if (channels < 3)
        return fail(ErrorCode::kInvalidArgument, source,
                    fmt::format("{}: {}; a normal map needs RGB (or RGBA)", key, has));
      break;
    case ImageRole::kBarkColor:
    case ImageRole::kSeason:
      if (channels < 3)
        return fail(ErrorCode::kInvalidArgument, source, fmt::format("{}: {}; a colour image needs RGB (or RGBA)", key, has));
      break;
    case ImageRole::kLeafTranslucency:
      break;
  }
  if (is_colour(role) && (img.format() == PixelFormat::kU8 || img.format() == PixelFormat::kU16)) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) img.at(x, y, c) = srgb_to_linear(img.at(x, y, c));
  }
  if (role == ImageRole::kLeafColor) {
    bool covered = false;
    for (int y = 0; y < h && !covered; ++y)
      for (int x = 0; x < w && !covered; ++x) covered = img.at(x, y, 3) > 0.5f;
    if (!covered)
      return fail(ErrorCode::kInvalidArgument, source,
                  fmt::format("{}: {} has no texel with alpha above 0.5 (the leaf outline is empty)", key, rel));
  }
  if (role == ImageRole::kSeason) {
    // One column, RGBA (presence 1 where the file has no alpha).
    const int rows = std::max(w, h);
    Image column(1, rows, 4, PixelFormat::kU8);
    for (int i = 0; i < rows; ++i)
      for (int c = 0; c < 4; ++c)
        column.at(0, i, c) = c < channels ? std::clamp(img.at(w == 1 ? 0 : i, w == 1 ? i : 0, c), 0.0f, 1.0f) : 1.0f;
    img = std::move(column);
  }
  files.push_back(path);
  return img;
}

Status read_species_images(const SpeciesTop& top, const nlohmann::json& rest, const fs::path& directory, std::string_view source,
                           std::vector<std::string>& warnings, SpeciesImages& out) {
  const auto read = [&](const std::string& rel, ImageRole role, std::string_view key, Image& into) -> Status {
    Result<Image> img = read_species_image(rel, role, key, directory, source, out.files);
    if (!img.ok()) return img.error();
    into = std::move(img).value();
    return ok_status();
  };
  if (rest.contains("leaf")) {
    if (top.leaf.color.empty())
      return fail(ErrorCode::kInvalidArgument, source, "leaf.color: missing (the leaf block needs a colour image with the outline in alpha)");
    SYLVA_TRY(read(top.leaf.color, ImageRole::kLeafColor, "leaf.color", out.leaf_color));
    if (!top.leaf.normal.empty()) SYLVA_TRY(read(top.leaf.normal, ImageRole::kLeafNormal, "leaf.normal", out.leaf_normal));
    if (!top.leaf.translucency.empty())
      SYLVA_TRY(read(top.leaf.translucency, ImageRole::kLeafTranslucency, "leaf.translucency", out.leaf_translucency));
  }
  if (rest.contains("bark")) {
    if (top.bark.color.empty()) return fail(ErrorCode::kInvalidArgument, source, "bark.color: missing (the bark block needs a colour image)");
    SYLVA_TRY(read(top.bark.color, ImageRole::kBarkColor, "bark.color", out.bark_color));
    if (!top.bark.normal.empty()) SYLVA_TRY(read(top.bark.normal, ImageRole::kBarkNormal, "bark.normal", out.bark_normal));
    if (rest.contains("bark_color")) warnings.push_back(fmt::format("{}: bark_color: ignored, bark.color gives the bark", source));
  }
  if (rest.contains("season")) SYLVA_TRY(read(top.season, ImageRole::kSeason, "season", out.season));
  return ok_status();
}

}  // namespace

Result<SpeciesFile> parse_species(std::string_view text, const fs::path& directory, std::string_view source,
                                  std::vector<std::string>& warnings) {
  Result<nlohmann::json> json = parse_json_text(text, source);
  if (!json.ok()) return json.error();
  if (!json->is_object()) return fail(ErrorCode::kInvalidArgument, source, "the species must be a JSON object");
  const auto model = json->find("model");
  if (model == json->end())
    return fail(ErrorCode::kInvalidArgument, source, R"(model: missing (an object with "objt" or "preset"))");
  if (!model->is_object() || model->contains("objt") == model->contains("preset"))
    return fail(ErrorCode::kInvalidArgument, source, R"(model: must be an object with either "objt" or "preset")");

  nlohmann::json rest = *json;
  rest.erase("model");
  Result<SpeciesTuning> tuning = read_tuning(rest, source, warnings);
  if (!tuning.ok()) return tuning.error();
  rest.erase("lod");
  rest.erase("animation");
  SpeciesTop top;
  std::vector<std::string> local;
  Status s = params_from_json(top, rest, local);
  add_warnings(warnings, local, source);
  if (!s.ok()) return fail(s.error().code, source, s.error().message);

  SpeciesFile out;
  const bool objt = model->contains("objt");
  SpeciesPreset preset = SpeciesPreset::kBroadleaf;
  Result<TreeModel> tree = objt ? load_objt_model(*model, top, directory, source, warnings)
                                : generate_preset_model(*model, source, warnings, preset);
  if (!tree.ok()) return tree.error();
  out.model = std::move(tree).value();
  if (out.model.branches.empty()) return fail(ErrorCode::kInvalidArgument, source, "model: the tree has no branches");
  if (top.units != 1.0f) scale_tree_model(out.model, top.units);
  const glm::vec3 extent = out.model.bounds_max() - out.model.bounds_min();
  const float largest = std::max({extent.x, extent.y, extent.z});
  if (!(largest <= kMaxTreeExtent))
    return fail(ErrorCode::kLimit, source,
                fmt::format("units: the tree is {:.4g} m across after scaling by {}, above the {} m limit", largest, top.units, kMaxTreeExtent));
  if (Status v = validate(out.model); !v.ok()) return fail(v.error().code, source, fmt::format("model: {}", v.error().message));

  out.name = !top.name.empty() ? top.name : fs::path(std::string(source)).stem().string();
  // A preset's own textures unless the file picks another look.
  out.look = objt || rest.contains("look") ? top.look : preset;
  out.tuning = *tuning;
  out.texture_seed = top.texture_seed;
  out.leaf_tint = top.leaf_tint;
  if (rest.contains("bark_color")) out.bark_color = top.bark_color;
  SYLVA_TRY(read_species_images(top, rest, directory, source, warnings, out.images));
  if (objt) out.objt_file = directory / model->at("objt").get<std::string>();  // a string: loaded above
  return out;
}

Result<SpeciesFile> load_species_file(const fs::path& file, std::vector<std::string>& warnings) {
  const std::string source = file.filename().string();
  std::error_code ec;
  if (!fs::exists(file, ec)) return fail(ErrorCode::kNotFound, file.string(), "no such file");
  const std::uintmax_t bytes = fs::file_size(file, ec);
  if (ec) return fail(ErrorCode::kIo, file.string(), ec.message());
  if (bytes > kMaxSpeciesFileBytes)
    return fail(ErrorCode::kLimit, source, fmt::format("{} bytes, above the {} MiB limit of a species file", bytes, kMaxSpeciesFileBytes >> 20));
  Result<std::string> text = read_file(file);
  if (!text.ok()) return text.error();
  return parse_species(*text, file.parent_path(), source, warnings);
}

Result<TreeTextureSet> make_species_textures(const SpeciesFile& species, int texture_size) {
  const SpeciesImages& images = species.images;
  TreeTextureSet set;
  LeafTextureSettings leaf = leaf_texture_settings_for(species_preset(species.look).leaf_shape, species.texture_seed);
  leaf.size = texture_size;
  std::optional<glm::vec3> photo_color;  // the leaf image's mean colour
  if (!images.leaf_color.empty()) {
    Result<LeafImageTextures> t = leaf_textures_from_images({images.leaf_color, images.leaf_normal, images.leaf_translucency}, leaf);
    if (!t.ok()) return t.error();
    set.leaves = std::move(t->textures);
    photo_color = t->base_color;
  } else {
    Result<LeafTextures> t = generate_leaf_textures(leaf);
    if (!t.ok()) return t.error();
    set.leaves = std::move(t).value();
  }
  if (!images.bark_color.empty()) {
    Result<BarkTextures> t = bark_textures_from_images(images.bark_color, images.bark_normal, texture_size);
    if (!t.ok()) return t.error();
    set.bark = std::move(t).value();
  } else {
    BarkTextureSettings bark = bark_texture_settings_for(species.look, species.texture_seed);
    bark.size = texture_size;
    if (species.bark_color) bark.color = *species.bark_color;
    Result<BarkTextures> t = generate_bark_textures(bark);
    if (!t.ok()) return t.error();
    set.bark = std::move(t).value();
  }
  if (!images.season.empty()) {
    set.season = images.season;
  } else {
    set.season = generate_season_texture(season_palette_for(species.look));
    // A leaf image holds one season's colour (seed §3.2): it stays the leaves' colour all year,
    // with the look's budding and leaf fall (the palette's alpha).
    if (photo_color) {
      for (int y = 0; y < set.season.height(); ++y)
        for (int c = 0; c < 3; ++c) set.season.at(0, y, c) = (*photo_color)[c];
    }
  }
  Image& season = set.season;
  for (int y = 0; y < season.height(); ++y)
    for (int x = 0; x < season.width(); ++x)
      for (int c = 0; c < 3; ++c) season.at(x, y, c) *= species.leaf_tint[c];
  return set;
}

}  // namespace sylva::vegetation
