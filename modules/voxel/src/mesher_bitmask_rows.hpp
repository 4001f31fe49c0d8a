#pragma once
// The bitmask mesher's pass over the ids (internal, included by mesher_bitmask.cpp only): every
// padded row along x becomes a non-air and an opaque mask, stored indexed (y, z) and (z, y), plus
// the opaque bytes of the row's two ring blocks. SSE2 is the baseline (x86-64, as Debian builds);
// an AVX2 variant classifies 32 ids per step and is chosen at run time (issue #18).

#include <sylva/voxel/block.hpp>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SYLVA_VOXEL_AVX2 1
#endif

namespace sylva::voxel::detail {

// Pitch of the P x P mask arrays (P = n + 2): with P a multiple of 32 (62^3 chunks: 64) a step
// across rows, 512 bytes, kept every column walk (the pass's (z, y) stores, the transposes'
// columns, the +-Z gathers) in 8 of the 64 L1 sets; one more word spreads them (issue #18,
// bench_voxel_mesher, 3 interleaved rounds: 62^3 solid 1.14-1.17x a 64^3 chunk per voxel ->
// 1.09-1.10x, hills 2-6 % faster). Other sizes keep P (64^3 chunks: the same code, within the
// noise of the same runs, 0.88-1.06).
inline int mask_pitch(int p) { return p % 32 == 0 ? p + 1 : p; }

// Where the pass writes: P x M masks (M = mask_pitch(P)), and the ends, P x P bytes each.
struct RowMasks {
  std::uint64_t* ax;  // non-air, index y * M + z (padded)
  std::uint64_t* ox;  // opaque, same index
  std::uint64_t* az;  // non-air, index z * M + y
  std::uint64_t* oz;  // opaque, same index
  std::uint8_t* lo_end;  // opaque byte of the ring block x = -1, index z * P + y
  std::uint8_t* hi_end;  // same for x = n
};

// Spread of the ids of the chunk proper (the ring aside): the OR of every id and the AND of
// every id minus one (16-bit wrap: air counts as all ones). The two agree (any - 1 == all_m1)
// exactly when the chunk holds one block id besides air (an underground stone chunk, a one-type
// terrain): each non-air id v has v <= any (a subset of its bits) and v - 1 >= any - 1 (a
// superset), so v == any. The face loop then groups faces by block without reading ids (issue
// #18). Minus one rather than "v, or all ones for air" spares the vector passes an air compare.
struct IdSpread {
  std::uint16_t any = 0;
  std::uint16_t all_m1 = 0xffff;
  void add(BlockId id) {
    any = static_cast<std::uint16_t>(any | id);
    all_m1 = static_cast<std::uint16_t>(all_m1 & static_cast<std::uint16_t>(id - 1));
  }
  void add(const IdSpread& o) {
    any = static_cast<std::uint16_t>(any | o.any);
    all_m1 = static_cast<std::uint16_t>(all_m1 & o.all_m1);
  }
  // The one non-air id of the chunk, or kAir when it holds none or several.
  BlockId single() const { return static_cast<std::uint16_t>(any - 1) == all_m1 ? any : kAir; }
};

#if defined(__SSE2__)
// IdSpread of the ids seen, eight lanes at a time.
struct SpreadAcc {
  __m128i any = _mm_setzero_si128();
  __m128i all_m1 = _mm_set1_epi32(-1);
  IdSpread scalar;  // ids classified one by one
  // Sixteen ids, of which the caller ORs into `any` itself (a row's OR at once, see
  // classify_row()).
  void add_all(__m128i v0, __m128i v1) {
    const __m128i ones = _mm_set1_epi32(-1);
    all_m1 = _mm_and_si128(all_m1, _mm_and_si128(_mm_add_epi16(v0, ones), _mm_add_epi16(v1, ones)));
  }
  IdSpread reduce() const {
    alignas(16) std::uint16_t a[8];
    alignas(16) std::uint16_t b[8];
    _mm_store_si128(reinterpret_cast<__m128i*>(a), any);
    _mm_store_si128(reinterpret_cast<__m128i*>(b), all_m1);
    IdSpread r = scalar;
    for (int i = 0; i < 8; ++i) r.add(IdSpread{a[i], b[i]});
    return r;
  }
};

// Bits of the ids >= first_special among 16 ids per group at row + 16 c (the last group ending
// at row + covered - 1, overlapping the one before; covered >= 16): the slow half of a row's
// classification, run only for rows holding such an id (alpha-cut blocks: leaves, glass).
inline std::uint64_t special_bits(const BlockId* row, int covered, __m128i limit) {
  const __m128i zero = _mm_setzero_si128();
  std::uint64_t special = 0;
  for (int c = 0; c < covered; c += 16) {
    const int i = std::min(c, covered - 16);
    const __m128i v0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i));
    const __m128i v1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i + 8));
    const __m128i s0 = _mm_cmpeq_epi16(_mm_subs_epu16(v0, limit), zero);
    const __m128i s1 = _mm_cmpeq_epi16(_mm_subs_epu16(v1, limit), zero);
    const auto ordinary = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(s0, s1)));
    special |= static_cast<std::uint64_t>(~ordinary & 0xffff) << i;
  }
  return special;
}
#else
struct SpreadAcc {
  IdSpread scalar;
  IdSpread reduce() const { return scalar; }
};
#endif

// The AVX2 pass may be used: the CPU has AVX2 and SYLVA_VOXEL_NO_AVX2 is unset (the variable
// lets the tests and benchmarks run the SSE2 pass on any machine).
inline bool use_avx2() {
#if defined(SYLVA_VOXEL_AVX2)
  return __builtin_cpu_supports("avx2") && std::getenv("SYLVA_VOXEL_NO_AVX2") == nullptr;
#else
  return false;
#endif
}

// kChunks (sizes other than 32 and 64, n >= 16): the row is read as kChunks groups of 16 ids,
// the last one ending at row[n - 1] and overlapping the one before (the bits they share are
// equal, so OR-ing them is harmless). A fixed count unrolls like the specialised sizes: with a
// run-time loop and a scalar tail, 62^3 chunks cost 1.4x a 64^3 one per voxel (issue #18).
// With track, the ids also go into acc.
// Per 16 ids the vector part is two loads, a signed saturating pack (zero exactly for air: a
// non-zero id packs to a non-zero byte), one byte compare and one movemask, and the OR of the
// ids. Ids >= first_special are only looked for (special_bits()) in rows whose OR reaches
// first_special: no id of the row can otherwise (the OR is at least each id), and the
// common terrain ids OR below the first alpha-cut id (issue #18: the SSE2 baseline's row pass
// was 13 us of a 62^3 terrain chunk behind AVX2's).
template <int kN, int kChunks>
inline void classify_row(const BlockId* row, int n_run, BlockId first_special, std::uint64_t& nonair,
                         std::uint64_t& special, SpreadAcc& acc, bool track) {
  const int n = kN > 0 ? kN : n_run;
  int x = 0;
#if defined(__SSE2__)
  {
    const __m128i zero = _mm_setzero_si128();
    // v - (first_special - 1), saturated at 0, is zero exactly for the ids below first_special.
    const __m128i limit = _mm_set1_epi16(static_cast<short>(static_cast<std::uint16_t>(first_special - 1)));
    __m128i row_or = zero;  // OR of the ids read
    // 16 ids at row + i: bit j of the result is set when row[i + j] is air. (track_ids: a bool
    // or std::bool_constant.)
    auto air16 = [&](int i, auto track_ids) -> std::uint32_t {
      const __m128i v0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i));
      const __m128i v1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i + 8));
      if (static_cast<bool>(track_ids)) acc.add_all(v0, v1);
      row_or = _mm_or_si128(row_or, _mm_or_si128(v0, v1));
      return static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_packs_epi16(v0, v1), zero)));
    };
    if constexpr (kN == 0 && kChunks > 0) {
      // Unrolled, once per value of track: GCC -O2 kept this a loop with a test of track and
      // a variable shift per 16 ids (issue #18: the SSE2-only pass of a solid 62^3 chunk was
      // 1.36x a 64^3 one per voxel).
      auto groups = [&](auto track_ids) {
        std::uint64_t bits = 0;
#pragma GCC unroll 4
        for (int c = 0; c < kChunks; ++c) {
          const int i = c + 1 < kChunks ? 16 * c : n - 16;
          bits |= static_cast<std::uint64_t>(~air16(i, track_ids) & 0xffff) << i;
        }
        return bits;
      };
      nonair |= track ? groups(std::true_type{}) : groups(std::false_type{});
      x = n;
    } else {
      // 32 ids per step (one step for a 32^3 chunk's row): one complement per mask instead of
      // a loop iteration per 16.
      for (; x + 32 <= n; x += 32) {
        nonair |= static_cast<std::uint64_t>(~(air16(x, track) | air16(x + 16, track) << 16)) << x;
      }
      for (; x + 16 <= n; x += 16) nonair |= static_cast<std::uint64_t>(~air16(x, track) & 0xffff) << x;
    }
    if (track) acc.any = _mm_or_si128(acc.any, row_or);
    if (x > 0 && _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_subs_epu16(row_or, limit), zero)) != 0xffff) {
      special |= special_bits(row, x, limit);
    }
  }
#endif
  for (; x < n; ++x) {
    nonair |= static_cast<std::uint64_t>(row[x] != kAir) << x;
    special |= static_cast<std::uint64_t>(row[x] >= first_special) << x;
    if (track) acc.scalar.add(row[x]);
  }
}

// The pass itself, with the row classification as a parameter: classify(row, n, first_special,
// nonair, special, interior) classifies a row and, for the rows of the chunk proper (interior),
// adds its ids to the spread that classify.spread() returns, which the pass returns. (classify
// is a local copy, so that its accumulators can stay in registers.)
template <int kN, class Classify>
inline IdSpread row_pass_with(const BlockId* ids, const std::uint8_t* opaque, BlockId first_special, int n_run,
                              const RowMasks& m, Classify classify) {
  const int n = kN > 0 ? kN : n_run;
  const int p = n + 2;
  const int mp = mask_pitch(p);
  for (int yy = 0; yy < p; ++yy) {
    for (int zz = 0; zz < p; ++zz) {
      const BlockId* row = ids + static_cast<std::ptrdiff_t>(zz + p * yy) * p;
      const auto k = static_cast<std::size_t>(yy * mp + zz);
      std::uint64_t nonair = 0;
      std::uint64_t special = 0;  // ids >= first alpha-cut id: classified by table below
      const bool interior = static_cast<unsigned>(yy - 1) < static_cast<unsigned>(n) &&
                            static_cast<unsigned>(zz - 1) < static_cast<unsigned>(n);
      classify(row + 1, n, first_special, nonair, special, interior);
      std::uint64_t alpha = 0;
      for (std::uint64_t s = special; s;) {
        const int b = std::countr_zero(s);
        s &= s - 1;
        if (!opaque[row[1 + b]]) alpha |= std::uint64_t{1} << b;
      }
      const std::uint64_t solid = nonair & ~alpha;
      m.ax[k] = nonair;
      m.ox[k] = solid;
      // The same masks indexed (z, y), so +-Z slices read their rows contiguously too.
      const auto kz = static_cast<std::size_t>(zz * mp + yy);
      m.az[kz] = nonair;
      m.oz[kz] = solid;
      const auto ke = static_cast<std::size_t>(zz * p + yy);
      m.lo_end[ke] = opaque[row[0]];
      m.hi_end[ke] = opaque[row[n + 1]];
    }
  }
  return classify.spread();
}

template <int kN, int kChunks>
struct ClassifySse2 {
  SpreadAcc acc;
  __attribute__((always_inline)) void operator()(const BlockId* row, int n, BlockId first_special,
                                                 std::uint64_t& nonair, std::uint64_t& special, bool interior) {
    classify_row<kN, kChunks>(row, n, first_special, nonair, special, acc, interior);
  }
  IdSpread spread() const { return acc.reduce(); }
};

template <int kN, int kChunks>
inline IdSpread row_pass(const BlockId* ids, const std::uint8_t* opaque, BlockId first_special, int n,
                         const RowMasks& m) {
  return row_pass_with<kN>(ids, opaque, first_special, n, m, ClassifySse2<kN, kChunks>{});
}

#if defined(SYLVA_VOXEL_AVX2)
// 32 ids at row: bit j of the result is set when row[j] is air (the pack as in classify_row();
// packs works within 128-bit lanes, so the bytes come out as ids 0-7, 16-23, 8-15, 24-31: one
// 64-bit lane permute puts them in order before the movemask).
// The ids are OR-ed into row_or; with track, they go into all_m1 (IdSpread lanes).
__attribute__((target("avx2"))) inline std::uint32_t air32_avx2(const BlockId* row, bool track, __m256i& all_m1,
                                                                __m256i& row_or) {
  const __m256i v0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row));
  const __m256i v1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + 16));
  if (track) {
    const __m256i ones = _mm256_set1_epi32(-1);
    all_m1 = _mm256_and_si256(all_m1, _mm256_and_si256(_mm256_add_epi16(v0, ones), _mm256_add_epi16(v1, ones)));
  }
  row_or = _mm256_or_si256(row_or, _mm256_or_si256(v0, v1));
  const __m256i air = _mm256_cmpeq_epi8(_mm256_packs_epi16(v0, v1), _mm256_setzero_si256());
  return static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_permute4x64_epi64(air, 0xd8)));
}

// Rows of 32 to 64 ids: two groups of 32, the second ending at row[n - 1] (overlapping the first
// for n < 64; shared bits are equal).
struct ClassifyAvx2 {
  __m256i any;  // IdSpread lanes, set by start()
  __m256i all_m1;
  __attribute__((target("avx2"))) void start() {
    any = _mm256_setzero_si256();
    all_m1 = _mm256_set1_epi32(-1);
  }
  __attribute__((target("avx2"))) void operator()(const BlockId* row, int n, BlockId first_special,
                                                  std::uint64_t& nonair, std::uint64_t& special, bool interior) {
    const __m256i limit = _mm256_set1_epi16(static_cast<short>(static_cast<std::uint16_t>(first_special - 1)));
    __m256i row_or = _mm256_setzero_si256();
    const std::uint32_t air0 = air32_avx2(row, interior, all_m1, row_or);
    const std::uint32_t air1 = air32_avx2(row + n - 32, interior, all_m1, row_or);
    if (interior) any = _mm256_or_si256(any, row_or);
    nonair = static_cast<std::uint64_t>(~air0) | static_cast<std::uint64_t>(~air1) << (n - 32);
    special = 0;
    // As in classify_row(): only rows whose OR reaches first_special can hold such an id.
    const __m256i above = _mm256_subs_epu16(row_or, limit);
    if (!_mm256_testz_si256(above, above)) special = special_bits(row, n, _mm256_castsi256_si128(limit));
  }
  __attribute__((target("avx2"))) IdSpread spread() const {
    SpreadAcc acc;
    acc.any = _mm_or_si128(_mm256_castsi256_si128(any), _mm256_extracti128_si256(any, 1));
    acc.all_m1 = _mm_and_si128(_mm256_castsi256_si128(all_m1), _mm256_extracti128_si256(all_m1, 1));
    return acc.reduce();
  }
};

// flatten: the row loop and the classification are inlined here, compiled for AVX2.
__attribute__((target("avx2"), flatten)) inline IdSpread row_pass_avx2(const BlockId* ids, const std::uint8_t* opaque,
                                                                        BlockId first_special, int n, const RowMasks& m) {
  ClassifyAvx2 classify;
  classify.start();
  return row_pass_with<0>(ids, opaque, first_special, n, m, classify);
}
#else
inline IdSpread row_pass_avx2(const BlockId* ids, const std::uint8_t* opaque, BlockId first_special, int n,
                              const RowMasks& m) {
  return row_pass<0, 0>(ids, opaque, first_special, n, m);
}
#endif

}  // namespace sylva::voxel::detail
