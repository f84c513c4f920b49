// The core's measured FMA peak, the yardstick for kernel efficiency: twelve
// independent 8-wide FMA chains (enough to cover latency x throughput on
// current x86 cores) in a loop. items_per_second = single-precision FLOP/s,
// an fma counting 2. Compiled with -mavx2 -mfma; registered only when the
// CPU has them.
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

const bool registered = [] {
  if (isa_supported(Isa::avx2)) benchmark::RegisterBenchmark("peak/fma/w8", fma_peak);
  return true;
}();

}  // namespace
}  // namespace quiver::bench
