#include "geometry/kinds/plane.h"

#include <cmath>

namespace quiver {

PlaneSoA build_planes(const DescRefs<PlaneDesc>& planes, BuildReport& report) {
  PlaneSoA soa;
  for (AlignedFloats* c : soa.columns()) c->reserve(padded_size(planes.size()));
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const PlaneDesc& p = planes[i];
    if (!all_finite(p.point) || !all_finite(p.normal)) {
      ++report.dropped_non_finite;
      continue;
    }
    const float len = length(p.normal);
    if (!(len > 0.f) || !std::isfinite(len)) {
      ++report.dropped_degenerate;
      continue;
    }
    const Vec3<float> n = p.normal / len;
    const float d = -dot(n, p.point);
    if (!std::isfinite(d)) {
      ++report.dropped_non_finite;
      continue;
    }
    soa.source.push_back(static_cast<std::uint32_t>(i));
    soa.nx.push_back(n.x);
    soa.ny.push_back(n.y);
    soa.nz.push_back(n.z);
    soa.d.push_back(d);
    soa.px.push_back(p.point.x);
    soa.py.push_back(p.point.y);
    soa.pz.push_back(p.point.z);
  }
  soa.count = soa.nx.size();
  report.kept += soa.count;
  for (AlignedFloats* c : soa.columns()) pad_column(*c, soa.count);
  return soa;
}

std::size_t PlaneSoA::memory_bytes() const {
  std::size_t bytes = source.capacity() * sizeof(std::uint32_t);
  for (const AlignedFloats* c : columns()) bytes += bytes_of(*c);
  return bytes;
}

// Planar (u, v): the point along the two tangent axes of the normal.
void map_surface(const PlaneSoA&, const MappingQuery& q, SurfaceMapping& out) {
  if (!q.textured) return;
  Vec3<float> t1, t2;
  tangent_axes(normalize(q.hit.ng), t1, t2);
  out.u = dot(q.position, t1);
  out.v = dot(q.position, t2);
  for (int a = 0; a < 2; ++a) {
    out.du[a] = dot(q.dp[a], t1);
    out.dv[a] = dot(q.dp[a], t2);
  }
}

}  // namespace quiver
