#include "simd/isa.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace quiver {

int lane_width(Isa isa) {
  switch (isa) {
    case Isa::scalar: return 1;
    case Isa::sse4: return 4;
    case Isa::avx2: return 8;
    case Isa::avx512: return 16;
  }
  return 1;
}

std::string_view isa_name(Isa isa) {
  switch (isa) {
    case Isa::scalar: return "scalar";
    case Isa::sse4: return "sse4";
    case Isa::avx2: return "avx2";
    case Isa::avx512: return "avx512";
  }
  return "scalar";
}

std::optional<Isa> parse_isa(std::string_view name) {
  for (Isa isa : kIsas) {
    if (name == isa_name(isa)) return isa;
  }
  return std::nullopt;
}

bool isa_supported(Isa isa) {
  // GCC's CPU model also checks that the OS saves AVX state (xsimd 8.1's
  // avx flag reads false on some AVX2 machines, so it is not used).
  switch (isa) {
    case Isa::scalar: return true;
    // The 4-wide unit is built with -msse4.2 -mfma, which implies VEX (AVX) encoding.
    case Isa::sse4:
      return __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("avx") && __builtin_cpu_supports("fma");
    case Isa::avx2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    // The 16-wide unit is built with -mavx512f -mavx512cd -mavx512dq -mavx512bw -mavx512vl -mfma.
    case Isa::avx512:
      return isa_supported(Isa::avx2) && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512vl");
  }
  return false;
}

int lane_width(KernelUnit unit) {
  switch (unit) {
    case KernelUnit::scalar:
    case KernelUnit::scalar_fma: return 1;
    case KernelUnit::sse4: return 4;
    case KernelUnit::avx2: return 8;
    case KernelUnit::avx512: return 16;
  }
  return 1;
}

std::string_view kernel_unit_name(KernelUnit unit) {
  switch (unit) {
    case KernelUnit::scalar: return "scalar";
    case KernelUnit::scalar_fma: return "scalar_fma";
    case KernelUnit::sse4: return "sse4";
    case KernelUnit::avx2: return "avx2";
    case KernelUnit::avx512: return "avx512";
  }
  return "scalar";
}

bool kernel_unit_supported(KernelUnit unit) {
  switch (unit) {
    case KernelUnit::scalar: return true;
    // -mfma implies VEX (AVX) encoding.
    case KernelUnit::scalar_fma: return __builtin_cpu_supports("avx") && __builtin_cpu_supports("fma");
    case KernelUnit::sse4: return isa_supported(Isa::sse4);
    case KernelUnit::avx2: return isa_supported(Isa::avx2);
    case KernelUnit::avx512: return isa_supported(Isa::avx512);
  }
  return false;
}

KernelUnit kernel_unit_for(Isa isa) {
  switch (isa) {
    case Isa::scalar:
      return kernel_unit_supported(KernelUnit::scalar_fma) ? KernelUnit::scalar_fma : KernelUnit::scalar;
    case Isa::sse4: return KernelUnit::sse4;
    case Isa::avx2: return KernelUnit::avx2;
    case Isa::avx512: return KernelUnit::avx512;
  }
  return KernelUnit::scalar;
}

Isa isa_of(KernelUnit unit) {
  switch (unit) {
    case KernelUnit::scalar:
    case KernelUnit::scalar_fma: return Isa::scalar;
    case KernelUnit::sse4: return Isa::sse4;
    case KernelUnit::avx2: return Isa::avx2;
    case KernelUnit::avx512: return Isa::avx512;
  }
  return Isa::scalar;
}

Isa best_supported_isa() {
  for (Isa isa : {Isa::avx512, Isa::avx2, Isa::sse4}) {
    if (isa_supported(isa)) return isa;
  }
  return Isa::scalar;
}

Isa resolve_isa(std::string_view requested) {
  if (requested.empty() || requested == "auto") return best_supported_isa();
  const auto isa = parse_isa(requested);
  if (!isa) {
    throw std::runtime_error("unknown SIMD choice '" + std::string(requested) +
                             "': expected auto, scalar, sse4, avx2 or avx512");
  }
  if (!isa_supported(*isa)) {
    throw std::runtime_error("SIMD choice '" + std::string(requested) +
                             "' is not supported by this CPU");
  }
  return *isa;
}

Isa isa_from_environment() {
  const char* value = std::getenv("QUIVER_SIMD");
  return resolve_isa(value ? std::string_view(value) : std::string_view());
}

}  // namespace quiver
