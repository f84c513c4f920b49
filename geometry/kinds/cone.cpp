#include "geometry/kinds/cone.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "geometry/primitive_bounds.h"

namespace quiver {

namespace {
// Squares neither overflow nor underflow to zero.
bool square_safe(float x) {
  const float sq = x * x;
  return std::isfinite(sq) && (x == 0.f || sq >= FLT_MIN);
}
}  // namespace

ConeSoA build_cones(const DescRefs<ConeDesc>& cones, BuildReport& report) {
  ConeSoA soa;
  for (AlignedFloats* c : soa.columns()) c->reserve(padded_size(cones.size()));
  for (std::size_t i = 0; i < cones.size(); ++i) {
    const ConeDesc& c = cones[i];
    if (!all_finite(c.base) || !all_finite(c.apex) || !std::isfinite(c.base_radius) || !std::isfinite(c.apex_radius)) {
      ++report.dropped_non_finite;
      continue;
    }
    // Axis and height in double: exact differences, no overflow in the squares.
    const double dx = double(c.apex.x) - c.base.x, dy = double(c.apex.y) - c.base.y,
                 dz = double(c.apex.z) - c.base.z;
    const double h = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (h > double(FLT_MAX)) {
      ++report.dropped_non_finite;
      continue;
    }
    // NFF: negative radii mean "inside visible"; mixed signs mean nothing.
    const bool inside = c.base_radius < 0.f || c.apex_radius < 0.f;
    const bool mixed = (c.base_radius < 0.f && c.apex_radius > 0.f) || (c.base_radius > 0.f && c.apex_radius < 0.f);
    const float r0 = std::fabs(c.base_radius), r1 = std::fabs(c.apex_radius);
    const float height = float(h);
    const float slope = float((double(r1) - double(r0)) / h);
    if (!(height >= FLT_MIN) || mixed || (r0 == 0.f && r1 == 0.f) || !std::isfinite(slope) ||
        !square_safe(r0) || !square_safe(r1) || !square_safe(slope) || !square_safe(std::max(r0, r1))) {
      ++report.dropped_degenerate;
      continue;
    }
    soa.source.push_back(static_cast<std::uint32_t>(i));
    soa.bx.push_back(c.base.x);
    soa.by.push_back(c.base.y);
    soa.bz.push_back(c.base.z);
    soa.ax.push_back(float(dx / h));
    soa.ay.push_back(float(dy / h));
    soa.az.push_back(float(dz / h));
    soa.height.push_back(height);
    soa.radius0.push_back(r0);
    soa.slope.push_back(slope);
    soa.facing.push_back(inside ? -1.f : 1.f);
  }
  soa.count = soa.bx.size();
  report.kept += soa.count;
  for (AlignedFloats* c : soa.columns()) pad_column(*c, soa.count);
  return soa;
}

std::size_t ConeSoA::memory_bytes() const {
  std::size_t bytes = bytes_of(source);
  for (const AlignedFloats* c : columns()) bytes += bytes_of(*c);
  return bytes;
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

// Cylindrical (u, v): u = the angle about the axis / 2 pi, v = s / h along it.
void map_surface(const ConeSoA& c, const MappingQuery& q, SurfaceMapping& out) {
  if (!q.textured) return;
  const std::uint32_t i = q.index;
  const Vec3<float> axis{c.ax[i], c.ay[i], c.az[i]};
  const Vec3<float> base{c.bx[i], c.by[i], c.bz[i]};
  const Vec3<float> radial = q.position - base - axis * dot(q.position - base, axis);
  Vec3<float> t1, t2;
  tangent_axes(axis, t1, t2);
  out.u = 0.5f + std::atan2(dot(radial, t2), dot(radial, t1)) * kInvTwoPi;
  out.v = q.hit.u;
  for (int a = 0; a < 2; ++a) {
    const Vec3<float> radial_change = q.dp[a] - axis * dot(q.dp[a], axis);
    out.du[a] = longitude_change(dot(radial, t1), dot(radial, t2), dot(radial_change, t1), dot(radial_change, t2));
    out.dv[a] = dot(q.dp[a], axis) / c.height[i];
  }
}

}  // namespace quiver
