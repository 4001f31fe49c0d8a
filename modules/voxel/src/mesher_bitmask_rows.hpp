#pragma once
// The bitmask mesher's pass over the ids (internal, included by mesher_bitmask.cpp only): every
// padded row along x becomes a non-air and an opaque mask, stored indexed (y, z) and (z, y), plus
// the opaque bytes of the row's two ring blocks. SSE2 is the baseline (x86-64, as Debian builds);
// an AVX2 variant classifies 32 ids per step and is chosen at run time (issue #18).

#include <sylva/voxel/block.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SYLVA_VOXEL_AVX2 1
#endif

namespace sylva::voxel::detail {

// Where the pass writes, all P x P (P = n + 2) except the ends, which hold P x P bytes each.
struct RowMasks {
  std::uint64_t* ax;  // non-air, index y * P + z (padded)
  std::uint64_t* ox;  // opaque, same index
  std::uint64_t* az;  // non-air, index z * P + y
  std::uint64_t* oz;  // opaque, same index
  std::uint8_t* lo_end;  // opaque byte of the ring block x = -1, index z * P + y
  std::uint8_t* hi_end;  // same for x = n
};

// Spread of the ids of the chunk proper (the ring aside): the OR of every id and the AND of the
// non-air ones (air counted as all ones). The two are equal exactly when the chunk holds one block
// id besides air (an underground stone chunk, a one-type terrain): the face loop then groups
// faces by block without reading ids (issue #18).
struct IdSpread {
  std::uint16_t any = 0;
  std::uint16_t all = 0xffff;
  void add(BlockId id) {
    any = static_cast<std::uint16_t>(any | id);
    all = static_cast<std::uint16_t>(all & (id == kAir ? 0xffffu : id));
  }
  void add(const IdSpread& o) {
    any = static_cast<std::uint16_t>(any | o.any);
    all = static_cast<std::uint16_t>(all & o.all);
  }
  // The one non-air id of the chunk, or kAir when it holds none or several.
  BlockId single() const { return any == all ? any : kAir; }
};

#if defined(__SSE2__)
// IdSpread of the ids seen, eight lanes at a time.
struct SpreadAcc {
  __m128i any = _mm_setzero_si128();
  __m128i all = _mm_set1_epi32(-1);
  IdSpread scalar;  // ids classified one by one
  // v: eight ids; is_air: their compare with zero.
  void add(__m128i v, __m128i is_air) {
    any = _mm_or_si128(any, v);
    all = _mm_and_si128(all, _mm_or_si128(v, is_air));
  }
  IdSpread reduce() const {
    alignas(16) std::uint16_t a[8];
    alignas(16) std::uint16_t b[8];
    _mm_store_si128(reinterpret_cast<__m128i*>(a), any);
    _mm_store_si128(reinterpret_cast<__m128i*>(b), all);
    IdSpread r = scalar;
    for (int i = 0; i < 8; ++i) r.add(IdSpread{a[i], b[i]});
    return r;
  }
};
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
    // 16 ids at row + i: bit j of air / ordinary for row[i + j].
    auto classify16 = [&](int i, std::uint32_t& air, std::uint32_t& ordinary) {
      const __m128i v0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i));
      const __m128i v1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i + 8));
      const __m128i a0 = _mm_cmpeq_epi16(v0, zero);
      const __m128i a1 = _mm_cmpeq_epi16(v1, zero);
      air = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(a0, a1)));
      if (track) {
        acc.add(v0, a0);
        acc.add(v1, a1);
      }
      const __m128i s0 = _mm_cmpeq_epi16(_mm_subs_epu16(v0, limit), zero);
      const __m128i s1 = _mm_cmpeq_epi16(_mm_subs_epu16(v1, limit), zero);
      ordinary = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(s0, s1)));
    };
    if constexpr (kN == 0 && kChunks > 0) {
      for (int c = 0; c < kChunks; ++c) {
        const int i = c + 1 < kChunks ? 16 * c : n - 16;
        std::uint32_t air, ordinary;
        classify16(i, air, ordinary);
        nonair |= static_cast<std::uint64_t>(~air & 0xffff) << i;
        special |= static_cast<std::uint64_t>(~ordinary & 0xffff) << i;
      }
      return;
    }
    // 32 ids per step (one step for a 32^3 chunk's row): one movemask pair and one
    // complement per mask instead of a loop iteration per 16.
    for (; x + 32 <= n; x += 32) {
      const __m128i v0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + x));
      const __m128i v1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + x + 8));
      const __m128i v2 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + x + 16));
      const __m128i v3 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + x + 24));
      const __m128i a0 = _mm_cmpeq_epi16(v0, zero);
      const __m128i a1 = _mm_cmpeq_epi16(v1, zero);
      const __m128i a2 = _mm_cmpeq_epi16(v2, zero);
      const __m128i a3 = _mm_cmpeq_epi16(v3, zero);
      const auto air = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(a0, a1))) |
                       static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(a2, a3))) << 16;
      if (track) {
        acc.add(v0, a0);
        acc.add(v1, a1);
        acc.add(v2, a2);
        acc.add(v3, a3);
      }
      const __m128i s0 = _mm_cmpeq_epi16(_mm_subs_epu16(v0, limit), zero);
      const __m128i s1 = _mm_cmpeq_epi16(_mm_subs_epu16(v1, limit), zero);
      const __m128i s2 = _mm_cmpeq_epi16(_mm_subs_epu16(v2, limit), zero);
      const __m128i s3 = _mm_cmpeq_epi16(_mm_subs_epu16(v3, limit), zero);
      const auto ordinary = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(s0, s1))) |
                            static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(s2, s3))) << 16;
      nonair |= static_cast<std::uint64_t>(~air) << x;
      special |= static_cast<std::uint64_t>(~ordinary) << x;
    }
    for (; x + 16 <= n; x += 16) {
      std::uint32_t air, ordinary;
      classify16(x, air, ordinary);
      nonair |= static_cast<std::uint64_t>(~air & 0xffff) << x;
      special |= static_cast<std::uint64_t>(~ordinary & 0xffff) << x;
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
  for (int yy = 0; yy < p; ++yy) {
    for (int zz = 0; zz < p; ++zz) {
      const BlockId* row = ids + static_cast<std::ptrdiff_t>(zz + p * yy) * p;
      const auto k = static_cast<std::size_t>(yy * p + zz);
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
      const auto kz = static_cast<std::size_t>(zz * p + yy);
      m.az[kz] = nonair;
      m.oz[kz] = solid;
      m.lo_end[kz] = opaque[row[0]];
      m.hi_end[kz] = opaque[row[n + 1]];
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
// 32 ids at row + i: bit j of air / ordinary (below first_special) for row[i + j]. packs works
// within 128-bit lanes, so the bytes come out as ids 0-7, 16-23, 8-15, 24-31: one 64-bit lane
// permute puts them in order before the movemask.
// With track, the ids also go into any / all (IdSpread lanes).
__attribute__((target("avx2"))) inline void classify32_avx2(const BlockId* row, __m256i limit, std::uint32_t& air,
                                                            std::uint32_t& ordinary, bool track, __m256i& any,
                                                            __m256i& all) {
  const __m256i zero = _mm256_setzero_si256();
  const __m256i v0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row));
  const __m256i v1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + 16));
  const __m256i a0 = _mm256_cmpeq_epi16(v0, zero);
  const __m256i a1 = _mm256_cmpeq_epi16(v1, zero);
  if (track) {
    any = _mm256_or_si256(any, _mm256_or_si256(v0, v1));
    all = _mm256_and_si256(all, _mm256_and_si256(_mm256_or_si256(v0, a0), _mm256_or_si256(v1, a1)));
  }
  const __m256i a = _mm256_packs_epi16(a0, a1);
  air = static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_permute4x64_epi64(a, 0xd8)));
  const __m256i s = _mm256_packs_epi16(_mm256_cmpeq_epi16(_mm256_subs_epu16(v0, limit), zero),
                                       _mm256_cmpeq_epi16(_mm256_subs_epu16(v1, limit), zero));
  ordinary = static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_permute4x64_epi64(s, 0xd8)));
}

// Rows of 32 to 64 ids: two groups of 32, the second ending at row[n - 1] (overlapping the first
// for n < 64; shared bits are equal).
struct ClassifyAvx2 {
  __m256i any;  // IdSpread lanes, set by start()
  __m256i all;
  __attribute__((target("avx2"))) void start() {
    any = _mm256_setzero_si256();
    all = _mm256_set1_epi32(-1);
  }
  __attribute__((target("avx2"))) void operator()(const BlockId* row, int n, BlockId first_special,
                                                  std::uint64_t& nonair, std::uint64_t& special, bool interior) {
    const __m256i limit = _mm256_set1_epi16(static_cast<short>(static_cast<std::uint16_t>(first_special - 1)));
    std::uint32_t air0, ord0, air1, ord1;
    classify32_avx2(row, limit, air0, ord0, interior, any, all);
    classify32_avx2(row + n - 32, limit, air1, ord1, interior, any, all);
    nonair = static_cast<std::uint64_t>(~air0) | static_cast<std::uint64_t>(~air1) << (n - 32);
    special = static_cast<std::uint64_t>(~ord0) | static_cast<std::uint64_t>(~ord1) << (n - 32);
  }
  __attribute__((target("avx2"))) IdSpread spread() const {
    SpreadAcc acc;
    acc.any = _mm_or_si128(_mm256_castsi256_si128(any), _mm256_extracti128_si256(any, 1));
    acc.all = _mm_and_si128(_mm256_castsi256_si128(all), _mm256_extracti128_si256(all, 1));
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
