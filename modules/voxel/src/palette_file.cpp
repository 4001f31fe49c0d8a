// Block palettes as data (palette_file.hpp): scalar keys through the params reflection (core
// params_json), "texture" read here (a procedural name, an image file, or one per face group).

#include <sylva/voxel/palette_file.hpp>

#include "embedded_data.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/voxel/block_textures.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <system_error>

namespace sylva::voxel {
namespace {

namespace fs = std::filesystem;

enum class BlockRender : std::uint8_t { kOpaque, kAlphaCut, kTranslucent };
constexpr std::array<EnumName<BlockRender>, 3> enum_names(BlockRender) {
  return {{{BlockRender::kOpaque, "opaque"}, {BlockRender::kAlphaCut, "alpha_cut"}, {BlockRender::kTranslucent, "translucent"}}};
}

// Everything of a block but "texture".
struct BlockHead {
  std::string name;
  BlockRender render = BlockRender::kOpaque;
  bool cull_same = true;
  bool sides_only = false;
  glm::vec3 emission{0.0f};
  float specular = 0.0f;
  float shininess = 16.0f;
  float opacity = 1.0f;

  template <class V>
  void visit(V& v) {
    v(name, "name", {.max = 64, .help = "Block name, [a-z0-9_]+, unique"});
    v(render, "render", {.help = "opaque, alpha_cut (cut-out texels) or translucent (blended: glass, water, ice; seed 004 §2.2)"});
    v(cull_same, "cull_same", {.help = "Faces between two blocks of this alpha-cut type are removed (glass); leaves keep them"});
    v(sides_only, "sides_only", {.help = "The seed's cube without bases (§1.3): grass tufts and flowers"});
    v(emission, "emission", {.min = 0.0, .max = 64.0, .help = "Linear RGB light emitted; non-zero makes a point light (seed 004 §2.3.3.2)"});
    v(specular, "specular", {.min = 0.0, .max = 1.0, .help = "Specular intensity scaling the specular map (seed 004 §2.3.2)"});
    v(shininess, "shininess", {.min = 1.0, .max = 1024.0, .help = "Phong shininess"});
    v(opacity, "opacity", {.min = 0.0, .max = 1.0, .help = "Multiplies the texture's alpha of a translucent block"});
  }
};

Error fail(ErrorCode code, std::string_view source, std::string_view what) {
  return make_error(code, fmt::format("{}: {}", source, what));
}

bool is_image_name(std::string_view s) {
  std::string lower(s);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (std::string_view ext : {".png", ".jpg", ".jpeg", ".tga", ".tif", ".tiff", ".bmp", ".exr"}) {
    if (lower.ends_with(ext)) return true;
  }
  return false;
}

// RGBA in [0, 1] from a 1-4 channel image (grey, grey + alpha, RGB, RGBA).
Image to_rgba(const Image& in) {
  Image out(in.width(), in.height(), 4);
  for (int y = 0; y < in.height(); ++y) {
    for (int x = 0; x < in.width(); ++x) {
      const int c = in.channels();
      const float r = in.at(x, y, 0);
      const float g = c >= 3 ? in.at(x, y, 1) : r;
      const float b = c >= 3 ? in.at(x, y, 2) : r;
      const float a = c == 4 ? in.at(x, y, 3) : c == 2 ? in.at(x, y, 1) : 1.0f;
      out.at(x, y, 0) = std::clamp(r, 0.0f, 1.0f);
      out.at(x, y, 1) = std::clamp(g, 0.0f, 1.0f);
      out.at(x, y, 2) = std::clamp(b, 0.0f, 1.0f);
      out.at(x, y, 3) = std::clamp(a, 0.0f, 1.0f);
    }
  }
  return out;
}

class PaletteReader {
 public:
  PaletteReader(std::string_view source, const fs::path& directory) : source_(source), directory_(directory) {}

  // One texture value at `path`: its layer index.
  Result<int> texture(const nlohmann::json& value, const std::string& path, BlockPalette& palette) {
    if (!value.is_string()) return fail(ErrorCode::kInvalidArgument, source_, fmt::format("{}: must be a texture name or an image file", path));
    const std::string name = value.get<std::string>();
    if (!is_image_name(name)) {
      for (int i = 0; i < kTextureCount; ++i) {
        if (texture_name(static_cast<TextureId>(i)) == name) return i;
      }
      std::string all;
      for (int i = 0; i < kTextureCount; ++i) all += fmt::format("{}{}", i ? ", " : "", texture_name(static_cast<TextureId>(i)));
      return fail(ErrorCode::kNotFound, source_,
                  fmt::format("{}: no procedural texture '{}' (one of {}; or an image file)", path, name.substr(0, 64), all));
    }
    if (const auto it = loaded_.find(name); it != loaded_.end()) return it->second;
    if (directory_.empty()) return fail(ErrorCode::kUnsupported, source_, fmt::format("{}: image files are not read here ({})", path, name));
    ImageReadOptions options;
    options.max_side = kMaxPaletteImageSide;
    options.allow_non_finite = false;
    auto image = read_image(fs::path(name).is_absolute() ? fs::path(name) : directory_ / name, options);
    if (!image.ok()) return fail(image.error().code, source_, fmt::format("{}: {}", path, image.error().message));
    auto layer = palette.add_image(to_rgba(*image));
    if (!layer.ok()) return fail(layer.error().code, source_, fmt::format("{}: {}", path, layer.error().message));
    loaded_[name] = *layer;
    return *layer;
  }

  Status block(const nlohmann::json& entry, const std::string& path, BlockPalette& palette, std::vector<std::string>& warnings) {
    if (!entry.is_object()) return fail(ErrorCode::kInvalidArgument, source_, fmt::format("{}: must be an object", path));
    for (const char* key : {"name", "texture"}) {
      if (!entry.contains(key)) return fail(ErrorCode::kInvalidArgument, source_, fmt::format("{}.{}: missing", path, key));
    }
    nlohmann::json head_json = entry;
    head_json.erase("texture");
    BlockHead head;
    std::vector<std::string> local;
    Status s = params_from_json(head, head_json, local, path);
    for (const std::string& w : local) warnings.push_back(fmt::format("{}: {}", source_, w));
    if (!s.ok()) return fail(s.error().code, source_, s.error().message);
    BlockType t;
    t.name = head.name;
    t.render = head.render == BlockRender::kAlphaCut      ? RenderClass::kAlphaCut
               : head.render == BlockRender::kTranslucent ? RenderClass::kTranslucent
                                                          : RenderClass::kOpaque;
    t.opacity = head.opacity;
    t.cull_same = head.cull_same;
    t.sides_only = head.sides_only;
    t.emission = head.emission;
    t.specular = head.specular;
    t.shininess = head.shininess;
    const nlohmann::json& tex = entry["texture"];
    const std::string tex_path = path + ".texture";
    if (tex.is_object()) {
      int* slots[] = {&t.texture_top, &t.texture_side, &t.texture_bottom};
      const char* keys[] = {"top", "side", "bottom"};
      for (const auto& [key, value] : tex.items()) {
        (void)value;
        if (key != "top" && key != "side" && key != "bottom") {
          return fail(ErrorCode::kInvalidArgument, source_, fmt::format("{}.{}: not a face group (top, side, bottom)", tex_path, key));
        }
      }
      for (int i = 0; i < 3; ++i) {
        const auto it = tex.find(keys[i]);
        if (it == tex.end()) return fail(ErrorCode::kInvalidArgument, source_, fmt::format("{}.{}: missing", tex_path, keys[i]));
        auto layer = texture(*it, fmt::format("{}.{}", tex_path, keys[i]), palette);
        if (!layer.ok()) return layer.error();
        *slots[i] = *layer;
      }
    } else {
      auto layer = texture(tex, tex_path, palette);
      if (!layer.ok()) return layer.error();
      t.texture_top = t.texture_side = t.texture_bottom = *layer;
    }
    auto id = palette.add(std::move(t));
    if (!id.ok()) return fail(id.error().code, source_, fmt::format("{}.name: {}", path, id.error().message));
    return ok_status();
  }

 private:
  std::string_view source_;
  fs::path directory_;
  std::map<std::string, int> loaded_;  // image file -> layer (one layer per file)
};

}  // namespace

Result<BlockPalette> parse_palette(std::string_view text, std::string_view source, const fs::path& directory,
                                   std::vector<std::string>& warnings) {
  Result<nlohmann::json> json = parse_json_text(text, source);
  if (!json.ok()) return json.error();
  if (!json->is_object()) return fail(ErrorCode::kInvalidArgument, source, R"(must be a JSON object {"blocks": [...]})");
  for (const auto& [key, value] : json->items()) {
    (void)value;
    if (key != "blocks") warnings.push_back(fmt::format("{}: {}: unknown key (ignored)", source, key));
  }
  const auto list = json->find("blocks");
  if (list == json->end() || !list->is_array() || list->empty()) {
    return fail(ErrorCode::kInvalidArgument, source, "blocks: missing, empty or not an array of blocks");
  }
  if (list->size() >= 0xffff) {
    return fail(ErrorCode::kLimit, source, fmt::format("blocks: {} entries, above the limit of 65534", list->size()));
  }
  BlockPalette palette;
  PaletteReader reader(source, directory);
  for (std::size_t i = 0; i < list->size(); ++i) {
    SYLVA_TRY(reader.block((*list)[i], fmt::format("blocks[{}]", i), palette, warnings));
  }
  return palette;
}

Result<BlockPalette> load_palette(const fs::path& path, std::vector<std::string>& warnings) {
  const std::string source = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) return fail(ErrorCode::kNotFound, source, "no such file");
  if (!fs::is_regular_file(path, ec)) return fail(ErrorCode::kIo, source, "not a file");
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec || bytes > kMaxPaletteFileBytes) {
    return fail(ErrorCode::kLimit, source, fmt::format("{} bytes, above the limit of {} MiB", bytes, kMaxPaletteFileBytes >> 20));
  }
  Result<std::string> text = read_file(path);
  if (!text.ok()) return text.error();
  fs::path directory = path.parent_path();
  if (directory.empty()) directory = ".";
  return parse_palette(*text, source, directory, warnings);
}

Result<BlockPalette> builtin_palette() {
  constexpr std::string_view kFile = "palette.json";
  const auto text = detail::embedded_file(kFile);
  if (!text) return make_error(ErrorCode::kNotFound, "no built-in palette.json");
  std::vector<std::string> warnings;
  return parse_palette(*text, kFile, {}, warnings);
}

}  // namespace sylva::voxel
