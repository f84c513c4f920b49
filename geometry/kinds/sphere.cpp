#include "geometry/kinds/sphere.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/primitive_bounds.h"

namespace quiver {

SphereSoA build_spheres(const DescRefs<SphereDesc>& spheres, BuildReport& report) {
  SphereSoA soa;
  for (AlignedFloats* c : soa.columns()) c->reserve(padded_size(spheres.size()));
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const SphereDesc& s = spheres[i];
    const Vec3<float>& c = s.center;
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(s.radius)) {
      ++report.dropped_non_finite;
      continue;
    }
    const float r2 = s.radius * s.radius;
    if (!std::isfinite(r2)) {
      ++report.dropped_non_finite;
      continue;
    }
    if (!(s.radius > 0.f) || r2 < std::numeric_limits<float>::min()) {
      ++report.dropped_degenerate;
      continue;
    }
    soa.source.push_back(static_cast<std::uint32_t>(i));
    soa.cx.push_back(c.x);
    soa.cy.push_back(c.y);
    soa.cz.push_back(c.z);
    soa.r2.push_back(r2);
    soa.inv_r.push_back(1.f / s.radius);
  }
  soa.count = soa.cx.size();
  report.kept += soa.count;
  for (AlignedFloats* c : soa.columns()) pad_column(*c, soa.count);
  return soa;
}

std::size_t SphereSoA::memory_bytes() const {
  std::size_t bytes = bytes_of(source);
  for (const AlignedFloats* c : columns()) bytes += bytes_of(*c);
  return bytes;
}

Box primitive_box(const SphereSoA& s, std::size_t i) {
  const double c[3] = {s.cx[i], s.cy[i], s.cz[i]};
  Box b = empty_box();
  grow_ball(b, c, std::sqrt(static_cast<double>(s.r2[i])));  // the kernels use r^2
  return b;
}

// Spherical (u, v) = (longitude, latitude) / (2 pi, pi) around +y: u = 0.5
// at +x growing with a right-handed turn about +y (0.75 at -z), v = 0.5 at
// the equator, 1 at +y; the shading normal is the outward one.
void map_surface(const SphereSoA& spheres, const MappingQuery& q, SurfaceMapping& out) {
  if (!q.textured && !q.footprint) return;
  const std::uint32_t i = q.index;
  const Vec3<float> c{spheres.cx[i], spheres.cy[i], spheres.cz[i]};
  const Vec3<float> d = normalize(q.position - c);
  if (q.textured) {
    out.u = 0.5f + std::atan2(-d.z, d.x) * kInvTwoPi;
    out.v = 0.5f + std::asin(std::clamp(d.y, -1.f, 1.f)) * kInvPi;
  }
  if (!q.footprint) return;
  for (int a = 0; a < 2; ++a) {
    // The unit outward normal d's change: dp less its radial part, over r.
    const Vec3<float> dd = (q.dp[a] - d * dot(d, q.dp[a])) * spheres.inv_r[i];
    out.normal_change[a] = dd;
    out.du[a] = longitude_change(d.x, -d.z, dd.x, -dd.z);
    out.dv[a] = dd.y / std::sqrt(std::max(1.f - d.y * d.y, 0.f)) * kInvPi;
  }
}

}  // namespace quiver
