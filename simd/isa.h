// Run-time choice of the lane width: the widest the CPU supports, unless
// forced by QUIVER_SIMD=auto|scalar|sse4|avx2|avx512 or the --simd flag.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace quiver {

enum class Isa { scalar, sse4, avx2, avx512 };

// The compiled kernel units (CMake builds each kernel source once per unit).
// Two scalar units: `scalar` runs on any x86-64 and is the reference;
// `scalar_fma` is the same source built with -mfma, so the kernels' explicit
// fma is an instruction rather than a libm call. They agree bit for bit
// (std::fma is correctly rounded either way), which the tests check.
enum class KernelUnit { scalar, scalar_fma, sse4, avx2, avx512 };

// Every ISA choice and every kernel unit, narrowest first.
inline constexpr std::array<Isa, 4> kIsas = {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512};
inline constexpr std::array<KernelUnit, 5> kKernelUnits = {KernelUnit::scalar, KernelUnit::scalar_fma, KernelUnit::sse4,
                                                           KernelUnit::avx2, KernelUnit::avx512};

int lane_width(Isa isa);
std::string_view isa_name(Isa isa);
std::optional<Isa> parse_isa(std::string_view name);  // not "auto"
bool isa_supported(Isa isa);
Isa best_supported_isa();
int lane_width(KernelUnit unit);
std::string_view kernel_unit_name(KernelUnit unit);
bool kernel_unit_supported(KernelUnit unit);
// The unit that runs an ISA choice: scalar_fma for scalar when the CPU has FMA.
KernelUnit kernel_unit_for(Isa isa);
// The ISA choice a unit runs (scalar for both scalar units).
Isa isa_of(KernelUnit unit);

// "auto" or empty gives best_supported_isa(); throws std::runtime_error on an
// unknown name or an ISA this CPU lacks.
Isa resolve_isa(std::string_view requested);
// resolve_isa(getenv("QUIVER_SIMD")).
Isa isa_from_environment();

}  // namespace quiver
