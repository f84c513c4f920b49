// Run-time choice of the lane width: the widest the CPU supports, unless
// forced by QUIVER_SIMD=auto|scalar|sse4|avx2|avx512 or the --simd flag.
// Everything here reads the table of kernel units (simd/kernel_units.h).
#pragma once

#include <optional>
#include <string_view>

#include "simd/kernel_units.h"

namespace quiver {

// Every ISA choice, narrowest first.
inline constexpr std::array<Isa, 4> kIsas = {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512};

int lane_width(Isa isa);
std::string_view isa_name(Isa isa);        // the name of its first unit
std::optional<Isa> parse_isa(std::string_view name);  // not "auto"
bool isa_supported(Isa isa);               // some unit of it runs on this CPU
Isa best_supported_isa();
int lane_width(KernelUnit unit);
std::string_view kernel_unit_name(KernelUnit unit);
bool kernel_unit_supported(KernelUnit unit);
// The unit that runs an ISA choice: its last supported unit in the table
// (scalar_fma for scalar when the CPU has FMA).
KernelUnit kernel_unit_for(Isa isa);
// The ISA choice a unit runs (scalar for both scalar units).
Isa isa_of(KernelUnit unit);

// "auto" or empty gives best_supported_isa(); throws std::runtime_error on an
// unknown name or an ISA this CPU lacks.
Isa resolve_isa(std::string_view requested);
// resolve_isa(getenv("QUIVER_SIMD")).
Isa isa_from_environment();

}  // namespace quiver
