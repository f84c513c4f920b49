// A packet against one box (geometry/bvh/slab.h, may_meet_box), the cull
// of a store scanned without a BVH: a ray meets the box where its segment
// crosses it, is culled where it passes by, ends before or points away, and
// is never culled where the test must stay conservative (on a face, along
// an axis-parallel slab, or reaching behind its origin).
#include <limits>

#include <gtest/gtest.h>

#include "geometry/bvh/slab.h"

namespace quiver {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
const Box kUnitBox{{0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}};

bool meets(Vec3<float> origin, Vec3<float> direction, float tmin, float tmax) {
  return may_meet_box(Ray<float>{origin, direction, tmin, tmax}, kUnitBox, true, tmax);
}

TEST(MayMeetBox, ASegmentThatCrossesTheBoxMeetsItAndOnePassingByDoesNot) {
  EXPECT_TRUE(meets({0.5f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, 0.f, kInf));
  EXPECT_TRUE(meets({-1.f, -1.f, -1.f}, {1.f, 1.f, 1.f}, 0.f, kInf));  // along the diagonal
  EXPECT_TRUE(meets({0.5f, 0.5f, 0.5f}, {1.f, -2.f, 0.3f}, 0.f, kInf));  // from inside
  EXPECT_FALSE(meets({0.5f, 0.5f, -2.f}, {0.f, 0.f, -1.f}, 0.f, kInf));  // away from it
  EXPECT_FALSE(meets({2.f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, 0.f, kInf));   // beside it
  EXPECT_FALSE(meets({0.5f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, 0.f, 1.5f));  // ends before it
  EXPECT_FALSE(meets({0.5f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, 3.5f, kInf));  // starts after it
  EXPECT_FALSE(may_meet_box(Ray<float>{{0.5f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, 0.f, kInf}, kUnitBox, false, kInf));
}

TEST(MayMeetBox, TheTestStaysConservativeWhereRoundingDecides) {
  EXPECT_TRUE(meets({0.5f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, 0.f, 2.f));   // ends exactly at the face
  EXPECT_TRUE(meets({1.f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, 0.f, kInf));   // along a face
  EXPECT_TRUE(meets({0.5f, -3.f, 0.25f}, {0.f, 1.f, 0.f}, 0.f, kInf));  // axis-parallel inside the slabs
  EXPECT_FALSE(meets({0.5f, -3.f, 1.25f}, {0.f, 1.f, 0.f}, 0.f, kInf));  // axis-parallel outside one
  // A segment reaching behind its origin is never culled (relative widening would narrow it there).
  EXPECT_TRUE(meets({2.f, 0.5f, -2.f}, {0.f, 0.f, 1.f}, -1.f, kInf));
  // Axis-parallel along a face at 0, whichever way the zero component's sign points: a sphere
  // touching that face is met there (a tangent hit the kernels report).
  const Box left_of_zero{{-2.f, 0.f, -1.f}, {0.f, 2.f, 1.f}}, right_of_zero{{0.f, 0.f, -1.f}, {2.f, 2.f, 1.f}};
  for (const float zero : {0.f, -0.f}) {
    const Ray<float> on_face{{0.f, 1.5f, 6.f}, {zero, -0.083f, -0.997f}, 0.f, kInf};
    EXPECT_TRUE(may_meet_box(on_face, left_of_zero, true, kInf)) << zero;
    EXPECT_TRUE(may_meet_box(on_face, right_of_zero, true, kInf)) << zero;
  }
}

}  // namespace
}  // namespace quiver
