#pragma once
// Hidden faces of L-system plant parts (issue #18, "Voxel world"): the faces of a plant's cubes
// that no camera outside the plant can see, found once per cached plant model (seed 004 §4.7)
// and used by the renderer to skip them (and whole parts whose six faces are all hidden).
//
// A face of part P is hidden by another part Q ("covers") when the face's rectangle lies inside
// Q's closed box and its plane lies inside Q or on Q's face pointing the other way (P and Q
// touch there). A face on Q's face pointing the same way is never hidden, so two coincident
// faces never hide each other; coincident duplicate parts keep the first. With these rules every
// hidden face lies inside the union of the parts (up to its edges), so dropping hidden faces and
// parts with all six hidden leaves the plant's visible surface unchanged. Only axis-aligned parts
// (identity orientation, the default; `orient_parts` turns them) hide or are hidden.

#include <sylva/voxel/plant.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sylva::voxel {

// Face bit of an axis (0 x, 1 y, 2 z) and side: bit 2 * axis + (negative ? 1 : 0), the face
// order of plant.vert (face = gl_VertexID / 6; axis = face >> 1, odd faces point -axis).
constexpr std::uint8_t face_bit(int axis, bool negative) {
  return static_cast<std::uint8_t>(1u << (2 * axis + (negative ? 1 : 0)));
}
inline constexpr std::uint8_t kAllFaces = 0x3F;

// One part with its cover class: opaque parts (logs) hide faces of every part; cut-out parts
// (leaves, seen through their holes) hide faces of other cut-out parts only when `cut_hides_cut`.
struct FacePart {
  PlantPart part;
  bool opaque = true;
  int tag = 0;  // the caller's (the renderer: the part's output array, i.e. its block)
};

// Hidden-face masks of `parts` (same order, kAllFaces = the part can be dropped). Parts are in
// one plant's space (blocks). O(n log n + pairs that touch), n up to the 200 000-part limit.
std::vector<std::uint8_t> hidden_faces(std::span<const FacePart> parts, bool cut_hides_cut);

// The far model of a plant (issue #18: far plants as merged low-detail meshes): every part moved
// to the cell of a grid of edge `cell` blocks (centred on the plant origin) holding its centre,
// one axis-aligned cube of edge `cell` per occupied cell. The cell takes the class with more
// parts in it (opaque on a tie) and the tag of its first part of that class. Cells in the order
// of their first part. `cell` > 0 (kInvalidArgument-free: a non-positive or non-finite cell
// returns the parts unchanged).
std::vector<FacePart> snap_to_grid(std::span<const FacePart> parts, float cell);

// The mask of a part after turning its plant by `yaw_quarters` x 90 degrees about +y (the
// renderer places plants so): face normals follow the turn.
std::uint8_t turn_faces(std::uint8_t mask, int yaw_quarters);

}  // namespace sylva::voxel
