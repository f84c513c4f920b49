// Lane types and the operations every kernel is written with.
//
// A kernel is a template over the number type F: `float` (one ray, the
// reference), or an xsimd batch of 4, 8 or 16 floats. Masks are `bool` or
// `batch_bool`. Every function here gives the same bits for a lane of a
// batch as for the same float, so the scalar path checks the SIMD path:
//   - select-based min/max (NaN and signed-zero behaviour identical),
//   - a fused multiply-add at every width (std::fma, vfmadd),
//   - IEEE sqrt and division only (no reciprocal approximations).
//
// Lane types per kernel unit (CMake builds each with its own flags):
//   scalar:     float                            (baseline x86-64, the reference)
//   scalar_fma: float                            (-mfma: fma is an instruction)
//   sse4:       xsimd::batch<float, sse4_2>      (-msse4.2 -mfma: FMA3 is required
//                                                 so that fma is fused as in scalar code)
//   avx2:       xsimd::batch<float, fma3<avx2>>  (-mavx2 -mfma)
//   avx512:     xsimd::batch<float, avx512bw>    (-mavx512f/cd/dq/bw/vl -mfma; 16 lanes,
//                                                 masks are k-registers)
// The streams (geometry/streams.h) carry the unit as a template argument and
// are flattened, so no kernel code compiled with one unit's flags is shared
// through the linker with another unit.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

// GCC 12 reports the deliberately undefined source of AVX-512 intrinsics
// (_mm512_undefined_ps) as uninitialized (GCC bug 105593).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <xsimd/xsimd.hpp>
#pragma GCC diagnostic pop

#include "simd/isa.h"
#include "simd/vec3.h"

#if defined(__SSE4_2__) && defined(__FMA__)
#include <immintrin.h>
#endif

namespace quiver {

// Widest lane count any unit uses; SoA arrays are padded to a multiple of it.
inline constexpr int kMaxLanes = 16;

template <class F>
struct LaneTraits;

template <>
struct LaneTraits<float> {
  using Mask = bool;
  using Int = std::int32_t;
  static constexpr int width = 1;
};

template <class A>
struct LaneTraits<xsimd::batch<float, A>> {
  using Mask = xsimd::batch_bool<float, A>;
  using Int = xsimd::batch<std::int32_t, A>;
  static constexpr int width = static_cast<int>(xsimd::batch<float, A>::size);
};

template <class F>
using Mask = typename LaneTraits<F>::Mask;
template <class F>
using IntLanes = typename LaneTraits<F>::Int;
template <class F>
inline constexpr int lane_count = LaneTraits<F>::width;

// Kernel unit -> lane type; a vector unit's type exists only in code
// compiled with that unit's flags.
template <KernelUnit U>
struct UnitLanesOf {
  using type = float;  // scalar and scalar_fma
};
#if XSIMD_WITH_SSE4_2 && defined(__FMA__)
template <>
struct UnitLanesOf<KernelUnit::sse4> {
  using type = xsimd::batch<float, xsimd::sse4_2>;
};
#endif
#if XSIMD_WITH_FMA3_AVX2
template <>
struct UnitLanesOf<KernelUnit::avx2> {
  using type = xsimd::batch<float, xsimd::fma3<xsimd::avx2>>;
};
#endif
#if XSIMD_WITH_AVX512BW
template <>
struct UnitLanesOf<KernelUnit::avx512> {
  using type = xsimd::batch<float, xsimd::avx512bw>;
};
#endif
template <KernelUnit U>
using UnitLanes = typename UnitLanesOf<U>::type;

inline namespace QUIVER_UNIT_NAMESPACE {

// ---- scalar forms -------------------------------------------------------

inline float select(bool m, float a, float b) { return m ? a : b; }
inline std::int32_t select(bool m, std::int32_t a, std::int32_t b) { return m ? a : b; }
inline float fma(float a, float b, float c) { return std::fma(a, b, c); }
inline float sqrt(float a) { return std::sqrt(a); }
inline float abs(float a) { return std::fabs(a); }
inline float copysign(float magnitude, float sign) { return std::copysign(magnitude, sign); }
inline bool any(bool m) { return m; }
inline bool all(bool m) { return m; }
inline bool none(bool m) { return !m; }
inline bool and_not(bool a, bool b) { return a && !b; }
inline bool isfinite_lanes(float a) { return std::isfinite(a); }

// ---- batch forms --------------------------------------------------------

template <class A>
inline xsimd::batch<float, A> select(const xsimd::batch_bool<float, A>& m,
                                     const xsimd::batch<float, A>& a,
                                     const xsimd::batch<float, A>& b) {
  return xsimd::select(m, a, b);
}

// The float mask's register reinterpreted as an int mask (xsimd's
// bitwise_cast of a batch_bool is a select, not a reinterpretation).
#if defined(__SSE4_2__) && defined(__FMA__)
inline xsimd::batch_bool<std::int32_t, xsimd::sse4_2> int_mask(const xsimd::batch_bool<float, xsimd::sse4_2>& m) {
  return _mm_castps_si128(m);
}
#endif
#if XSIMD_WITH_FMA3_AVX2
inline xsimd::batch_bool<std::int32_t, xsimd::fma3<xsimd::avx2>> int_mask(
    const xsimd::batch_bool<float, xsimd::fma3<xsimd::avx2>>& m) {
  return _mm256_castps_si256(m);
}
#endif
#if XSIMD_WITH_AVX512BW
inline xsimd::batch_bool<std::int32_t, xsimd::avx512bw> int_mask(const xsimd::batch_bool<float, xsimd::avx512bw>& m) {
  return static_cast<__mmask16>(m);
}
#endif

// a && !b. (xsimd 8.1 negates an AVX float mask by comparing each 128-bit
// half with false, four instructions; andnot is one.)
#if defined(__SSE4_2__) && defined(__FMA__)
inline xsimd::batch_bool<float, xsimd::sse4_2> and_not(const xsimd::batch_bool<float, xsimd::sse4_2>& a,
                                                       const xsimd::batch_bool<float, xsimd::sse4_2>& b) {
  return _mm_andnot_ps(b, a);
}
#endif
#if XSIMD_WITH_FMA3_AVX2
inline xsimd::batch_bool<float, xsimd::fma3<xsimd::avx2>> and_not(
    const xsimd::batch_bool<float, xsimd::fma3<xsimd::avx2>>& a,
    const xsimd::batch_bool<float, xsimd::fma3<xsimd::avx2>>& b) {
  return _mm256_andnot_ps(b, a);
}
#endif
#if XSIMD_WITH_AVX512BW
inline xsimd::batch_bool<float, xsimd::avx512bw> and_not(const xsimd::batch_bool<float, xsimd::avx512bw>& a,
                                                         const xsimd::batch_bool<float, xsimd::avx512bw>& b) {
  return static_cast<__mmask16>(static_cast<__mmask16>(a) & ~static_cast<__mmask16>(b));
}
#endif

template <class A>
inline xsimd::batch<std::int32_t, A> select(const xsimd::batch_bool<float, A>& m,
                                            const xsimd::batch<std::int32_t, A>& a,
                                            const xsimd::batch<std::int32_t, A>& b) {
  return xsimd::select(int_mask(m), a, b);
}

template <class A>
inline xsimd::batch<float, A> fma(const xsimd::batch<float, A>& a, const xsimd::batch<float, A>& b,
                                  const xsimd::batch<float, A>& c) {
  return xsimd::fma(a, b, c);
}

#if XSIMD_WITH_SSE4_2 && defined(__FMA__)
// xsimd's sse4_2 fma is a multiply then an add; fuse it as std::fma does.
inline xsimd::batch<float, xsimd::sse4_2> fma(const xsimd::batch<float, xsimd::sse4_2>& a,
                                              const xsimd::batch<float, xsimd::sse4_2>& b,
                                              const xsimd::batch<float, xsimd::sse4_2>& c) {
  return _mm_fmadd_ps(a, b, c);
}
#endif
#if XSIMD_WITH_AVX512BW
// xsimd 8.1 has no AVX-512 fma: its generic one multiplies, then adds.
inline xsimd::batch<float, xsimd::avx512bw> fma(const xsimd::batch<float, xsimd::avx512bw>& a,
                                                const xsimd::batch<float, xsimd::avx512bw>& b,
                                                const xsimd::batch<float, xsimd::avx512bw>& c) {
  return _mm512_fmadd_ps(a, b, c);
}
#endif

template <class A>
inline xsimd::batch<float, A> sqrt(const xsimd::batch<float, A>& a) {
  return xsimd::sqrt(a);
}
template <class A>
inline xsimd::batch<float, A> abs(const xsimd::batch<float, A>& a) {
  return xsimd::abs(a);
}
template <class A>
inline xsimd::batch<float, A> copysign(const xsimd::batch<float, A>& magnitude, const xsimd::batch<float, A>& sign) {
  return xsimd::copysign(magnitude, sign);
}
template <class A>
inline bool any(const xsimd::batch_bool<float, A>& m) {
  return xsimd::any(m);
}
template <class A>
inline bool all(const xsimd::batch_bool<float, A>& m) {
  return xsimd::all(m);
}
template <class A>
inline bool none(const xsimd::batch_bool<float, A>& m) {
  return xsimd::none(m);
}
template <class A>
inline xsimd::batch_bool<float, A> isfinite_lanes(const xsimd::batch<float, A>& a) {
  // |a| <= max finite is false for NaN and for +-inf.
  return xsimd::abs(a) <= xsimd::batch<float, A>(3.40282347e+38f);
}

// Int lanes != 0 as a float mask: every non-zero int32 converts to a
// non-zero float. (Not via all-ones bits as a NaN: xsimd 8.1's AVX != is an
// ordered compare, false for NaN.)
template <class A>
inline xsimd::batch_bool<float, A> nonzero_lanes(const xsimd::batch<std::int32_t, A>& i) {
  return xsimd::to_float(i) != xsimd::batch<float, A>(0.f);
}
inline bool nonzero_lanes(std::int32_t i) { return i != 0; }

// a < b for int lanes (hit ids), as a float mask. The difference cannot
// overflow for ids in [-1, 2^31 - 1); its sign survives the conversion.
inline bool int_less(std::int32_t a, std::int32_t b) { return a < b; }
template <class A>
inline xsimd::batch_bool<float, A> int_less(const xsimd::batch<std::int32_t, A>& a,
                                            const xsimd::batch<std::int32_t, A>& b) {
  return xsimd::to_float(b - a) > xsimd::batch<float, A>(0.f);
}

// a != b for masks. Never write != or == between masks: xsimd 8.1's SSE
// batch_bool comparison treats the all-ones lanes as floats (NaNs), so
// true != true there; xor is right at every width.
inline bool masks_differ(bool a, bool b) { return a != b; }
template <class A>
inline xsimd::batch_bool<float, A> masks_differ(const xsimd::batch_bool<float, A>& a,
                                                const xsimd::batch_bool<float, A>& b) {
  return a ^ b;
}
#if XSIMD_WITH_AVX512BW
// xsimd 8.1's AVX-512 mask xor is an or (bitwise_xor in xsimd_avx512f.hpp): xor the k-registers.
inline xsimd::batch_bool<float, xsimd::avx512bw> masks_differ(const xsimd::batch_bool<float, xsimd::avx512bw>& a,
                                                              const xsimd::batch_bool<float, xsimd::avx512bw>& b) {
  return static_cast<__mmask16>(static_cast<__mmask16>(a) ^ static_cast<__mmask16>(b));
}
#endif

// ---- written once for every width ----------------------------------------

// min/max as selects: identical bits for NaN and +-0 at every width.
template <class F>
inline F min(const F& a, const F& b) {
  return select(b < a, b, a);
}
template <class F>
inline F max(const F& a, const F& b) {
  return select(a < b, b, a);
}

// a*b - c*d with one rounding error bound (Kahan's algorithm via fma).
template <class F>
inline F difference_of_products(const F& a, const F& b, const F& c, const F& d) {
  const F cd = c * d;
  const F error = fma(-c, d, cd);  // exact rounding error of c*d
  const F dop = fma(a, b, -cd);
  return dop + error;
}

// ---- memory <-> lanes (arrays 64-byte aligned, padded to kMaxLanes) ------

template <class F>
inline F load_lanes(const float* p) {
  if constexpr (lane_count<F> == 1) {
    return *p;
  } else {
    return F::load_aligned(p);
  }
}
template <class F>
inline IntLanes<F> load_int_lanes(const std::int32_t* p) {
  if constexpr (lane_count<F> == 1) {
    return *p;
  } else {
    return IntLanes<F>::load_aligned(p);
  }
}
template <class F>
inline void store_lanes(const F& v, float* p) {
  if constexpr (lane_count<F> == 1) {
    *p = v;
  } else {
    v.store_aligned(p);
  }
}
template <class F>
inline void store_int_lanes(const IntLanes<F>& v, std::int32_t* p) {
  if constexpr (lane_count<F> == 1) {
    *p = v;
  } else {
    v.store_aligned(p);
  }
}

// table[index] per lane (a gather; the indices must be in range in every lane).
template <class F>
inline F gather_lanes(const float* table, const IntLanes<F>& index) {
  if constexpr (lane_count<F> == 1) {
    return table[index];
  } else {
    return F::gather(table, index);
  }
}

// Loads from any float address (a leaf of a primitive store starts anywhere).
template <class F>
inline F load_lanes_unaligned(const float* p) {
  if constexpr (lane_count<F> == 1) {
    return *p;
  } else {
    return F::load_unaligned(p);
  }
}

// Bit k set iff lane k of the mask is set.
inline unsigned lane_bits(bool m) { return m ? 1u : 0u; }
#if defined(__SSE4_2__) && defined(__FMA__)
inline unsigned lane_bits(const xsimd::batch_bool<float, xsimd::sse4_2>& m) {
  return static_cast<unsigned>(_mm_movemask_ps(m));  // the mask register itself
}
#endif
#if XSIMD_WITH_FMA3_AVX2
inline unsigned lane_bits(const xsimd::batch_bool<float, xsimd::fma3<xsimd::avx2>>& m) {
  return static_cast<unsigned>(_mm256_movemask_ps(m));  // the mask register itself
}
#endif
#if XSIMD_WITH_AVX512BW
inline unsigned lane_bits(const xsimd::batch_bool<float, xsimd::avx512bw>& m) {
  return static_cast<__mmask16>(m);  // the k-register itself
}
#endif

// The mask whose lane k is bit k of `bits` (lane_bits' inverse): the bits
// broadcast and tested per lane (per-lane stores and a wide load would not
// be store-forwarded); in AVX-512 the k-register itself.
template <class F>
inline Mask<F> mask_from_bits(unsigned bits) {
  if constexpr (lane_count<F> == 1) {
    return (bits & 1u) != 0;
#if XSIMD_WITH_AVX512BW
  } else if constexpr (std::is_same_v<F, xsimd::batch<float, xsimd::avx512bw>>) {
    return Mask<F>(static_cast<__mmask16>(bits));
#endif
  } else {
    alignas(64) static constexpr std::int32_t kLaneBit[kMaxLanes] = {
        1 << 0, 1 << 1, 1 << 2,  1 << 3,  1 << 4,  1 << 5,  1 << 6,  1 << 7,
        1 << 8, 1 << 9, 1 << 10, 1 << 11, 1 << 12, 1 << 13, 1 << 14, 1 << 15};
    return nonzero_lanes(IntLanes<F>(static_cast<std::int32_t>(bits)) & load_int_lanes<F>(kLaneBit));
  }
}

// Floats compared through their bits as signed ints: +0 to +inf order as
// they do as floats, every float with the sign bit set (negatives, -0,
// NaNs from x86 arithmetic) lies below them, and a NaN with the sign bit
// clear above +inf. Integer max and min have a latency of one cycle where
// the float ones have four on Intel cores since Skylake (Intel's optimization
// manual; Embree's node tests use them the same way).
inline std::int32_t float_bits(float x) { return std::bit_cast<std::int32_t>(x); }
inline float float_of_bits(std::int32_t i) { return std::bit_cast<float>(i); }
inline std::int32_t bits_max(std::int32_t a, std::int32_t b) { return a < b ? b : a; }
inline std::int32_t bits_min(std::int32_t a, std::int32_t b) { return b < a ? b : a; }
// Bit k set iff a <= b in lane k.
inline unsigned bits_at_most(std::int32_t a, std::int32_t b) { return a <= b ? 1u : 0u; }
template <class A>
inline xsimd::batch<std::int32_t, A> float_bits(const xsimd::batch<float, A>& x) {
  return xsimd::bitwise_cast<xsimd::batch<std::int32_t, A>>(x);
}
template <class A>
inline xsimd::batch<float, A> float_of_bits(const xsimd::batch<std::int32_t, A>& i) {
  return xsimd::bitwise_cast<xsimd::batch<float, A>>(i);
}
template <class A>
inline xsimd::batch<std::int32_t, A> bits_max(const xsimd::batch<std::int32_t, A>& a,
                                              const xsimd::batch<std::int32_t, A>& b) {
  return xsimd::max(a, b);
}
template <class A>
inline xsimd::batch<std::int32_t, A> bits_min(const xsimd::batch<std::int32_t, A>& a,
                                              const xsimd::batch<std::int32_t, A>& b) {
  return xsimd::min(a, b);
}
// (SSE and AVX2: a > b's sign bits, flipped by one xor; AVX-512: one compare into a mask register.)
#if defined(__SSE4_2__) && defined(__FMA__)
inline unsigned bits_at_most(const xsimd::batch<std::int32_t, xsimd::sse4_2>& a,
                             const xsimd::batch<std::int32_t, xsimd::sse4_2>& b) {
  return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(a, b)))) ^ 0xfu;
}
#endif
#if XSIMD_WITH_FMA3_AVX2
inline unsigned bits_at_most(const xsimd::batch<std::int32_t, xsimd::fma3<xsimd::avx2>>& a,
                             const xsimd::batch<std::int32_t, xsimd::fma3<xsimd::avx2>>& b) {
#if defined(__AVX512VL__)
  return _mm256_cmple_epi32_mask(a, b);  // the AVX-512 unit's 8-lane node tests
#else
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(a, b)))) ^ 0xffu;
#endif
}
#endif
#if XSIMD_WITH_AVX512BW
inline unsigned bits_at_most(const xsimd::batch<std::int32_t, xsimd::avx512bw>& a,
                             const xsimd::batch<std::int32_t, xsimd::avx512bw>& b) {
  return _mm512_cmple_epi32_mask(a, b);
}
#endif

// The smallest float greater than t (t itself for +inf and NaN): with it as
// a kernel's exclusive tmax, a hit at exactly t is still reported.
inline float next_float_up(float t) {
  if (!(t < std::numeric_limits<float>::infinity())) return t;
  if (t == 0.f) return std::numeric_limits<float>::denorm_min();
  const std::int32_t bits = std::bit_cast<std::int32_t>(t);
  return std::bit_cast<float>(t > 0.f ? bits + 1 : bits - 1);
}
template <class A>
inline xsimd::batch<float, A> next_float_up(const xsimd::batch<float, A>& t) {
  using Int = xsimd::batch<std::int32_t, A>;
  using Float = xsimd::batch<float, A>;
  const Int bits = xsimd::bitwise_cast<Int>(t);
  // Positive (and +0): one more in the bit pattern; negative: one less; -0: the smallest positive.
  const Int up = select(t > Float(0.f), bits + Int(1), bits - Int(1));
  const Float stepped = select(t == Float(0.f), Float(std::numeric_limits<float>::denorm_min()),
                               xsimd::bitwise_cast<Float>(up));
  return select(t < Float(std::numeric_limits<float>::infinity()), stepped, t);
}

// The smallest lane, for lanes without NaN (min by halves).
inline float horizontal_min(float v) { return v; }
#if defined(__SSE4_2__) && defined(__FMA__)
inline float horizontal_min(const xsimd::batch<float, xsimd::sse4_2>& v) {
  const __m128 pairs = _mm_min_ps(v, _mm_movehl_ps(v, v));
  return _mm_cvtss_f32(_mm_min_ss(pairs, _mm_shuffle_ps(pairs, pairs, 1)));
}
#endif
#if XSIMD_WITH_FMA3_AVX2
inline float horizontal_min(const xsimd::batch<float, xsimd::fma3<xsimd::avx2>>& v) {
  const __m256 x = v;
  return horizontal_min(xsimd::batch<float, xsimd::sse4_2>(_mm_min_ps(_mm256_castps256_ps128(x),
                                                                     _mm256_extractf128_ps(x, 1))));
}
#endif
#if XSIMD_WITH_AVX512BW
inline float horizontal_min(const xsimd::batch<float, xsimd::avx512bw>& v) {
  const __m512 x = v;
  return horizontal_min(xsimd::batch<float, xsimd::fma3<xsimd::avx2>>(
      _mm256_min_ps(_mm512_castps512_ps256(x), _mm512_extractf32x8_ps(x, 1))));
}
#endif

// The largest lane, for lanes without NaN.
template <class F>
inline float horizontal_max(const F& v) {
  return -horizontal_min(-v);
}

// Lane numbers 0..W-1 as int and float lanes.
template <class F>
inline IntLanes<F> lane_index() {
  alignas(64) static constexpr std::int32_t kIndex[kMaxLanes] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  return load_int_lanes<F>(kIndex);
}
template <class F>
inline F lane_index_float() {
  alignas(64) static constexpr float kIndex[kMaxLanes] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  return load_lanes<F>(kIndex);
}

// Lanes [0, remaining) active; remaining may exceed the width.
template <class F>
inline Mask<F> first_lanes(std::size_t remaining) {
  const float n = remaining < std::size_t(kMaxLanes) ? float(remaining) : float(kMaxLanes);
  return lane_index_float<F>() < F(n);
}

// Left-packing stores of a row of columns: the lanes whose bit is set in
// `bits` (lane_bits), in lane order, to each column's p[0], p[1], ...
// (popcount(bits) values; nothing else is written, p needs no alignment).
// AVX-512 packs each column in a register (compress) and stores it under a
// mask; AVX2 permutes each by a table of the 256 masks' lane orders and
// stores under a mask; SSE4 sets the lanes aside and copies every column's
// set ones in one loop over the bits, so the loop's exit is mispredicted
// once per row rather than once per column.
#if XSIMD_WITH_FMA3_AVX2
// Per 8-bit mask, its set lanes' numbers in order, a nibble each (lowest first).
inline constexpr std::array<std::uint32_t, 256> kLeftPackOrder = [] {
  std::array<std::uint32_t, 256> order{};
  for (unsigned mask = 0; mask < 256; ++mask) {
    unsigned nibble = 0;
    for (unsigned lane = 0; lane < 8; ++lane) {
      if ((mask >> lane & 1u) != 0) order[mask] |= lane << (4 * nibble++);
    }
  }
  return order;
}();
#endif
template <class F, class T, class V, std::size_t N>
inline void store_selected_packed(unsigned bits, const std::array<V, N>& values, const std::array<T*, N>& to) {
  if constexpr (lane_count<F> == 1) {
    if ((bits & 1u) == 0) return;
    for (std::size_t c = 0; c < N; ++c) *to[c] = values[c];
#if XSIMD_WITH_AVX512BW
  } else if constexpr (std::is_same_v<F, xsimd::batch<float, xsimd::avx512bw>>) {
    const auto set = static_cast<__mmask16>(bits);
    const auto packed = static_cast<__mmask16>((1u << std::popcount(bits)) - 1u);
    for (std::size_t c = 0; c < N; ++c) {
      if constexpr (std::is_same_v<T, float>) {
        _mm512_mask_storeu_ps(to[c], packed, _mm512_maskz_compress_ps(set, values[c]));
      } else {
        _mm512_mask_storeu_epi32(to[c], packed, _mm512_maskz_compress_epi32(set, values[c]));
      }
    }
#endif
#if XSIMD_WITH_FMA3_AVX2
  } else if constexpr (std::is_same_v<F, xsimd::batch<float, xsimd::fma3<xsimd::avx2>>>) {
    const __m256i order = _mm256_and_si256(
        _mm256_srlv_epi32(_mm256_set1_epi32(static_cast<int>(kLeftPackOrder[bits])),
                          _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28)),
        _mm256_set1_epi32(7));
    const __m256i kept = _mm256_cmpgt_epi32(_mm256_set1_epi32(std::popcount(bits)),
                                            _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    for (std::size_t c = 0; c < N; ++c) {
      if constexpr (std::is_same_v<T, float>) {
        _mm256_maskstore_ps(to[c], kept, _mm256_permutevar8x32_ps(values[c], order));
      } else {
        _mm256_maskstore_epi32(to[c], kept, _mm256_permutevar8x32_epi32(values[c], order));
      }
    }
#endif
  } else {
    static_assert(lane_count<F> == 1, "store_selected_packed: no left-pack for this unit's lanes");
  }
}

// Float columns `to_float` and int columns `to_int`, each a row's column.
template <class F, std::size_t N, std::size_t M>
inline void store_selected_lanes(unsigned bits, const std::array<F, N>& floats, const std::array<float*, N>& to_float,
                                 const std::array<IntLanes<F>, M>& ints, const std::array<std::int32_t*, M>& to_int) {
  if constexpr (lane_count<F> == 4) {
    alignas(16) std::array<std::array<float, 4>, N> float_lanes;
    alignas(16) std::array<std::array<std::int32_t, 4>, M> int_lanes;
    for (std::size_t c = 0; c < N; ++c) floats[c].store_aligned(float_lanes[c].data());
    for (std::size_t c = 0; c < M; ++c) ints[c].store_aligned(int_lanes[c].data());
    for (std::size_t i = 0; bits != 0; bits &= bits - 1, ++i) {
      const int k = std::countr_zero(bits);
      for (std::size_t c = 0; c < N; ++c) to_float[c][i] = float_lanes[c][k];
      for (std::size_t c = 0; c < M; ++c) to_int[c][i] = int_lanes[c][k];
    }
  } else {
    store_selected_packed<F>(bits, floats, to_float);
    store_selected_packed<F>(bits, ints, to_int);
  }
}

// ---- Vec3 forms ------------------------------------------------------------

template <class F>
inline Vec3<F> select(const Mask<F>& m, const Vec3<F>& a, const Vec3<F>& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
// Component by component (colours and weights).
template <class F>
inline Vec3<F> mul(const Vec3<F>& a, const Vec3<F>& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
// The largest component (max's NaN rule).
template <class F>
inline F max_component(const Vec3<F>& a) {
  return max(a.x, max(a.y, a.z));
}
// Cross product with each component from difference_of_products (error <= 1.5 ulp).
template <class F>
inline Vec3<F> cross_accurate(const Vec3<F>& a, const Vec3<F>& b) {
  return {difference_of_products(a.y, b.z, a.z, b.y), difference_of_products(a.z, b.x, a.x, b.z),
          difference_of_products(a.x, b.y, a.y, b.x)};
}
template <class F>
inline F length(const Vec3<F>& a) {
  return sqrt(dot(a, a));
}
// a / |a|; a itself where |a| is zero or NaN (no division by zero).
template <class F>
inline Vec3<F> normalize(const Vec3<F>& a) {
  const F l = length(a);
  return a / select(l > F(0.f), l, F(1.f));
}
// Two unit axes perpendicular to the unit vector n: t1 = normalize(n x h),
// h the x axis (the y axis where |n.x| >= 0.9), and t2 = n x t1.
template <class F>
inline void tangent_axes(const Vec3<F>& n, Vec3<F>& t1, Vec3<F>& t2) {
  const Mask<F> off_x = abs(n.x) < F(0.9f);
  const Vec3<F> helper(select(off_x, F(1.f), F(0.f)), select(off_x, F(0.f), F(1.f)), F(0.f));
  t1 = normalize(cross(n, helper));
  t2 = cross(n, t1);
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
