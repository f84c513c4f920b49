// Run-time choice of the lane width: the widest the CPU supports, unless
// forced by QUIVER_SIMD=auto|scalar|sse4|avx2 (the CLI flag comes later).
#pragma once

#include <optional>
#include <string_view>

namespace quiver {

enum class Isa { scalar, sse4, avx2 };

int lane_width(Isa isa);
Isa isa_for_width(int width);  // 1 -> scalar, 4 -> sse4, 8 -> avx2
std::string_view isa_name(Isa isa);
std::optional<Isa> parse_isa(std::string_view name);  // not "auto"
bool isa_supported(Isa isa);
Isa best_supported_isa();
// "auto" or empty gives best_supported_isa(); throws std::runtime_error on an
// unknown name or an ISA this CPU lacks.
Isa resolve_isa(std::string_view requested);
// resolve_isa(getenv("QUIVER_SIMD")).
Isa isa_from_environment();

}  // namespace quiver
