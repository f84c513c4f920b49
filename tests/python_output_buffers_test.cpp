// The kept output buffers of the Python module (python/output_buffers.h):
// a released buffer serves a later request of at most its size and at
// least half of it; a smaller request gets memory of its own, so a small
// query does not hold a large one's pages.
#include <gtest/gtest.h>

#include "python/output_buffers.h"

namespace quiver {
namespace {

TEST(OutputBuffers, AKeptBufferServesRequestsFromHalfItsSizeToItsSize) {
  const OutputBuffer first = acquire_output_buffer(1000);
  ASSERT_NE(first.data, nullptr);
  EXPECT_EQ(first.bytes, 1000u);
  release_output_buffer(first);
  const OutputBuffer same = acquire_output_buffer(1000);
  EXPECT_EQ(same.data, first.data);  // the kept one
  release_output_buffer(same);
  const OutputBuffer third = acquire_output_buffer(300);  // 1000 is more than twice 300
  EXPECT_NE(third.data, first.data);
  const OutputBuffer half = acquire_output_buffer(500);  // 1000 is twice 500
  EXPECT_EQ(half.data, first.data);
  EXPECT_EQ(half.bytes, 1000u);
  const OutputBuffer larger = acquire_output_buffer(2000);  // nothing kept is large enough
  EXPECT_EQ(larger.bytes, 2000u);
  for (const OutputBuffer& b : {third, half, larger}) release_output_buffer(b);
}

}  // namespace
}  // namespace quiver
