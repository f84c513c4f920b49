// The left-packing stores of simd/lanes.h checked inside each kernel unit
// (tests/support/left_pack_unit.cpp is compiled once per unit with its
// flags, like the kernels), for tests/simd_lanes_test.cpp.
#pragma once

#include <string>

#include "simd/kernel_units.h"

namespace quiver::testing {

// Every mask of the unit's width through store_selected_lanes with two
// float columns and one int column: "" when each column holds the set
// lanes in lane order and nothing past them was written, else the first
// mask that failed and how.
template <KernelUnit U>
std::string left_pack_every_mask();

}  // namespace quiver::testing
