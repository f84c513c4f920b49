// The walks' traversal stacks push a node's children farthest first, so the
// nearest is popped next: each push is an insertion into the entries pushed
// for the same node. The stacks themselves are local arrays in each walk, so
// nothing outside the walk can alias them.
#pragma once

#include <cstddef>

#include "simd/kernel_units.h"

namespace quiver {
inline namespace QUIVER_UNIT_NAMESPACE {

// The slot for an entry with `key` among the entries pushed since `base`
// (in decreasing key order up to `top`, the slot being added): entries
// with a smaller key move up one slot. key_at(i) is slot i's key;
// move_up(i) copies slot i - 1 to slot i.
template <class KeyAt, class MoveUp>
[[gnu::always_inline]] inline std::size_t sorted_slot(std::size_t base, std::size_t top, float key,
                                                      const KeyAt& key_at, const MoveUp& move_up) {
  std::size_t at = top;
  for (; at > base && key_at(at - 1) < key; --at) move_up(at);
  return at;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
