#include "simd/isa.h"

#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

namespace quiver {

namespace {

// GCC's CPU model also checks that the OS saves AVX state (xsimd 8.1's avx
// flag reads false on some AVX2 machines, so it is not used). The builtin
// takes only literal names, hence one case per feature.
bool cpu_has(CpuFeature feature) {
  switch (feature) {
    case CpuFeature::avx: return __builtin_cpu_supports("avx");
    case CpuFeature::fma: return __builtin_cpu_supports("fma");
    case CpuFeature::sse4_2: return __builtin_cpu_supports("sse4.2");
    case CpuFeature::avx2: return __builtin_cpu_supports("avx2");
    case CpuFeature::avx512f: return __builtin_cpu_supports("avx512f");
    case CpuFeature::avx512cd: return __builtin_cpu_supports("avx512cd");
    case CpuFeature::avx512dq: return __builtin_cpu_supports("avx512dq");
    case CpuFeature::avx512bw: return __builtin_cpu_supports("avx512bw");
    case CpuFeature::avx512vl: return __builtin_cpu_supports("avx512vl");
  }
  return false;
}

bool supported(const KernelUnitSpec& spec) {
  for (unsigned f = 0; f < 32; ++f) {
    if (((spec.required_features >> f) & 1u) != 0 && !cpu_has(static_cast<CpuFeature>(f))) return false;
  }
  return true;
}

// The first unit of an ISA choice (every choice has one).
const KernelUnitSpec& first_unit_of(Isa isa) {
  for (const KernelUnitSpec& spec : kKernelUnitSpecs) {
    if (spec.isa == isa) return spec;
  }
  return kKernelUnitSpecs[0];
}

}  // namespace

int lane_width(Isa isa) { return first_unit_of(isa).lanes; }

std::string_view isa_name(Isa isa) { return first_unit_of(isa).name; }

std::optional<Isa> parse_isa(std::string_view name) {
  for (Isa isa : kIsas) {
    if (name == isa_name(isa)) return isa;
  }
  return std::nullopt;
}

bool isa_supported(Isa isa) {
  for (const KernelUnitSpec& spec : kKernelUnitSpecs) {
    if (spec.isa == isa && supported(spec)) return true;
  }
  return false;
}

int lane_width(KernelUnit unit) { return spec_of(unit).lanes; }

std::string_view kernel_unit_name(KernelUnit unit) { return spec_of(unit).name; }

bool kernel_unit_supported(KernelUnit unit) { return supported(spec_of(unit)); }

KernelUnit kernel_unit_for(Isa isa) {
  // The ISA's first unit, or a later one of the same ISA this CPU supports
  // (scalar: scalar_fma where the CPU has FMA).
  std::optional<KernelUnit> chosen;
  for (const KernelUnitSpec& spec : kKernelUnitSpecs) {
    if (spec.isa == isa && (!chosen || supported(spec))) chosen = spec.unit;
  }
  return chosen.value_or(KernelUnit::scalar);
}

Isa isa_of(KernelUnit unit) { return spec_of(unit).isa; }

Isa best_supported_isa() {
  Isa best = Isa::scalar;
  for (Isa isa : kIsas) {
    if (isa_supported(isa)) best = isa;
  }
  return best;
}

Isa resolve_isa(std::string_view requested) {
  if (requested.empty() || requested == "auto") return best_supported_isa();
  const auto isa = parse_isa(requested);
  if (!isa) {
    throw std::runtime_error("unknown SIMD choice '" + std::string(requested) +
                             "': expected auto, scalar, sse4, avx2 or avx512");
  }
  if (!isa_supported(*isa)) {
    throw std::runtime_error("SIMD choice '" + std::string(requested) + "' is not supported by this CPU");
  }
  return *isa;
}

Isa isa_from_environment() {
  const char* value = std::getenv("QUIVER_SIMD");
  return resolve_isa(value ? std::string_view(value) : std::string_view());
}

}  // namespace quiver
