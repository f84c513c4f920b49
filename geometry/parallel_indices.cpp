#include "geometry/parallel_indices.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace quiver {

namespace {

constexpr std::size_t kIndicesPerTask = 4096;

}  // namespace

void for_each_block(std::size_t count, const std::function<void(std::size_t, std::size_t)>& visit_block) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kIndicesPerTask),
                    [&](const tbb::blocked_range<std::size_t>& block) { visit_block(block.begin(), block.end()); });
}

void for_each_task(std::size_t count, const std::function<void(std::size_t)>& visit) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1), [&](const tbb::blocked_range<std::size_t>& block) {
    for (std::size_t i = block.begin(); i != block.end(); ++i) visit(i);
  });
}

}  // namespace quiver
