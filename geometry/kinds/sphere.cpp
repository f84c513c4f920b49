#include "geometry/kinds/sphere.h"

#include <cmath>
#include <limits>

#include "geometry/primitive_bounds.h"

namespace quiver {

SphereSoA build_spheres(std::span<const SphereDesc> spheres, BuildReport& report) {
  SphereSoA soa;
  for (AlignedFloats* c : {&soa.cx, &soa.cy, &soa.cz, &soa.r2, &soa.inv_r}) c->reserve(padded_size(spheres.size()));
  for (const SphereDesc& s : spheres) {
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
    soa.source.push_back(static_cast<std::uint32_t>(&s - spheres.data()));
    soa.cx.push_back(c.x);
    soa.cy.push_back(c.y);
    soa.cz.push_back(c.z);
    soa.r2.push_back(r2);
    soa.inv_r.push_back(1.f / s.radius);
  }
  soa.count = soa.cx.size();
  report.kept += soa.count;
  for (AlignedFloats* c : {&soa.cx, &soa.cy, &soa.cz, &soa.r2, &soa.inv_r}) pad_column(*c, soa.count);
  return soa;
}

std::size_t SphereSoA::memory_bytes() const {
  std::size_t bytes = bytes_of(source);
  for (const AlignedFloats* c : {&cx, &cy, &cz, &r2, &inv_r}) bytes += bytes_of(*c);
  return bytes;
}

Box primitive_box(const SphereSoA& s, std::size_t i) {
  const double c[3] = {s.cx[i], s.cy[i], s.cz[i]};
  Box b = empty_box();
  grow_ball(b, c, std::sqrt(static_cast<double>(s.r2[i])));  // the kernels use r^2
  return b;
}

}  // namespace quiver
