#include <sylva/voxel/block.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/voxel/block_textures.hpp>

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
  const auto id = static_cast<BlockId>(types_.size());
  if (type.render == RenderClass::kAlphaCut && id < first_alpha_cut_) first_alpha_cut_ = id;
  opaque_.push_back(type.render == RenderClass::kOpaque ? 1 : 0);
  render_.push_back(static_cast<std::uint8_t>(type.render));
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

namespace {

BlockType make_type(std::string name, RenderClass render, TextureId top, TextureId side, TextureId bottom) {
  BlockType t;
  t.name = std::move(name);
  t.render = render;
  t.texture_top = static_cast<int>(top);
  t.texture_side = static_cast<int>(side);
  t.texture_bottom = static_cast<int>(bottom);
  return t;
}

BlockType same(std::string name, RenderClass render, TextureId all) {
  return make_type(std::move(name), render, all, all, all);
}

BlockPalette build_standard() {
  using T = TextureId;
  using R = RenderClass;
  BlockPalette p;
  auto add = [&p](BlockType t) {
    auto r = p.add(std::move(t));
    SYLVA_ASSERT(r.ok(), "standard palette: {}", r.ok() ? "" : r.error().message);
  };
  BlockType stone = same("stone", R::kOpaque, T::kStone);
  stone.specular = 0.25f;
  stone.shininess = 24.0f;
  add(stone);
  add(same("dirt", R::kOpaque, T::kDirt));
  add(make_type("grass", R::kOpaque, T::kGrassTop, T::kGrassSide, T::kDirt));
  add(make_type("dry_grass", R::kOpaque, T::kDryGrassTop, T::kDryGrassSide, T::kDirt));
  BlockType sand = same("sand", R::kOpaque, T::kSand);
  sand.specular = 0.1f;
  add(sand);
  BlockType snow = same("snow", R::kOpaque, T::kSnow);
  snow.specular = 0.6f;
  snow.shininess = 48.0f;
  add(snow);
  add(same("gravel", R::kOpaque, T::kGravel));
  add(make_type("oak_log", R::kOpaque, T::kLogTop, T::kOakBark, T::kLogTop));
  add(make_type("birch_log", R::kOpaque, T::kLogTop, T::kBirchBark, T::kLogTop));
  add(make_type("acacia_log", R::kOpaque, T::kLogTop, T::kAcaciaBark, T::kLogTop));
  add(make_type("jungle_log", R::kOpaque, T::kLogTop, T::kJungleBark, T::kLogTop));
  for (auto [name, tex] : {std::pair{"oak_leaves", T::kOakLeaves}, {"birch_leaves", T::kBirchLeaves},
                           {"acacia_leaves", T::kAcaciaLeaves}, {"jungle_leaves", T::kJungleLeaves},
                           {"bush_leaves", T::kBushLeaves}, {"berry_leaves", T::kBerryLeaves}}) {
    BlockType leaves = same(name, R::kAlphaCut, tex);
    leaves.cull_same = false;
    leaves.specular = 0.15f;
    add(leaves);
  }
  BlockType tall_grass = same("tall_grass", R::kAlphaCut, T::kTallGrass);
  tall_grass.cull_same = false;
  tall_grass.sides_only = true;
  add(tall_grass);
  BlockType flowers = same("flowers", R::kAlphaCut, T::kFlowers);
  flowers.cull_same = false;
  flowers.sides_only = true;
  add(flowers);
  BlockType lantern = same("lantern", R::kOpaque, T::kLantern);
  lantern.emission = {1.0f, 0.75f, 0.4f};
  add(lantern);
  BlockType glow = same("glowstone", R::kOpaque, T::kGlowstone);
  glow.emission = {0.55f, 0.8f, 1.0f};
  add(glow);
  return p;
}

}  // namespace

const BlockPalette& BlockPalette::standard() {
  static const BlockPalette palette = build_standard();
  return palette;
}

}  // namespace sylva::voxel
