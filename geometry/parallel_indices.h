// for_each_index: a loop over [0, count) run in blocks on oneTBB's threads,
// for loops whose iteration i writes only its own outputs (slot i of the
// arrays it fills), so that the result is the serial loop's, bit for bit,
// for any thread count. oneTBB stays in parallel_indices.cpp, so that a
// header using this one may reach the kernel units, whose objects must hold
// no code of a library's headers built with their flags (simd/kernel_units.h).
#pragma once

#include <cstddef>
#include <functional>

namespace quiver {

// visit_block(begin, end) for blocks covering [0, count), in parallel (a few
// thousand indices a block: enough work to outweigh a task's scheduling).
void for_each_block(std::size_t count, const std::function<void(std::size_t, std::size_t)>& visit_block);

// visit(i) for every i in [0, count), in parallel, each index a task of its
// own: for a few large items.
void for_each_task(std::size_t count, const std::function<void(std::size_t)>& visit);

template <class Visit>
void for_each_index(std::size_t count, const Visit& visit) {
  for_each_block(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i) visit(i);
  });
}

}  // namespace quiver
