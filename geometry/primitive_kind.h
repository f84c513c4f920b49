// A primitive kind as hits, AOVs and stats name it: its position in the
// list of kinds (geometry/kinds.h, kind_tag), so the list alone numbers them.
#pragma once

#include <cstdint>

namespace quiver {

enum class PrimitiveKind : std::int32_t {};
// A miss.
inline constexpr std::int32_t kNoKind = -1;

}  // namespace quiver
