// The kernel units' table (simd/kernel_units.h): feature bits, and every
// instruction set a unit is compiled for among the features it requires
// (a unit missing one would be chosen on a CPU without it).
#include "simd/kernel_units.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>

namespace quiver {
namespace {

constexpr unsigned bit(CpuFeature f) { return 1u << static_cast<unsigned>(f); }

TEST(CpuFeatures, OneBitPerFeatureAllKept) {
  EXPECT_EQ(cpu_features({}), 0u);
  EXPECT_EQ(cpu_features({CpuFeature::fma}), bit(CpuFeature::fma));
  EXPECT_EQ(cpu_features({CpuFeature::avx2, CpuFeature::fma, CpuFeature::avx512vl}),
            bit(CpuFeature::avx2) | bit(CpuFeature::fma) | bit(CpuFeature::avx512vl));
  EXPECT_EQ(cpu_features({CpuFeature::fma, CpuFeature::fma}), bit(CpuFeature::fma));
}

TEST(KernelUnitSpecs, EveryCompileFlagsInstructionSetIsRequired) {
  const std::pair<std::string_view, CpuFeature> implied[] = {
      {"-mfma", CpuFeature::fma},           {"-msse4.2", CpuFeature::sse4_2},     {"-mavx2", CpuFeature::avx2},
      {"-mavx512f", CpuFeature::avx512f},   {"-mavx512cd", CpuFeature::avx512cd}, {"-mavx512dq", CpuFeature::avx512dq},
      {"-mavx512bw", CpuFeature::avx512bw}, {"-mavx512vl", CpuFeature::avx512vl},
  };
  for (const KernelUnitSpec& spec : kKernelUnitSpecs) {
    SCOPED_TRACE(std::string(spec.name));
    std::string flags(" ");
    flags.append(spec.flags).append(" ");
    for (const auto& [flag, feature] : implied) {
      std::string word(" ");
      word.append(flag).append(" ");
      if (flags.find(word) == std::string::npos) continue;
      EXPECT_NE(spec.required_features & bit(feature), 0u) << flag;
    }
    // Every unit after the scalar reference needs at least what its flags name.
    if (spec.unit != KernelUnit::scalar) {
      EXPECT_NE(spec.required_features, 0u);
    }
  }
  EXPECT_EQ(spec_of(KernelUnit::scalar).required_features, 0u);
}

}  // namespace
}  // namespace quiver
