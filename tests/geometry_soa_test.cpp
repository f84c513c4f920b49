// Tests of geometry/soa.h: a padded column holds a full load of kMaxLanes
// from any index of its data (BVH leaves start anywhere), in whole blocks,
// and its padding repeats the last value.
#include "geometry/soa.h"

#include <gtest/gtest.h>

namespace quiver {
namespace {

TEST(Soa, PaddedSizeHoldsAFullLoadFromTheLastIndexInWholeBlocks) {
  EXPECT_EQ(padded_size(0), 0u);
  for (std::size_t n = 1; n <= 3 * kMaxLanes; ++n) {
    const std::size_t padded = padded_size(n);
    EXPECT_GE(padded, n - 1 + kMaxLanes) << n;  // a load from index n - 1
    EXPECT_EQ(padded % kMaxLanes, 0u) << n;
    EXPECT_LT(padded, n - 1 + 2 * kMaxLanes) << n;  // the least such size
  }
}

TEST(Soa, APaddedColumnRepeatsItsLastValue) {
  AlignedFloats column{1.f, 2.f, 3.f};
  pad_column(column, 3);
  ASSERT_EQ(column.size(), padded_size(3));
  EXPECT_EQ(column[2], 3.f);
  for (std::size_t i = 3; i < column.size(); ++i) EXPECT_EQ(column[i], 3.f) << i;
}

}  // namespace
}  // namespace quiver
