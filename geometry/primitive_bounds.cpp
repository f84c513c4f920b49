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

// Grows b by the points c +- r (per axis), computed in double.
void grow_ball(Box& b, const double c[3], double r) {
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::min(b.lo[a], round_down(c[a] - r));
    b.hi[a] = std::max(b.hi[a], round_up(c[a] + r));
  }
}

}  // namespace

Box primitive_box(const SphereSoA& s, std::size_t i) {
  const double c[3] = {s.cx[i], s.cy[i], s.cz[i]};
  Box b = empty_box();
  grow_ball(b, c, std::sqrt(static_cast<double>(s.r2[i])));  // the kernels use r^2
  return b;
}

Box primitive_box(const TriangleSoA& t, std::size_t i) {
  Box b = empty_box();
  for (int k = 0; k < 3; ++k) grow(b, t.vertex(i, k));
  return b;  // the vertices are stored exactly
}

Box primitive_box(const PolygonSoA& g, std::size_t i) {
  // The vertices as stored (the ray-space test's) and lifted from their
  // projections onto the plane through the first one, in double (the plane
  // hit's).
  const int au = g.axis_u[i], av = g.axis_v[i], ak = 3 - au - av;
  const double n[3] = {g.nx[i], g.ny[i], g.nz[i]};
  const std::size_t first = g.first_vertex[i];
  const double v0k = ak == 0 ? g.px[first] : (ak == 1 ? g.py[first] : g.pz[first]);
  Box b = empty_box();
  for (std::int32_t k = 0; k < g.vertex_count[i]; ++k) {
    const std::size_t at = g.first_vertex[i] + static_cast<std::size_t>(k);
    grow(b, Vec3<float>{g.px[at], g.py[at], g.pz[at]});
    double p[3];
    p[au] = static_cast<double>(g.origin_u[i]) + g.pu[at];
    p[av] = static_cast<double>(g.origin_v[i]) + g.pv[at];
    p[ak] = v0k - (n[au] * g.pu[at] + n[av] * g.pv[at]) / n[ak];
    grow_ball(b, p, 0.0);
  }
  return b;
}

Box primitive_box(const ConeSoA& c, std::size_t i) {
  const double base[3] = {c.bx[i], c.by[i], c.bz[i]};
  const double axis[3] = {c.ax[i], c.ay[i], c.az[i]};
  const double h = c.height[i];
  const double apex[3] = {base[0] + axis[0] * h, base[1] + axis[1] * h, base[2] + axis[2] * h};
  // The wider rim bounds both (|facing| does not change the surface).
  const double r = std::max(std::fabs(static_cast<double>(c.radius0[i])),
                            std::fabs(c.radius0[i] + static_cast<double>(c.slope[i]) * h));
  Box b = empty_box();
  grow_ball(b, base, r);
  grow_ball(b, apex, r);
  return b;
}

}  // namespace quiver
