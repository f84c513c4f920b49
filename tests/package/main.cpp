// Links the installed quiver::quiver and traces one ray: exit 0 on the expected hit.
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/kind_streams.h"

int main() {
  quiver::BuildReport report;
  const std::vector<quiver::PlaneDesc> floor{{{0, 0, 0}, {0, 1, 0}}};
  const quiver::PlaneSoA planes = quiver::build_planes(floor, report);
  quiver::RaySoA rays(1);
  rays.set(0, {{0, 2, 0}, {0, -1, 0}, 0.f, 1e30f});
  rays.pad();
  quiver::HitSoA hits(rays);
  const quiver::KernelUnit unit = quiver::kernel_unit_for(quiver::isa_from_environment());
  const auto streams = quiver::with_kernel_unit(
      unit, [](auto u) { return quiver::product_streams_of<decltype(u)::value, quiver::PlaneKind>(quiver::PlaneMethod::anchored).scan; });
  streams.closest_packets(rays, planes, hits);
  std::printf("%s unit: hit id %d at t %g\n", std::string(quiver::kernel_unit_name(unit)).c_str(), hits.id[0],
              double(hits.t[0]));
  return hits.id[0] == 0 && hits.t[0] == 2.f ? 0 : 1;
}
