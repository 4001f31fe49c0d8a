#pragma once
// Block types and the palette that names them (seed 004 §1.3, §2.2: opaque cubes, cut-out
// textures such as leaves and grass, point-light sources).
//
// A BlockId is an index into one BlockPalette. Chunks store ids; region files store block
// *names* so a saved world survives a palette that gained or reordered entries.

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::voxel {

using BlockId = std::uint16_t;
inline constexpr BlockId kAir = 0;

// How a block is drawn and how it hides its neighbours.
enum class RenderClass : std::uint8_t {
  kAir,       // nothing drawn, hides nothing
  kOpaque,    // hides the faces of every neighbour; drawn in the opaque mesh with back-face culling
  kAlphaCut,  // texels are either fully opaque or cut (alpha < 0.5 discarded, seed §2.2 used 0.05);
              // drawn in the alpha-cut mesh without back-face culling; hides nothing
  kTranslucent,  // glass, water, ice (seed §2.2): meshed like alpha-cut (hides nothing, cull_same),
                 // drawn after the opaque pass with blending, chunks back to front, texels below
                 // the seed's alpha threshold discarded; alpha = texture alpha x opacity
};

// The six face directions. Index = 2 * axis + (negative ? 1 : 0); axis 0 = x, 1 = y (up), 2 = z.
enum class Face : std::uint8_t { kPosX = 0, kNegX = 1, kPosY = 2, kNegY = 3, kPosZ = 4, kNegZ = 5 };
inline constexpr int face_axis(int face) { return face >> 1; }
inline constexpr int face_sign(int face) { return (face & 1) ? -1 : 1; }

struct BlockType {
  std::string name;                     // unique, [a-z0-9_]+
  RenderClass render = RenderClass::kOpaque;
  // Texture-array layer per face group (filled by the texture generator; see block_textures.hpp).
  // Seed §1.3 builds a grass block from three parts: top, sides, bottom.
  int texture_top = 0;
  int texture_side = 0;
  int texture_bottom = 0;
  // Faces between two blocks of this same alpha-cut type are removed (like glass). Leaves keep
  // them (false) so a crown seen through its holes is not hollow.
  bool cull_same = true;
  // Drawn without top and bottom faces: the seed's "cube without bases" geometry (§1.3) for grass
  // tufts and flowers, whose cut-out texture looks wrong seen from above.
  bool sides_only = false;
  // Linear RGB emitted light; non-zero makes the block a point-light source (seed §2.3.3.2) and
  // draws it unlit at this colour.
  glm::vec3 emission{0.0f};
  // Specular intensity in [0, 1] scaling the block's specular map, and Phong shininess (seed §2.3.2).
  float specular = 0.0f;
  float shininess = 16.0f;
  // Multiplies the texture's alpha of a translucent block (1 = the texture's own alpha).
  float opacity = 1.0f;

  bool emits_light() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

class BlockPalette {
 public:
  // A palette holding only air (id 0).
  BlockPalette();

  // The standard palette used by world generation: terrain, the woods and leaves of the seed's
  // species (acacia, birch, oak, jungle, two bushes), plains grass and two light sources. It is
  // data/palette.json (palette_file.hpp), embedded, read by the same parser as a user's palette.
  static const BlockPalette& standard();

  // Adds a type. Errors (kInvalidArgument): duplicate or malformed name, more than 65535 types,
  // an air render class (only id 0 is air).
  Result<BlockId> add(BlockType type);

  std::size_t size() const { return types_.size(); }
  const BlockType& operator[](BlockId id) const { return types_[id]; }
  // kNotFound naming the missing block.
  Result<BlockId> find(std::string_view name) const;
  // For code that names a block it registered itself (asserts when missing).
  BlockId id(std::string_view name) const;

  // Flat lookup tables for the meshers' inner loops (indexed by BlockId).
  const std::vector<std::uint8_t>& opaque_table() const { return opaque_; }
  const std::vector<std::uint8_t>& render_table() const { return render_; }
  bool is_opaque(BlockId id) const { return opaque_[id] != 0; }
  // The class the meshers see: a translucent block meshes as alpha-cut (its faces go to the
  // alpha-cut list; the renderer draws them in its translucent pass, translucent()).
  RenderClass render(BlockId id) const { return static_cast<RenderClass>(render_[id]); }
  bool translucent(BlockId id) const { return types_[id].render == RenderClass::kTranslucent; }
  bool culls_same(BlockId id) const { return types_[id].cull_same; }
  const std::vector<std::uint8_t>& sides_only_table() const { return sides_only_; }
  bool sides_only(BlockId id) const { return sides_only_[id] != 0; }
  // Diffuse RGBA images a palette file brought (palette_file.hpp): texture index
  // kTextureCount + i (block_textures.hpp) is images()[i]; the procedural textures come first.
  // Returns that index; kLimit past kMaxPaletteImages.
  Result<int> add_image(Image rgba);
  const std::vector<Image>& images() const { return images_; }

  // Smallest alpha-cut id (0xffff when there is none): ids below it are air or opaque, which lets
  // the bitmask mesher classify whole rows with SIMD compares.
  BlockId first_alpha_cut() const { return first_alpha_cut_; }

 private:
  std::vector<BlockType> types_;
  std::vector<std::uint8_t> opaque_;
  std::vector<std::uint8_t> render_;
  std::vector<std::uint8_t> sides_only_;
  BlockId first_alpha_cut_ = 0xffff;
  std::vector<Image> images_;
};

inline constexpr std::size_t kMaxPaletteImages = 256;

}  // namespace sylva::voxel
