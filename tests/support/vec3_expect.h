// A Vec3<float> expected near (x, y, z), component by component.
#pragma once

#include <gtest/gtest.h>

#include "simd/vec3.h"

namespace quiver::testing {

inline void expect_vec3_near(const Vec3<float>& v, double x, double y, double z, double tolerance = 1e-5) {
  EXPECT_NEAR(v.x, x, tolerance);
  EXPECT_NEAR(v.y, y, tolerance);
  EXPECT_NEAR(v.z, z, tolerance);
}

}  // namespace quiver::testing
