// Links the installed quiver::quiver and traces one ray: exit 0 on the expected hit.
#include <cstdio>
#include <vector>

#include "geometry/plane_streams.h"

int main() {
  quiver::BuildReport report;
  const std::vector<quiver::PlaneDesc> floor{{{0, 0, 0}, {0, 1, 0}}};
  const quiver::PlaneSoA planes = quiver::build_planes(floor, report);
  quiver::RaySoA rays(1);
  rays.set(0, {{0, 2, 0}, {0, -1, 0}, 0.f, 1e30f});
  rays.pad();
  quiver::HitSoA hits(rays);
  quiver::plane_streams<1>(quiver::PlaneMethod::seed).closest_packets(rays, planes, hits);
  std::printf("hit id %d at t %g\n", hits.id[0], double(hits.t[0]));
  return hits.id[0] == 0 && hits.t[0] == 2.f ? 0 : 1;
}
