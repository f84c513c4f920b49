#include "geometry/primitive_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace quiver {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The largest float <= x and the smallest float >= x.
float round_down(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -kInf) : f;
}
float round_up(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, kInf) : f;
}

}  // namespace

void grow_ball(Box& b, const double c[3], double r) {
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::min(b.lo[a], round_down(c[a] - r));
    b.hi[a] = std::max(b.hi[a], round_up(c[a] + r));
  }
}

}  // namespace quiver
