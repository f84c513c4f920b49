#include "geometry/affine_transform.h"

#include <cmath>

namespace quiver {

std::optional<AffineTransform> inverse(const AffineTransform& t) {
  double a[3][3], b[3];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a[r][c] = t.at(r, c);
    b[r] = t.at(r, 3);
  }
  // The adjugate over the determinant.
  const double cof[3][3] = {{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[1][2] * a[2][0] - a[1][0] * a[2][2],
                             a[1][0] * a[2][1] - a[1][1] * a[2][0]},
                            {a[0][2] * a[2][1] - a[0][1] * a[2][2], a[0][0] * a[2][2] - a[0][2] * a[2][0],
                             a[0][1] * a[2][0] - a[0][0] * a[2][1]},
                            {a[0][1] * a[1][2] - a[0][2] * a[1][1], a[0][2] * a[1][0] - a[0][0] * a[1][2],
                             a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
  const double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
  if (!std::isfinite(det) || det == 0.0) return std::nullopt;
  double inv[3][3];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) inv[r][c] = cof[c][r] / det;
  }
  AffineTransform out;
  for (int r = 0; r < 3; ++r) {
    double shift = 0.0;
    for (int c = 0; c < 3; ++c) {
      out.m[static_cast<std::size_t>(4 * r + c)] = static_cast<float>(inv[r][c]);
      shift -= inv[r][c] * b[c];
    }
    out.m[static_cast<std::size_t>(4 * r + 3)] = static_cast<float>(shift);
  }
  for (float v : out.m) {
    if (!std::isfinite(v)) return std::nullopt;
  }
  return out;
}

AffineTransform absolute(const AffineTransform& t) {
  AffineTransform out;
  for (std::size_t k = 0; k < t.m.size(); ++k) out.m[k] = std::fabs(t.m[k]);
  return out;
}

}  // namespace quiver
