#include <sylva/voxel/block.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/voxel/block_textures.hpp>
#include <sylva/voxel/palette_file.hpp>

#include <fmt/format.h>

namespace sylva::voxel {

BlockPalette::BlockPalette() {
  BlockType air;
  air.name = "air";
  air.render = RenderClass::kAir;
  types_.push_back(air);
  opaque_.push_back(0);
  render_.push_back(static_cast<std::uint8_t>(RenderClass::kAir));
  sides_only_.push_back(0);
}

Result<BlockId> BlockPalette::add(BlockType type) {
  if (type.name.empty()) return make_error(ErrorCode::kInvalidArgument, "block palette: empty block name");
  for (char c : type.name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("block palette: name '{}' may only hold [a-z0-9_]", type.name));
    }
  }
  if (type.render == RenderClass::kAir) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("block palette: '{}' cannot be air (only id 0 is air)", type.name));
  }
  if (find(type.name).ok()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("block palette: duplicate name '{}'", type.name));
  }
  if (types_.size() >= 0xffff) {
    return make_error(ErrorCode::kLimit, fmt::format("block palette: more than 65535 types adding '{}'", type.name));
  }
  if (!(type.opacity >= 0.0f && type.opacity <= 1.0f)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("block palette: '{}' opacity outside [0, 1]", type.name));
  }
  const auto id = static_cast<BlockId>(types_.size());
  // Translucent blocks mesh as alpha-cut ones (render()).
  const RenderClass meshed = type.render == RenderClass::kTranslucent ? RenderClass::kAlphaCut : type.render;
  if (meshed == RenderClass::kAlphaCut && id < first_alpha_cut_) first_alpha_cut_ = id;
  opaque_.push_back(type.render == RenderClass::kOpaque ? 1 : 0);
  render_.push_back(static_cast<std::uint8_t>(meshed));
  sides_only_.push_back(type.sides_only ? 1 : 0);
  types_.push_back(std::move(type));
  return id;
}

Result<BlockId> BlockPalette::find(std::string_view name) const {
  for (std::size_t i = 0; i < types_.size(); ++i) {
    if (types_[i].name == name) return static_cast<BlockId>(i);
  }
  return make_error(ErrorCode::kNotFound, fmt::format("block palette: no block named '{}'", name));
}

BlockId BlockPalette::id(std::string_view name) const {
  auto r = find(name);
  SYLVA_ASSERT(r.ok(), "block '{}' is not in the palette", name);
  return *r;
}

Result<int> BlockPalette::add_image(Image rgba) {
  if (images_.size() >= kMaxPaletteImages) {
    return make_error(ErrorCode::kLimit, fmt::format("block palette: more than {} images", kMaxPaletteImages));
  }
  images_.push_back(std::move(rgba));
  return kTextureCount + static_cast<int>(images_.size()) - 1;
}

const BlockPalette& BlockPalette::standard() {
  static const BlockPalette palette = [] {
    auto p = builtin_palette();
    SYLVA_ASSERT(p.ok(), "data/palette.json: {}", p.ok() ? "" : p.error().message);
    return std::move(*p);
  }();
  return palette;
}

}  // namespace sylva::voxel
