// The core's measured FMA peak, the yardstick for kernel efficiency: twelve
// independent 8-wide (or 16-wide) FMA chains (enough to cover latency x
// throughput on current x86 cores) in a loop. items_per_second =
// single-precision FLOP/s, an fma counting 2. Compiled with -mavx2 -mfma, the
// 16-wide loop with AVX-512 as its target attribute; each registered only
// when the CPU has its instructions.
#include <benchmark/benchmark.h>
#include <immintrin.h>

#include "simd/isa.h"

namespace quiver::bench {
namespace {

void fma_peak(benchmark::State& state) {
  constexpr int kChains = 12;
  constexpr std::int64_t kStepsPerIteration = 1 << 16;
  __m256 acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = _mm256_set1_ps(float(c));
  const __m256 scale = _mm256_set1_ps(0.999999f);
  const __m256 offset = _mm256_set1_ps(1e-7f);
  for (auto _ : state) {
    for (std::int64_t i = 0; i < kStepsPerIteration; ++i) {
      for (int c = 0; c < kChains; ++c) acc[c] = _mm256_fmadd_ps(acc[c], scale, offset);
    }
    for (int c = 0; c < kChains; ++c) benchmark::DoNotOptimize(acc[c]);
  }
  state.SetItemsProcessed(state.iterations() * kStepsPerIteration * kChains * 8 * 2);
}

__attribute__((target("avx512f"))) void fma_peak_16(benchmark::State& state) {
  constexpr int kChains = 12;
  constexpr std::int64_t kStepsPerIteration = 1 << 16;
  __m512 acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = _mm512_set1_ps(float(c));
  const __m512 scale = _mm512_set1_ps(0.999999f);
  const __m512 offset = _mm512_set1_ps(1e-7f);
  for (auto _ : state) {
    for (std::int64_t i = 0; i < kStepsPerIteration; ++i) {
      for (int c = 0; c < kChains; ++c) acc[c] = _mm512_fmadd_ps(acc[c], scale, offset);
    }
    for (int c = 0; c < kChains; ++c) benchmark::DoNotOptimize(acc[c]);
  }
  state.SetItemsProcessed(state.iterations() * kStepsPerIteration * kChains * 16 * 2);
}

const bool registered = [] {
  if (isa_supported(Isa::avx2)) benchmark::RegisterBenchmark("peak/fma/w8", fma_peak);
  if (isa_supported(Isa::avx512)) benchmark::RegisterBenchmark("peak/fma/w16", fma_peak_16);
  return true;
}();

}  // namespace
}  // namespace quiver::bench
