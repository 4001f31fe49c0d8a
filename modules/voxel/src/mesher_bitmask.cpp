// Binary greedy meshing.
//
// 1. Occupancy as 64-bit masks, in one pass over the ids. Every padded row along x (one per
//    padded (y, z)) becomes a "non-air" and an "opaque" mask of its n interior bits, stored twice
//    (indexed (y, z) and (z, y)) so the +-Y and +-Z slices both read their rows contiguously; the
//    opaque bytes of the padding ends (x = -1, x = n) are kept apart (66 bits do not fit), so 64^3
//    chunks work too. Rows are classified 16 blocks at a time with SSE2 compares; only ids at or
//    above the palette's first alpha-cut id need a table lookup. Masks along y (for +-X faces)
//    come from 32x32 / 64x64 bit-matrix transposes (Hacker's Delight §7-3).
// 2. Visible faces of a whole row in one expression, e.g. +Y at height s, row z:
//        faces = nonair_x[s][z] & ~opaque_x[s + 1][z]
//    two rows per SSE2 operation for a whole slice, with a mask of the rows holding faces, so
//    only those are visited (bit scan).
// 3. Ambient occlusion per face from a 512-entry table: bits b - 1, b, b + 1 of the three opaque
//    rows r - 1, r, r + 1 of the layer in front are the face's 3 x 3 neighbourhood. A row with
//    nothing opaque in front (open ground) skips all AO work, and on the other rows the faces
//    with nothing opaque around them are found bit-parallel and skip it too; faces on the
//    chunk's edge bits read the padding blocks instead (AoSampler).
// 4. Faces with uniform AO are bucketed by key (block, face, AO) into per-slice bit planes (open
//    rows in runs of one block id, one update per run) and merged into rectangles with
//    count-trailing-zeros / count-trailing-ones on the rows. Faces whose AO differs between
//    corners stay unit quads, so every mesher shades identically; so do faces with no face
//    beside them in the slice (they could merge with nothing), without a slot. Without AO, chunks
//    of plain opaque blocks skip the slot planes: the same rectangles straight from the face rows,
//    block ids compared in place (merge_by_id(), merge_dense()).
// 5. Whole-chunk shortcuts (issue #18): an all-air chunk is found by a scan and costs no masks;
//    slabs of only empty and full rows are not transposed; +-Z slices take rows along x instead
//    of y when the chunk's +-X faces mostly merged (terrain without AO, see mesh_faces()).
//
// The public binary greedy mesher (cgerikj/binary-greedy-meshing) pads 62^3 chunks into 64-bit
// columns and has no AO merging rule; this one also handles 64^3 chunks.

#include <sylva/core/assert.hpp>

#include "mesher_bitmask_rows.hpp"
#include "mesher_impl.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <type_traits>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace sylva::voxel::detail {
namespace {

// Transposes the top-left W x W bit block (W 32 or 64) in place:
// afterwards bit y of a[x] equals the former bit x of a[y]. W is a template argument and the
// pairs (k, k + j) run as contiguous inner loops of constant length, so at -O2 GCC unrolls them
// and does two rows per SSE2 operation.
template <int W>
void transpose_bits(std::uint64_t* a) {
  static constexpr std::uint64_t kMasks[6] = {0x5555555555555555ULL, 0x3333333333333333ULL, 0x0F0F0F0F0F0F0F0FULL,
                                              0x00FF00FF00FF00FFULL, 0x0000FFFF0000FFFFULL, 0x00000000FFFFFFFFULL};
  auto level = [a](auto jc) {
    constexpr int j = decltype(jc)::value;
    const std::uint64_t m = kMasks[std::countr_zero(static_cast<unsigned>(j))];
    for (int base = 0; base < W; base += 2 * j) {
      std::uint64_t* lo = a + base;
      std::uint64_t* hi = a + base + j;
      for (int i = 0; i < j; ++i) {
        const std::uint64_t t = ((lo[i] >> j) ^ hi[i]) & m;
        lo[i] ^= t << j;
        hi[i] ^= t;
      }
    }
  };
  if constexpr (W == 64) level(std::integral_constant<int, 32>{});
  level(std::integral_constant<int, 16>{});
  level(std::integral_constant<int, 8>{});
  level(std::integral_constant<int, 4>{});
  level(std::integral_constant<int, 2>{});
  level(std::integral_constant<int, 1>{});
}

void transpose_bits(std::uint64_t* a, int width) {
  if (width == 64) {
    transpose_bits<64>(a);
  } else {
    transpose_bits<32>(a);
  }
}


// AO byte (pack_ao order) of a face from its 3 x 3 neighbourhood in the layer in front of it
// (Lysenko's rule, see mesher.hpp): bit 3 * (dr + 1) + (db + 1) of the index is the opaque
// neighbour at row offset dr and bit offset db. kUIsRow: the face's u axis runs along rows (+-Y
// faces), otherwise along bits. Built at compile time from the same vertex formula as AoSampler.
// Entry: the AO byte, plus 0x100 when all four corners are equal (the face may merge).
template <bool kUIsRow>
constexpr std::array<std::uint16_t, 512> make_ao_table() {
  std::array<std::uint16_t, 512> t{};
  for (int nb = 0; nb < 512; ++nb) {
    auto occ = [nb](int du, int dv) {
      const int dr = kUIsRow ? du : dv;
      const int db = kUIsRow ? dv : du;
      return (nb >> (3 * (dr + 1) + (db + 1))) & 1;
    };
    auto vertex = [](int s1, int s2, int c) { return (s1 && s2) ? 0 : 3 - (s1 + s2 + c); };
    const int a0 = vertex(occ(-1, 0), occ(0, -1), occ(-1, -1));  // (u0, v0)
    const int a1 = vertex(occ(1, 0), occ(0, -1), occ(1, -1));    // (u1, v0)
    const int a2 = vertex(occ(1, 0), occ(0, 1), occ(1, 1));      // (u1, v1)
    const int a3 = vertex(occ(-1, 0), occ(0, 1), occ(-1, 1));    // (u0, v1)
    const bool uniform = a0 == a1 && a0 == a2 && a0 == a3;
    t[static_cast<std::size_t>(nb)] = static_cast<std::uint16_t>(a0 | a1 << 2 | a2 << 4 | a3 << 6 | (uniform ? 0x100 : 0));
  }
  return t;
}
constexpr std::array<std::uint16_t, 512> kAoRowU = make_ao_table<true>();
constexpr std::array<std::uint16_t, 512> kAoBitU = make_ao_table<false>();

constexpr std::uint8_t kFlagAlpha = 1;     // alpha-cut block
constexpr std::uint8_t kFlagSidesOnly = 2;  // no faces along y
constexpr std::uint8_t kFlagCullSame = 4;   // alpha-cut block hiding faces towards itself

// Axes of one face direction's slices (F, and for +-Z whether rows run along x, see
// mesh_faces()): bits run along y for +-X faces and +-Z rows along x, else along x; rows are the
// quad's u axis for +-Y faces and +-Z rows along x. Shifts: PackedQuad word0 of the bit and row axes.
template <int F, bool kRowsAlongX>
struct SliceAxes {
  static constexpr int kAxis = F >> 1;
  static constexpr bool kBitsAlongY = kAxis == 0 || kRowsAlongX;
  static constexpr bool kRowsAreU = kAxis == 1 || kRowsAlongX;
  static constexpr int kBitShift = kBitsAlongY ? 6 : 0;
  static constexpr int kRowShift = kRowsAlongX ? 0 : kAxis == 2 ? 6 : 12;
};

class BitmaskMesher final : public Mesher {
 public:
  explicit BitmaskMesher(const MesherOptions& options) : options_(options), avx2_(use_avx2()) {}
  MesherKind kind() const override { return MesherKind::kBitmask; }

  void mesh(const PaddedBlocks& blocks, const BlockPalette& palette, ChunkMesh& out) override {
    SYLVA_ASSERT(blocks.n >= 1 && blocks.n <= 64, "chunk size {}", blocks.n);
    // Write buffers: chunks up to 32^3 start in the mesher's own scratch lists, which only ever
    // grow, and copy the quads into the ChunkMesh at the end (a memcpy). Growing the ChunkMesh
    // lists slice by slice instead costs a resize per slice and zeroes the room past the last
    // quad on every call (std::vector value-initialises what it grows): ~3 % of a terrain 32^3
    // mesh. Larger chunks, and any list passing kScratchQuads (4096), write straight into the
    // ChunkMesh lists (their current elements treated as already-constructed room, cut at the
    // end), so large outputs are not copied.
    // An all-air chunk (sky, most of a world's chunks) has no face whatever its ring holds: a
    // scan that stops at the first block costs a fraction of the mask pass (issue #18: the
    // empty chunk cost 3.7x the peer's).
    if (interior_empty(blocks)) {
      out.clear();
      return;
    }
    out_[0] = &out.opaque;
    out_[1] = &out.alpha_cut;
    const bool small = blocks.n <= 32;
    lists_[0] = small ? &scratch_[0] : out_[0];
    lists_[1] = small ? &scratch_[1] : out_[1];
    n_ = blocks.n;
    p_ = n_ + 2;
    full_ = n_ == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n_) - 1;
    // The common chunk sizes get the mask pass with n known at compile time: the per-row
    // classification unrolls completely and every index step is a constant.
    switch (n_ == 32 || n_ == 64 || n_ < 16 ? 0 : (n_ + 15) / 16) {
      case 1: build_masks<0, 1>(blocks, palette); break;
      case 2: build_masks<0, 2>(blocks, palette); break;
      case 3: build_masks<0, 3>(blocks, palette); break;
      case 4: build_masks<0, 4>(blocks, palette); break;
      default:
        if (n_ == 32) {
          build_masks<32, 0>(blocks, palette);
        } else if (n_ == 64) {
          build_masks<64, 0>(blocks, palette);
        } else {
          build_masks<0, 0>(blocks, palette);
        }
    }
    // One flag byte per block for the face loop: most faces are of plain opaque blocks and pass
    // with a single load and test.
    const std::uint8_t* render = palette.render_table().data();
    const std::uint8_t* sides_only = palette.sides_only_table().data();
    flags_.resize(palette.size());
    if (slot_index_.size() < 4 * palette.size()) slot_index_.resize(4 * palette.size());
    for (std::size_t i = 0; i < palette.size(); ++i) {
      const auto id = static_cast<BlockId>(i);
      const bool alpha = render[i] == static_cast<std::uint8_t>(RenderClass::kAlphaCut);
      flags_[i] = static_cast<std::uint8_t>((alpha ? kFlagAlpha : 0) | (sides_only[i] ? kFlagSidesOnly : 0) |
                                            (alpha && palette.culls_same(id) ? kFlagCullSame : 0));
    }
    // One plain block id in the chunk (air aside): its faces need no ids to find their slot.
    single_ = spread_.single();
    if (single_ != kAir && (single_ >= palette.size() || flags_[single_] != 0)) single_ = kAir;
    // Only plain opaque blocks (every id up to the OR of the chunk's ids has no flag): AO-off
    // slices merge without slot planes (merge_by_id()).
    plain_ = spread_.any < palette.size();
    for (std::size_t i = 1; plain_ && i <= spread_.any; ++i) plain_ = flags_[i] == 0;
    const BlockId* ids = blocks.ids.data();
    count_[0] = count_[1] = 0;
    // Faces on the chunk's edge rows read their padding neighbours straight from the ids.
    const AoSampler edge_ao(blocks, palette.opaque_table());
    if (n_ == 32) {
      mesh_faces<32>(ids, render, edge_ao);
    } else {
      mesh_faces<0>(ids, render, edge_ao);
    }
    for (int list = 0; list < 2; ++list) {
      if (lists_[list] == out_[list]) {
        out_[list]->resize(count_[list]);
      } else {
        out_[list]->assign(lists_[list]->data(), lists_[list]->data() + count_[list]);
      }
    }
  }

 private:
  template <int kN>
  void mesh_faces(const BlockId* ids, const std::uint8_t* render, const AoSampler& edge_ao) {
    x_unit_ = x_merged_ = 0;
    mesh_face<0, kN>(ids, render, edge_ao);
    mesh_face<1, kN>(ids, render, edge_ao);
    mesh_face<2, kN>(ids, render, edge_ao);
    mesh_face<3, kN>(ids, render, edge_ao);
    // +-Z slices have two orientations. Rows along y (bits x, ids of a row contiguous) suit
    // faces that stay unit quads (checkerboard, random: read their ids along a row); rows
    // along x (bits y, like +-X) suit terrain without AO, whose side faces stack in columns
    // (of a few ids): merged along the row, one slot update per face or set, instead of short
    // runs along x and a vertical merge loop that mispredicts (issue #18: 62^3 3-type hills
    // without AO, +-Z 130 -> 90 k cycles each). The +-X faces, meshed just before with the same
    // orientation, tell which: rows along x when more of their quads came out of the merge than
    // were written as unit quads at once. Both give the same surface (other rectangles, about
    // as many).
    if (x_merged_ > x_unit_) {
      mesh_face<4, kN, true>(ids, render, edge_ao);
      mesh_face<5, kN, true>(ids, render, edge_ao);
    } else {
      mesh_face<4, kN>(ids, render, edge_ao);
      mesh_face<5, kN>(ids, render, edge_ao);
    }
  }

  // One face direction, specialised so the axis mapping is resolved at compile time; kN as for
  // build_masks (32: strides and the face-row pass are constants).
  // kZRowsX (+-Z only): rows along x, bits along y (see mesh_faces()).
  template <int F, int kN, bool kZRowsX = false>
  void mesh_face(const BlockId* ids, const std::uint8_t* render, const AoSampler& edge_ao) {
    constexpr int kAxis = F >> 1;
    constexpr int kSign = (F & 1) ? -1 : 1;
    const int n = kN > 0 ? kN : n_;
    const int p = n + 2;
    const int stride[3] = {1, p * p, p};
    const int mp = mask_pitch(p);  // of the mask arrays
    const bool ao_on = options_.ambient_occlusion;
    const int front = kSign * stride[kAxis];
    // Stride between consecutive bits of a row, in the padded id array: bits run along y for
    // +-X faces and along x otherwise.
    constexpr bool kRowsAlongX = kAxis == 2 && kZRowsX;
    using Axes = SliceAxes<F, kRowsAlongX>;
    constexpr bool kBitsAlongY = Axes::kBitsAlongY;
    const int bit_stride = kBitsAlongY ? p * p : 1;
    constexpr int kBitShift = Axes::kBitShift;  // PackedQuad word0 shift of the bit axis
    // Rows run along z (+-X, +-Y faces) or y (+-Z faces): their id stride and word0 shift.
    const int row_ids = kRowsAlongX ? 1 : kAxis == 2 ? p * p : p;
    constexpr int kRowShift = Axes::kRowShift;
    // Raw pointers: stores into the output vectors would otherwise force reloads of every
    // member vector's data pointer inside the loops.
    // Non-air masks of the slices and opaque masks of the layers in front, rows contiguous:
    // +-X: bits y, rows z (ay_, oy_); +-Y: bits x, rows z (ax_, ox_); +-Z: bits x, rows y (az_, oz_).
    // (+-Z with rows along x: bits y, rows x, gathered from ay_ / oy_ per slice below.)
    const std::uint64_t* am = kAxis == 0 ? ay_.data() : kAxis == 1 ? ax_.data() : kRowsAlongX ? ay_.data() : az_.data();
    const std::uint64_t* lm = kAxis == 0 ? oy_.data() : kAxis == 1 ? ox_.data() : kRowsAlongX ? oy_.data() : oz_.data();
    const std::uint8_t* flags = flags_.data();
    const BlockId single = single_;  // the chunk's one plain block id, or kAir
    // Flags that exclude a face of this direction outright / that need a closer look.
    constexpr std::uint8_t kSpecial = kFlagAlpha | (kAxis == 1 ? kFlagSidesOnly : 0);
    // AO neighbourhood table for this orientation, and the opaque masks of the layer's rows.
    const std::uint16_t* ao_table = kAxis == 1 || kRowsAlongX ? kAoRowU.data() : kAoBitU.data();
    // Faces at bit 0 or n - 1 need the padding blocks beside the row (read from the ids).
    const std::uint64_t edges = std::uint64_t{1} | std::uint64_t{1} << (n - 1);
    for (int s = 0; s < n; ++s) {
      const int layer = s + kSign;  // the slice in front of the faces, in [-1, n]
      // Visible faces of every row of the slice, and the rows holding any (bit r), so the loop
      // below visits only those.
      const std::uint64_t* lrows = lm + idx2(layer, 0, mp);  // lrows[r]: row r; [-1] and [n] are padding
      const std::uint64_t* srows = am + idx2(s, 0, mp);
      if constexpr (kRowsAlongX) {
        // Rows x of slice z and of the layer in front: the (x, z) columns, p apart, gathered
        // only for slices with a face (found from the contiguous (z, y) rows: most +-Z slices
        // of a solid chunk have none).
        if (face_rows<kN>(az_.data() + idx2(s, 0, mp), oz_.data() + idx2(layer, 0, mp), n, face_rows_) == 0) continue;
        for (int x = 0; x < n; ++x) zslice_[x] = am[(x + 1) * mp + s + 1];
        for (int x = -1; x <= n; ++x) zlayer_[x + 1] = lm[(x + 1) * mp + layer + 1];
        srows = zslice_;
        lrows = zlayer_ + 1;
      }
      const std::uint64_t nonempty = face_rows<kN>(srows, lrows, n, face_rows_);
      if (nonempty == 0) continue;  // no face in this slice: nothing to write or merge
      // Quads are written through raw pointers into the output lists, grown to leave room for
      // the slice: each quad covers at least one unit face, and the faces lie in the rows
      // between the first and the last non-empty one, at most n per row. The bound is tight so
      // that the room beyond the last quad, which std::vector zeroes when it grows the list and
      // which is cut again at the end of mesh(), stays small (a flat n^2 per slice cost ~2 n^2
      // zeroed quads per call: 2 % of a terrain 32^3 mesh).
      // (Two plain locals, never address-taken, so they stay in registers across calls.)
      const int span = 64 - std::countl_zero(nonempty) - std::countr_zero(nonempty);
      for (int list = 0; list < 2; ++list) {
        const std::size_t need = count_[list] + static_cast<std::size_t>(span) * static_cast<std::size_t>(n);
        if (need > kScratchQuads && lists_[list] != out_[list]) {
          // Too large for the scratch list: move what is written to the ChunkMesh and go on there.
          // (Copied over its current elements, not assigned: a cut would make the growth below
          // zero again what the ChunkMesh already holds, e.g. the previous mesh of this chunk.)
          std::vector<PackedQuad>& o = *out_[list];
          if (o.size() < count_[list]) o.resize(count_[list]);
          std::copy_n(lists_[list]->data(), count_[list], o.data());
          lists_[list] = out_[list];
        }
        std::vector<PackedQuad>& q = *lists_[list];
        // Within the capacity only up to `need` (every new element is zeroed), beyond it doubling.
        if (q.size() < need) q.resize(need > q.capacity() ? std::max(need, 2 * q.capacity()) : need);
      }
      PackedQuad* dst_opaque = lists_[0]->data() + count_[0];
      PackedQuad* dst_alpha = lists_[1]->data() + count_[1];
      if (plain_ && !ao_on) {
        // AO off, plain opaque blocks only: the rectangles straight from the face rows, ids
        // compared in place (see merge_by_id()), no slot planes.
        PackedQuad* const start = dst_opaque;
        int ox, oy, oz;
        origin(F, kRowsAlongX, s, 0, 0, ox, oy, oz);
        std::size_t alone = 0;
        dst_opaque = merge_by_id<F, kRowsAlongX>(ids + (ox + 1) + p * ((oz + 1) + p * (oy + 1)), s, row_ids, bit_stride,
                                                 nonempty, dst_opaque, alone);
        if constexpr (kAxis == 0) {
          x_unit_ += alone;
          x_merged_ += static_cast<std::size_t>(dst_opaque - start) - alone;
        }
        count_[0] = static_cast<std::size_t>(dst_opaque - lists_[0]->data());
        continue;
      }
      slot_count_ = 0;
      if (++slice_stamp_ == 0) {  // stamps wrapped: forget every entry
        std::fill(slot_index_.begin(), slot_index_.end(), SlotRef{});
        slice_stamp_ = 1;
      }
      // Padded id index and word0 of bit 0 of row 0; rows step by row_ids / 1 << kRowShift.
      int x0, y0, z0;
      origin(F, kRowsAlongX, s, 0, 0, x0, y0, z0);
      const int slice_base = (x0 + 1) + p * ((z0 + 1) + p * (y0 + 1));
      const std::uint32_t slice_word0 = pack_word0(x0, y0, z0, 1, 1);
      for (std::uint64_t rows_left = nonempty; rows_left; rows_left &= rows_left - 1) {
        const int r = std::countr_zero(rows_left);
        std::uint64_t faces = face_rows_[r];
        // Faces with no face beside them in the slice (left, right, rows r - 1 and r + 1) can
        // merge with nothing: they are written as unit quads at once instead of going through
        // a slot and the rectangle merge (checkerboard: every face; random 50 %: most).
        const std::uint64_t prev = r > 0 ? face_rows_[r - 1] : 0;
        const std::uint64_t next = r + 1 < n ? face_rows_[r + 1] : 0;
        const std::uint64_t alone = faces & ~(faces << 1 | faces >> 1 | prev | next);
        // The opaque rows r - 1, r, r + 1 of the layer in front. With none of them opaque and no
        // face on an edge bit, every corner of every face of the row is open (AO 3): open ground
        // takes the run path below without any AO work.
        const std::uint64_t l0 = lrows[r - 1], l1 = lrows[r], l2 = lrows[r + 1];
        // Faces on an edge bit read the ring blocks beside the row: they alone take the edge
        // path, so the rest of a row on a chunk's open side (e.g. every row of a solid chunk's
        // surface) still takes the run path.
        const bool occluded = ao_on && (l0 | l1 | l2) != 0;
        std::uint64_t edge_faces = ao_on ? faces & edges : 0;
        faces &= ~edge_faces;
        const int row_base = slice_base + r * row_ids;
        // word0 of the unit quad at bit 0; bit b adds b to its y (+-X) or x coordinate.
        const std::uint32_t row_word0 = slice_word0 + (static_cast<std::uint32_t>(r) << kRowShift);
        // Adds the faces `bits` (one block, one uniform AO value) to the slot of `key`.
        // (The slot table is read for every call: caching the last key mispredicts on rows
        // whose blocks alternate.)
        auto add = [&](std::uint32_t key, std::uint64_t bits) __attribute__((always_inline)) {
          const SlotRef& e = slot_index_[(key & 0xffffu) * 4 + ((key >> 19) & 3u)];
          const auto k = static_cast<std::size_t>(e.slice == slice_stamp_ ? e.slot : find_slot(key));
          rows_[k * 64 + static_cast<std::size_t>(r)] |= bits;
          used_[k] |= std::uint64_t{1} << r;
        };
        // One face at bit b: special blocks; AO open (kOpen), the neighbourhood table's entry
        // `table` (kTable, see ao_entry()) or, for faces on an edge bit, from the padding blocks
        // (kEdge).
        enum Ao { kOpen, kTable, kEdge };
        auto one = [&](int b, Ao mode, std::uint32_t table = 0) __attribute__((always_inline)) {
          const int idx = row_base + b * bit_stride;
          const BlockId self = ids[idx];
          const std::uint8_t f = flags[self];
          const bool alpha = (f & kFlagAlpha) != 0;
          if (f & kSpecial) {
            if (kAxis == 1 && (f & kFlagSidesOnly)) return;
            if ((f & kFlagCullSame) && ids[idx + front] == self) return;
          }
          std::uint32_t aob = 0xffu;  // all four corners open
          bool uniform = true;
          if (mode == kTable) {
            aob = table & 0xffu;
            uniform = (table & 0x100u) != 0;
          } else if (mode == kEdge) {
            aob = edge_ao.face_bits(idx, F);
            uniform = ao_uniform(aob);
          }
          if (uniform && !((alone >> b) & 1)) {
            add(pack_word1(self, F, aob), std::uint64_t{1} << b);
          } else {
            const PackedQuad q{row_word0 + (static_cast<std::uint32_t>(b) << kBitShift), pack_word1(self, F, aob)};
            if (alpha) {
              *dst_alpha++ = q;
            } else {
              *dst_opaque++ = q;
            }
          }
        };
        // Faces that may merge (not alone) and see nothing opaque around them (AO 3 at every
        // corner): with AO on they are told apart from the rest bit-parallel, from the 3 x 3
        // neighbourhood of the whole row at once, so on occluded rows only the others pay the
        // per-face table lookup (terrain sides: most rows have ground in front somewhere).
        std::uint64_t open_merge;
        if (occluded) {
          const std::uint64_t nb = l0 | l1 | l2;
          open_merge = faces & ~(nb | nb << 1 | nb >> 1 | alone);
          faces &= ~open_merge;
          // The rest by the table: mostly unit quads (corners differ). The few uniform ones that
          // may merge (rare) are added below with the open ones, in bit order, so slots are made
          // in the order the faces come (the mesh's quad order does not depend on this split).
          std::uint64_t rare = 0;
          // One plain block id: no id, flag or list choice per face.
          const std::uint32_t single_word1 = pack_word1(single, F, 0);
          while (faces) {
            const int b = std::countr_zero(faces);
            faces &= faces - 1;
            const std::uint32_t e = ao_entry(ao_table, l0, l1, l2, b);
            if ((e & 0x100u) && !((alone >> b) & 1)) {
              rare |= std::uint64_t{1} << b;
            } else if (single != kAir) {
              *dst_opaque++ = PackedQuad{row_word0 + (static_cast<std::uint32_t>(b) << kBitShift), single_word1 | (e & 0xffu) << 19};
            } else {
              one(b, kTable, e);
            }
          }
          if (rare) {
            for (std::uint64_t all = rare | open_merge; all; all &= all - 1) {
              const int b = std::countr_zero(all);
              one(b, kTable, ao_entry(ao_table, l0, l1, l2, b));
            }
            open_merge = 0;
          }
        } else {
          open_merge = faces & ~alone;
          faces &= ~open_merge;
          if (single != kAir) {
            // Alone faces of a one-id chunk (checkerboard): unit quads without an id read. The ids
            // of +-X faces lie p^2 apart (8 KB at 62^3), one cache line per face.
            const std::uint32_t open_word1 = pack_word1(single, F, 0xffu);
            while (faces) {
              const int b = std::countr_zero(faces);
              faces &= faces - 1;
              *dst_opaque++ = PackedQuad{row_word0 + (static_cast<std::uint32_t>(b) << kBitShift), open_word1};
            }
          }
          while (faces) {  // alone: unit quads
            const int b = std::countr_zero(faces);
            faces &= faces - 1;
            one(b, kOpen);
          }
        }
        if (single != kAir) {  // one block id: the open faces are one set
          if (open_merge) add(pack_word1(single, F, 0xffu), open_merge);
        } else if constexpr (!kBitsAlongY) {
          // Bits run along x here: open faces go in runs of one block id (same_next bit b: the
          // block at b + 1 has the same id as the one at b), one slot update per run instead of
          // per face. (A single face is a run of one: no need to compare the row's ids.)
          std::uint64_t uni = open_merge;
          const std::uint64_t same_next = (uni & (uni - 1)) != 0 ? same_next_mask(ids + row_base, n) : 0;
          while (uni) {
            const int b = std::countr_zero(uni);
            const BlockId self = ids[row_base + b];
            if (flags[self] & kSpecial) {
              one(b, kOpen);
              uni &= uni - 1;
              continue;
            }
            const int len = 1 + std::countr_one(((uni >> 1) & same_next) >> b);
            const std::uint64_t run = (len >= 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << len) - 1)) << b;
            uni &= ~run;
            add(pack_word1(self, F, 0xffu), run);
          }
        } else {
          // Bits along y: ids p^2 apart, one slot update per face.
          while (open_merge) {
            const int b = std::countr_zero(open_merge);
            open_merge &= open_merge - 1;
            one(b, kOpen);
          }
        }
        while (edge_faces) {
          const int b = std::countr_zero(edge_faces);
          edge_faces &= edge_faces - 1;
          one(b, kEdge);
        }
      }
      const PackedQuad* const unit_end[2] = {dst_opaque, dst_alpha};
      for (int k = 0; k < slot_count_; ++k) {
        const auto block = static_cast<BlockId>(keys_[static_cast<std::size_t>(k)] & 0xffffu);
        if (render[block] == static_cast<std::uint8_t>(RenderClass::kAlphaCut)) {
          dst_alpha = merge_slot(k, F, kRowsAlongX, s, dst_alpha);
        } else {
          dst_opaque = merge_slot(k, F, kRowsAlongX, s, dst_opaque);
        }
      }
      if constexpr (kAxis == 0) {
        x_unit_ += static_cast<std::size_t>((unit_end[0] - lists_[0]->data()) + (unit_end[1] - lists_[1]->data())) -
                   count_[0] - count_[1];
        x_merged_ += static_cast<std::size_t>((dst_opaque - unit_end[0]) + (dst_alpha - unit_end[1]));
      }
      for (int list = 0; list < 2; ++list) {
        count_[list] = static_cast<std::size_t>((list == 0 ? dst_opaque : dst_alpha) - lists_[list]->data());
      }
    }
  }

  // Greedy rectangles of one slice's face rows (face_rows_, consumed) for chunks of plain opaque
  // blocks without AO, the key being the block id alone: the lowest face left in the lowest row
  // starts a run of faces of its id along the row, which then grows over the next rows while
  // they hold faces of that id at every bit of the run. Per block id this is the slot planes'
  // merge (merge_slot()) on that id's faces, so the quads are the same set, in another order;
  // faces with no face beside them (written as unit quads at once otherwise) come out as 1 x 1.
  // The ids are compared in place instead of bucketed per id first (issue #18: with the slot
  // planes AO off cost more than AO on on mixed-id chunks). slice_ids: the padded ids of bit 0,
  // row 0; rows step by row_ids, bits by bit_stride. Returns the end of what it wrote; alone:
  // the count of faces with no face beside them (+-X only, for the +-Z orientation choice).
  template <int F, bool kRowsAlongX>
  PackedQuad* merge_by_id(const BlockId* slice_ids, int s, int row_ids, int bit_stride, std::uint64_t nonempty,
                          PackedQuad* dst, std::size_t& alone) {
    using Axes = SliceAxes<F, kRowsAlongX>;
    constexpr int kAxis = Axes::kAxis;
    constexpr bool kBitsAlongY = Axes::kBitsAlongY;
    const int n = n_;
    const BlockId single = single_;
    std::uint64_t* rows = face_rows_;
    // Faces with no face beside them (left, right, rows r - 1 and r + 1) merge with nothing: unit
    // quads in a tight loop, without the run and row tests (checkerboard, most of random 50 %).
    // Found for every row before any row is consumed.
    std::uint64_t alone_rows = 0;  // bit r: row r holds alone faces
    for (std::uint64_t left = nonempty; left; left &= left - 1) {
      const int r = std::countr_zero(left);
      const std::uint64_t f = rows[r];
      const std::uint64_t prev = r > 0 ? rows[r - 1] : 0;
      const std::uint64_t next = r + 1 < n ? rows[r + 1] : 0;
      alone_[r] = f & ~(f << 1 | f >> 1 | prev | next);
      alone_rows |= static_cast<std::uint64_t>(alone_[r] != 0) << r;
    }
    // Slices where most rows hold alone faces (random content: many short runs of either id)
    // take the branch-poor variant: ids compared a whole row at a time up front.
    if (single == kAir && 2 * std::popcount(alone_rows) > std::popcount(nonempty)) {
      return merge_dense<F, kRowsAlongX>(slice_ids, s, row_ids, bit_stride, nonempty, dst, alone);
    }
    constexpr int kBitShift = Axes::kBitShift;
    constexpr int kRowShift = Axes::kRowShift;
    int x0, y0, z0;
    origin(F, kRowsAlongX, s, 0, 0, x0, y0, z0);
    const std::uint32_t slice_word0 = pack_word0(x0, y0, z0, 1, 1);
    const std::uint32_t single_word1 = pack_word1(single, F, 0xffu);
    // Bits along x: same_next masks of the rows (bit b: ids b and b + 1 equal), made once per row
    // when first needed.
    std::uint64_t have_same = 0;
    auto same_next = [&](int r) __attribute__((always_inline)) {
      if (!((have_same >> r) & 1)) {
        same_[r] = same_next_mask(slice_ids + r * row_ids, n);
        have_same |= std::uint64_t{1} << r;
      }
      return same_[r];
    };
    for (std::uint64_t left = nonempty; left; left &= left - 1) {
      const int r = std::countr_zero(left);
      const BlockId* row = slice_ids + r * row_ids;
      std::uint64_t unit = alone_[r];
      rows[r] &= ~unit;
      const std::uint32_t row_word0 = slice_word0 + (static_cast<std::uint32_t>(r) << kRowShift);
      const PackedQuad* const units = dst;  // (counted by pointers: popcount is a libgcc call at -O2)
      if (single != kAir) {
        for (; unit; unit &= unit - 1) {
          *dst++ = PackedQuad{row_word0 + (static_cast<std::uint32_t>(std::countr_zero(unit)) << kBitShift), single_word1};
        }
      }
      for (; unit; unit &= unit - 1) {
        const int b = std::countr_zero(unit);
        *dst++ = PackedQuad{row_word0 + (static_cast<std::uint32_t>(b) << kBitShift), pack_word1(row[b * bit_stride], F, 0xffu)};
      }
      if constexpr (kAxis == 0) alone += static_cast<std::size_t>(dst - units);
      while (rows[r]) {
        const int b = std::countr_zero(rows[r]);
        const std::uint64_t from_b = rows[r] >> b;
        int w;
        BlockId id = single;
        if (single != kAir) {
          w = std::countr_one(from_b);
        } else if constexpr (!kBitsAlongY) {
          id = row[b];
          w = 1 + std::countr_one((from_b >> 1) & (same_next(r) >> b));
        } else {
          id = row[b * bit_stride];
          const int most = std::countr_one(from_b);
          w = 1;
          while (w < most && row[(b + w) * bit_stride] == id) ++w;
        }
        const std::uint64_t run = (w == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << w) - 1)) << b;
        rows[r] &= ~run;
        // Grows while the next row holds faces of the run's id at every bit of the run.
        int h = 1;
        for (; r + h < n && (rows[r + h] & run) == run; ++h) {
          if (single == kAir) {
            const BlockId* next = row + h * row_ids;
            if constexpr (!kBitsAlongY) {
              const std::uint64_t inner = run & (run >> 1);  // bits b .. b + w - 2
              if (next[b] != id || (same_next(r + h) & inner) != inner) break;
            } else {
              int k = 0;
              while (k < w && next[(b + k) * bit_stride] == id) ++k;
              if (k < w) break;
            }
          }
          rows[r + h] &= ~run;
        }
        int x, y, z;
        origin(F, kRowsAlongX, s, r, b, x, y, z);
        *dst++ = PackedQuad{pack_word0(x, y, z, Axes::kRowsAreU ? h : w, Axes::kRowsAreU ? w : h), pack_word1(id, F, 0xffu)};
      }
    }
    return dst;
  }

  // merge_by_id() for slices of many short runs of mixed ids (random content): the same
  // rectangles, with the ids of every row with merging faces compared up front, a row at a time
  // (SSE2): along the row (same_) and with the next row (down_); bits along y first gather the
  // merging faces' ids (p^2 apart) into contiguous rows, each read once. The run and row tests
  // are then mask operations, whose data-dependent branches cost more than the compares there.
  template <int F, bool kRowsAlongX>
  PackedQuad* merge_dense(const BlockId* slice_ids, int s, int row_ids, int bit_stride, std::uint64_t nonempty,
                          PackedQuad* dst, std::size_t& alone) {
    using Axes = SliceAxes<F, kRowsAlongX>;
    constexpr bool kBitsAlongY = Axes::kBitsAlongY;
    const int n = n_;
    std::uint64_t* rows = face_rows_;
    std::uint64_t merging = 0;  // bit r: row r has faces that may merge
    for (std::uint64_t left = nonempty; left; left &= left - 1) {
      const int r = std::countr_zero(left);
      merging |= static_cast<std::uint64_t>(rows[r] != alone_[r]) << r;
    }
    auto row_of = [&](int r) __attribute__((always_inline)) -> const BlockId* {
      if constexpr (kBitsAlongY) {
        return id_rows_[r];
      } else {
        return slice_ids + r * row_ids;
      }
    };
    if constexpr (kBitsAlongY) {
      for (std::uint64_t left = merging; left; left &= left - 1) {
        const int r = std::countr_zero(left);
        const BlockId* src = slice_ids + r * row_ids;
        for (std::uint64_t f = rows[r] & ~alone_[r]; f; f &= f - 1) {
          const int b = std::countr_zero(f);
          id_rows_[r][b] = src[b * bit_stride];
        }
      }
    }
    for (std::uint64_t left = merging; left; left &= left - 1) {
      const int r = std::countr_zero(left);
      const BlockId* ids_r = row_of(r);
      same_[r] = equal_mask(ids_r, ids_r + 1, n);
      down_[r] = r + 1 < n && ((merging >> (r + 1)) & 1) ? equal_mask(ids_r, row_of(r + 1), n) : 0;
    }
    int x0, y0, z0;
    origin(F, kRowsAlongX, s, 0, 0, x0, y0, z0);
    const std::uint32_t slice_word0 = pack_word0(x0, y0, z0, 1, 1);
    for (std::uint64_t left = nonempty; left; left &= left - 1) {
      const int r = std::countr_zero(left);
      const std::uint32_t row_word0 = slice_word0 + (static_cast<std::uint32_t>(r) << Axes::kRowShift);
      const BlockId* src = slice_ids + r * row_ids;
      std::uint64_t unit = alone_[r];
      rows[r] &= ~unit;
      const PackedQuad* const units = dst;
      for (; unit; unit &= unit - 1) {
        const int b = std::countr_zero(unit);
        *dst++ = PackedQuad{row_word0 + (static_cast<std::uint32_t>(b) << Axes::kBitShift), pack_word1(src[b * bit_stride], F, 0xffu)};
      }
      if constexpr (Axes::kAxis == 0) alone += static_cast<std::size_t>(dst - units);
      const BlockId* ids_r = row_of(r);
      const std::uint64_t same = same_[r];
      while (rows[r]) {
        const int b = std::countr_zero(rows[r]);
        const int w = 1 + std::countr_one(((rows[r] >> 1) & same) >> b);
        const std::uint64_t run = (w == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << w) - 1)) << b;
        rows[r] &= ~run;
        int h = 1;
        while (r + h < n && (rows[r + h] & down_[r + h - 1] & run) == run) {
          rows[r + h] &= ~run;
          ++h;
        }
        int x, y, z;
        origin(F, kRowsAlongX, s, r, b, x, y, z);
        *dst++ = PackedQuad{pack_word0(x, y, z, Axes::kRowsAreU ? h : w, Axes::kRowsAreU ? w : h), pack_word1(ids_r[b], F, 0xffu)};
      }
    }
    return dst;
  }

  // Entry of the AO table (make_ao_table()) for a face at bit b (not an edge bit) of a row whose
  // layer in front has the opaque rows l0, l1, l2: bits b - 1, b, b + 1 of each are the index.
  static std::uint32_t ao_entry(const std::uint16_t* table, std::uint64_t l0, std::uint64_t l1, std::uint64_t l2, int b) {
    const int sh = b - 1;
    return table[((l0 >> sh) & 7u) | ((l1 >> sh) & 7u) << 3 | ((l2 >> sh) & 7u) << 6];
  }

  // faces[r] = slice[r] & ~layer[r] for r in [0, n); returns the mask of rows with faces.
  // Two rows per SSE2 operation.
  template <int kN>
  static std::uint64_t face_rows(const std::uint64_t* slice, const std::uint64_t* layer, int n_run,
                                 std::uint64_t* faces) {
    const int n = kN > 0 ? kN : n_run;
    std::uint64_t nonempty = 0;
    int r = 0;
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    std::uint64_t empty = 0;  // bit r: row r has no face
    if (n <= 32) {
      // Rows of at most 32 bits: four rows' low halves share one compare (the high halves are 0).
#pragma GCC unroll 8
      for (; r + 4 <= n; r += 4) {
        const __m128i f0 = _mm_andnot_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(layer + r)),
                                            _mm_loadu_si128(reinterpret_cast<const __m128i*>(slice + r)));
        const __m128i f1 = _mm_andnot_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(layer + r + 2)),
                                            _mm_loadu_si128(reinterpret_cast<const __m128i*>(slice + r + 2)));
        _mm_store_si128(reinterpret_cast<__m128i*>(faces + r), f0);
        _mm_store_si128(reinterpret_cast<__m128i*>(faces + r + 2), f1);
        const __m128 lows = _mm_shuffle_ps(_mm_castsi128_ps(f0), _mm_castsi128_ps(f1), _MM_SHUFFLE(2, 0, 2, 0));
        const __m128i z = _mm_cmpeq_epi32(_mm_castps_si128(lows), zero);
        empty |= static_cast<std::uint64_t>(_mm_movemask_ps(_mm_castsi128_ps(z))) << r;
      }
    }
    for (; r + 2 <= n; r += 2) {
      const __m128i f = _mm_andnot_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(layer + r)),
                                         _mm_loadu_si128(reinterpret_cast<const __m128i*>(slice + r)));
      _mm_store_si128(reinterpret_cast<__m128i*>(faces + r), f);
      // A 64-bit row is zero when both of its 32-bit halves are: AND the halves' compare masks,
      // then one sign bit per row.
      const __m128i z = _mm_cmpeq_epi32(f, zero);
      const __m128i zz = _mm_and_si128(z, _mm_shuffle_epi32(z, _MM_SHUFFLE(2, 3, 0, 1)));
      empty |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_castsi128_pd(zz))) << r;
    }
    nonempty = ~empty & (r == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << r) - 1);
#endif
    for (; r < n; ++r) {
      faces[r] = slice[r] & ~layer[r];
      nonempty |= static_cast<std::uint64_t>(faces[r] != 0) << r;
    }
    return nonempty;
  }

  // Index of padded (a, b) in [-1, n]^2 for the P x P mask arrays.
  // (p passed in: the member would be reloaded after every store into the uint64_t scratch.)
  static int idx2(int a, int b, int p) { return (a + 1) * p + (b + 1); }

  // kN: the chunk size when known at compile time, else 0 (n_ at run time).
  template <int kN, int kChunks>
  void build_masks(const PaddedBlocks& blocks, const BlockPalette& palette) {
    const int n = kN > 0 ? kN : n_;
    const int p = n + 2;
    const auto pp = static_cast<std::size_t>(p * p);
    const int mp = mask_pitch(p);
    // Every entry is written below (no clearing pass: it cost as much as a transpose).
    for (auto* v : {&ax_, &ox_, &az_, &oz_, &ay_, &oy_}) v->resize(static_cast<std::size_t>(p * mp));
    const std::uint8_t* opaque = palette.opaque_table().data();
    const BlockId* ids = blocks.ids.data();
    const BlockId first_special = palette.first_alpha_cut();
    std::uint64_t* ax = ax_.data();
    std::uint64_t* ox = ox_.data();
    std::uint64_t* az = az_.data();
    std::uint64_t* oz = oz_.data();
    // The padding columns x = -1 and x = n along y (bit y), per padded z: the opaque masks of the
    // +-X layers -1 and n, gathered here from the rows' end blocks.
    // Stored as bytes (index z * P + y) and packed into bit columns after the pass: a byte store
    // per row instead of a read-modify-write of the column mask.
    ends_.resize(2 * (pp + 64));
    std::uint8_t* lo_end = ends_.data();
    std::uint8_t* hi_end = ends_.data() + pp + 64;
    // One pass over the ids (mesher_bitmask_rows.hpp); AVX2 where the CPU has it, for the
    // sizes with two 32-id groups per row.
    const RowMasks masks{ax, ox, az, oz, lo_end, hi_end};
    if (avx2_ && n >= 32) {
      spread_ = row_pass_avx2(ids, opaque, first_special, n, masks);
    } else {
      spread_ = row_pass<kN, kChunks>(ids, opaque, first_special, n, masks);
    }
    // Columns along y for interior x: transpose each z-slab of the x rows (rows y in [0, n)).
    // For n <= 32 two slabs share one transpose: slab zz in the low and zz + 1 in the high 32
    // bits of every word (the 32-wide transpose never moves bits across the halves).
    const int width = n <= 32 ? 32 : 64;
    const int lanes = n <= 32 ? 2 : 1;
    const std::uint64_t low_lane = lanes == 2 ? 0xffffffffULL : ~std::uint64_t{0};
    static constexpr std::uint64_t kNoSlab[64] = {};
    alignas(16) std::uint64_t a[64];
    alignas(16) std::uint64_t o[64];
    std::uint64_t* ay = ay_.data();
    std::uint64_t* oy = oy_.data();
    const std::uint64_t full = full_;
    for (int zz = 0; zz < p; zz += lanes) {
      const bool second = lanes == 2 && zz + 1 < p;
      // Rows y of slab zz are az[zz][1 .. n], contiguous.
      const std::uint64_t* sa0 = az + static_cast<std::size_t>(zz * mp + 1);
      const std::uint64_t* so0 = oz + static_cast<std::size_t>(zz * mp + 1);
      const std::uint64_t* sa1 = second ? sa0 + mp : kNoSlab;
      const std::uint64_t* so1 = second ? so0 + mp : kNoSlab;
      std::uint64_t diff = 0;  // opaque == non-air (no alpha-cut block in the slabs): one transpose
      // Slabs whose rows are each empty or full (air, solid chunks, air over a flat floor)
      // transpose to the same column for every x: the mask of the full rows (col0, col1).
      std::uint64_t col0 = 0, col1 = 0;
      bool mixed = false;
      // kTwo: two slabs share the words (n <= 32). Chunks of 33-63 know the lane count only at
      // run time: without the split they OR in a second slab of zeros (issue #18: this loop was
      // a fifth of a solid 62^3 chunk against a sixth of a 64^3 one).
      auto scan = [&](auto two) __attribute__((always_inline)) {
        constexpr bool kTwo = decltype(two)::value;
        for (int y = 0; y < n; ++y) {
          const std::uint64_t a0 = sa0[y];
          const std::uint64_t a1 = kTwo ? sa1[y] : 0;
          a[y] = a0 | a1 << 32;
          diff |= (a0 ^ so0[y]) | (kTwo ? a1 ^ so1[y] : 0);
          col0 |= static_cast<std::uint64_t>(a0 == full) << y;
          if constexpr (kTwo) col1 |= static_cast<std::uint64_t>(a1 == full) << y;
          mixed |= (a0 != 0 && a0 != full) || (kTwo && a1 != 0 && a1 != full);
        }
      };
      if (lanes == 2) {
        scan(std::true_type{});
      } else {
        scan(std::false_type{});
      }
      if (mixed || diff != 0) {
        std::fill(a + n, a + width, 0);
        transpose_bits(a, width);
        const std::uint64_t* oc = a;
        if (diff != 0) {
          for (int y = 0; y < n; ++y) o[y] = so0[y] | so1[y] << 32;
          std::fill(o + n, o + width, 0);
          transpose_bits(o, width);
          oc = o;
        }
        for (int x = 0; x < n; ++x) {
          ay[(x + 1) * mp + zz] = a[x] & low_lane;
          oy[(x + 1) * mp + zz] = oc[x] & low_lane;
        }
        if (second) {
          for (int x = 0; x < n; ++x) {
            ay[(x + 1) * mp + zz + 1] = a[x] >> 32;
            oy[(x + 1) * mp + zz + 1] = oc[x] >> 32;
          }
        }
      } else {
        for (int x = 0; x < n; ++x) {
          ay[(x + 1) * mp + zz] = col0;
          oy[(x + 1) * mp + zz] = col0;
        }
        if (second) {
          for (int x = 0; x < n; ++x) {
            ay[(x + 1) * mp + zz + 1] = col1;
            oy[(x + 1) * mp + zz + 1] = col1;
          }
        }
      }
      for (int z = zz; z < zz + (second ? 2 : 1); ++z) {
        oy[z] = bytes_to_bits(lo_end + z * p + 1, n);
        oy[(n + 1) * mp + z] = bytes_to_bits(hi_end + z * p + 1, n);
      }
    }
  }

  // True when every block of the chunk proper (the ring aside) is air; stops at the first
  // block that is not, so a chunk with ground in its lowest rows pays a few rows.
  static bool interior_empty(const PaddedBlocks& blocks) {
    const int n = blocks.n;
    const int p = n + 2;
    const BlockId* ids = blocks.ids.data();
    for (int y = 0; y < n; ++y) {
      const BlockId* layer = ids + static_cast<std::ptrdiff_t>(1 + p * (y + 1)) * p + 1;
#if defined(__SSE2__)
      if (n >= 8) {
        // The layer's rows OR-ed, tested once per layer: a per-row test (compare, movemask,
        // branch) cost as much as the row's loads (issue #18: empty 62^3 chunks 1.15x a 64^3
        // one per voxel).
        __m128i acc = _mm_setzero_si128();
        for (int z = 0; z < n; ++z) {
          const BlockId* row = layer + static_cast<std::ptrdiff_t>(z) * p;
          // The row's OR starts from its last 8 ids (overlapping the ones the loop reads when n is
          // not a multiple of 8) and joins the layer's only at the end: the rows' chains overlap.
          __m128i r = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + n - 8));
          for (int x = 0; x + 8 < n; x += 8) r = _mm_or_si128(r, _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + x)));
          acc = _mm_or_si128(acc, r);
        }
        if (_mm_movemask_epi8(_mm_cmpeq_epi8(acc, _mm_setzero_si128())) != 0xffff) return false;
        continue;
      }
#endif
      for (int z = 0; z < n; ++z) {
        const BlockId* row = layer + static_cast<std::ptrdiff_t>(z) * p;
        for (int x = 0; x < n; ++x) {
          if (row[x] != kAir) return false;
        }
      }
    }
    return true;
  }

  // nonair: bit x set when row[x] != 0; special: bit x set when row[x] >= first_special.
  // Bit i set when b[i] != 0, i in [0, n) (b readable up to 15 bytes past n).
  static std::uint64_t bytes_to_bits(const std::uint8_t* b, int n) {
    std::uint64_t bits = 0;
    int i = 0;
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    for (; i < n; i += 16) {
      const int z = _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(b + i)), zero));
      bits |= static_cast<std::uint64_t>(~z & 0xffff) << i;
    }
    return n == 64 ? bits : bits & ((std::uint64_t{1} << n) - 1);
#else
    for (; i < n; ++i) bits |= static_cast<std::uint64_t>(b[i] != 0) << i;
    return bits;
#endif
  }

  // Bit x set when row[x + 1] == row[x], x in [0, n) (row[n] is the padding block, readable).
  static std::uint64_t same_next_mask(const BlockId* row, int n) { return equal_mask(row, row + 1, n); }

  // Bit x set when a[x] == b[x], x in [0, n).
  static std::uint64_t equal_mask(const BlockId* a, const BlockId* b, int n) {
    std::uint64_t same = 0;
    int x = 0;
#if defined(__SSE2__)
    // 16 ids per step, the last step ending at id n - 1 and overlapping the one before (equal
    // bits OR-ed twice): a scalar tail made the open rows of 62^3 chunks cost 14 compares each.
    for (int c = 0; n >= 16 && c < n; c += 16) {
      x = std::min(c, n - 16);
      const __m128i v0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + x));
      const __m128i v1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + x + 8));
      const __m128i w0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + x));
      const __m128i w1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + x + 8));
      const int eq = _mm_movemask_epi8(_mm_packs_epi16(_mm_cmpeq_epi16(v0, w0), _mm_cmpeq_epi16(v1, w1)));
      same |= static_cast<std::uint64_t>(eq & 0xffff) << x;
      x = n;
    }
#endif
    for (; x < n; ++x) same |= static_cast<std::uint64_t>(a[x] == b[x]) << x;
    return same;
  }


  // Block coordinates of bit b in row r of slice s for face f (rows_x: +-Z rows along x).
  static void origin(int f, bool rows_x, int s, int r, int b, int& x, int& y, int& z) {
    switch (f >> 1) {
      case 0: x = s; y = b; z = r; break;
      case 1: x = b; y = s; z = r; break;
      default:
        x = rows_x ? r : b;
        y = rows_x ? b : r;
        z = s;
        break;
    }
  }

  // Slots of one slice (one face direction) differ only by block and uniform AO value: a table
  // indexed (block, AO & 3) stamped with the slice's number finds a slot in O(1). A linear search
  // of the keys cost ~10 % of a 3-type terrain chunk without AO, whose runs change block often.
  int find_slot(std::uint32_t key) {
    SlotRef& e = slot_index_[(key & 0xffffu) * 4 + ((key >> 19) & 3u)];
    if (e.slice == slice_stamp_) return e.slot;
    const int k = slot_count_++;
    e = SlotRef{slice_stamp_, k};
    if (keys_.size() < static_cast<std::size_t>(slot_count_)) {
      keys_.resize(static_cast<std::size_t>(slot_count_));
      rows_.resize(static_cast<std::size_t>(slot_count_) * 64, 0);
      used_.resize(static_cast<std::size_t>(slot_count_), 0);
    }
    keys_[static_cast<std::size_t>(k)] = key;
    return k;
  }

  // Emits slot k's rectangles at `list`; returns the end of what it wrote.
  PackedQuad* merge_slot(int k, int f, bool rows_x, int s, PackedQuad* list) {
    const int n = n_;
    std::uint64_t* rows = rows_.data() + static_cast<std::size_t>(k) * 64;
    const std::uint32_t key = keys_[static_cast<std::size_t>(k)];
    const std::uint64_t used_rows = std::exchange(used_[static_cast<std::size_t>(k)], 0);
    // +-Y: rows run along u (z), bits along v (x); +-Z with rows along x: u (x), v (y).
    const bool rows_are_u = (f >> 1) == 1 || rows_x;
    // Only the rows that received a face (a slot of a slice usually touches a few).
    for (std::uint64_t used = used_rows; used; used &= used - 1) {
      const int r = std::countr_zero(used);
      while (rows[r]) {
        const int b = std::countr_zero(rows[r]);
        const int w = std::countr_one(rows[r] >> b);
        const std::uint64_t run = (w == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << w) - 1)) << b;
        rows[r] &= ~run;
        int h = 1;
        while (r + h < n && (rows[r + h] & run) == run) {
          rows[r + h] &= ~run;
          ++h;
        }
        int x, y, z;
        origin(f, rows_x, s, r, b, x, y, z);
        const int du = rows_are_u ? h : w;
        const int dv = rows_are_u ? w : h;
        *list++ = PackedQuad{pack_word0(x, y, z, du, dv), key};
      }
    }
    return list;
  }

  MesherOptions options_;
  bool avx2_ = false;  // the row pass's AVX2 variant (run-time dispatch, see use_avx2())
  int n_ = 0;
  int p_ = 0;
  std::uint64_t full_ = 0;
  IdSpread spread_;        // ids of the chunk proper, from the mask pass
  BlockId single_ = kAir;  // the chunk's one plain (opaque, all-sides) block id, or kAir
  bool plain_ = false;     // every block id of the chunk is plain (no alpha cut, all sides)
  // Non-air / opaque masks over the padded P x P rows: bits along x indexed (y, z) (ax_, ox_)
  // and the same indexed (z, y) (az_, oz_); bits along y indexed (x, z) (ay_, oy_).
  std::vector<std::uint64_t> ax_, ox_, az_, oz_, ay_, oy_;
  std::vector<std::uint32_t> keys_;
  std::vector<std::uint64_t> rows_;
  std::vector<std::uint64_t> used_;
  alignas(16) std::uint64_t face_rows_[64];
  // merge_by_id() / merge_dense(): per row of a slice, the faces with no face beside them and the
  // same-id masks along the row and (merge_dense()) towards the next row.
  std::uint64_t alone_[64];
  std::uint64_t same_[64];
  std::uint64_t down_[64];
  alignas(16) std::uint64_t zslice_[64];  // +-Z rows along x: the slice's and the layer's rows
  alignas(16) std::uint64_t zlayer_[66];
  // +-X quads of this chunk written as unit quads at once / out of the merge (mesh_faces()).
  std::size_t x_unit_ = 0;
  std::size_t x_merged_ = 0;
  std::vector<std::uint8_t> ends_;  // opaque bytes of the x = -1 and x = n padding blocks, per (z, y)
  // The ChunkMesh lists being written (opaque, alpha-cut) and the quads written so far.
  std::vector<PackedQuad>* lists_[2] = {nullptr, nullptr};
  std::vector<PackedQuad>* out_[2] = {nullptr, nullptr};  // the ChunkMesh lists
  std::vector<PackedQuad> scratch_[2];
  static constexpr std::size_t kScratchQuads = 4096;  // 32 KB per list (terrain 32^3: ~3 000 quads)
  std::size_t count_[2] = {0, 0};
  std::vector<std::uint8_t> flags_;   // per block: kFlag* bits  // per slot: rows holding faces (bit r)
  int slot_count_ = 0;
  struct SlotRef {
    std::uint32_t slice = 0;  // slice_stamp_ of the slice that made the slot
    int slot = 0;
  };
  std::vector<SlotRef> slot_index_;  // per (block, uniform AO value), see find_slot()
  std::uint32_t slice_stamp_ = 0;
  // merge_dense(), bits along y: the merging faces' ids gathered per row (72: equal_mask() reads
  // up to id n of a row).
  alignas(64) BlockId id_rows_[64][72] = {};
};

}  // namespace

std::unique_ptr<Mesher> make_bitmask_mesher(const MesherOptions& options) { return std::make_unique<BitmaskMesher>(options); }

}  // namespace sylva::voxel::detail
