// The watertightness and self-intersection studies (watertight.csv,
// self_intersection.csv) over the counters of bench/accuracy/robustness.cpp:
// triangle methods on three closed meshes (an off-center box, an
// octasphere, a jittered octasphere 1e3 from the origin; 10^7 rays per
// method) and the polygon method on closed polygon meshes (the box's quads,
// prisms of a square, a 24-gon, a 5-point star, a 12-tooth gear and the gear
// 1e3 from the origin; 10^7 rays; and the far gear with origins as near its
// faces as the near ones', where the seed plane's t failed); acne per method,
// scene scale 1e-4..1e6 and offset rule.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bench/accuracy/closed_meshes.h"
#include "bench/accuracy/measure.h"
#include "bench/accuracy/studies.h"

namespace quiver::accuracy {
namespace {

KernelUnit widest_unit() { return units_by_width().back(); }

struct MeshCase {
  const char* name;
  ClosedMesh mesh;
  OriginSampler origins;
  std::size_t rays;
};

}  // namespace

void watertight_study(const StudyOptions& options) {
  const double share = options.quick ? 0.01 : 1.0;
  auto rays = [&](double n) { return std::size_t(n * share); };
  const Vec3<double> far_center{1000.3, -700.7, 300.1};
  const Prism square = prism(regular_outline(4, 1.5), -0.9, 1.3, {0.2, -0.1, 0.05});
  const Prism convex = prism(regular_outline(24, 1.3), -1.0, 0.7, {0, 0, 0});
  const Prism star = prism(star_outline(5, 0.6, 1.6), -0.5, 0.5, {0, 0, 0});
  const Prism gear = prism(gear_outline(12, 1.0, 1.25), -0.3, 0.3, {0, 0, 0});
  const Prism far_gear = prism(gear_outline(12, 1.0, 1.25), -0.3, 0.3, far_center);
  MeshCase cases[] = {
      {"box", box_triangles({-1.3, -0.7, -1.1}, {0.9, 1.6, 1.2}), ball_origins({-0.2f, 0.45f, 0.05f}, 0.3f), rays(4e6)},
      {"octasphere2", octasphere(2, {0, 0, 0}, {1, 1, 1}, 0.0, 1), ball_origins({0.f, 0.f, 0.f}, 0.3f), rays(3e6)},
      {"jittered_far", octasphere(2, far_center, {2.7, 1.4, 3.3}, 0.15, 2),
       ball_origins({float(far_center.x), float(far_center.y), float(far_center.z)}, 0.3f), rays(3e6)},
      {"box_quads", box_quads({-1.3, -0.7, -1.1}, {0.9, 1.6, 1.2}), ball_origins({-0.2f, 0.45f, 0.05f}, 0.3f),
       rays(2e6)},
      {"square_prism", square.mesh, prism_interior(square), rays(1.6e6)},
      {"convex_prism24", convex.mesh, prism_interior(convex), rays(1.6e6)},
      {"star_prism", star.mesh, prism_interior(star), rays(1.6e6)},
      {"gear_prism", gear.mesh, prism_interior(gear), rays(1.6e6)},
      {"gear_prism_far", far_gear.mesh, prism_interior(far_gear, 3e-2), rays(1.6e6)},
      // Origins within 1e-5 of its faces: the planes' rounding there (6e-5) decides the sign of t.
      {"gear_prism_far_grazing", far_gear.mesh, prism_interior(far_gear), rays(4e5)},
  };
  std::FILE* f = open_csv(options.out / "watertight.csv",
                          "mesh,faces,kind,method,unit,edge_rays,vertex_rays,edge_leaks,vertex_leaks");
  const KernelUnit unit = widest_unit();
  for (const MeshCase& mc : cases) {
    if (!mc.mesh.closed()) throw std::runtime_error(std::string(mc.name) + " is not closed");
    const bool polygons = mc.mesh.faces.front().size() > 3;
    for (const Method& method : kMethods) {
      if (method.kind != (polygons ? Kind::polygon : Kind::triangle)) continue;
      const LeakCount n = count_leaks(method, unit, mc.mesh, mc.origins, mc.rays, 99);
      std::fprintf(f, "%s,%zu,%s,%s,%s,%zu,%zu,%zu,%zu\n", mc.name, mc.mesh.faces.size(), method.kind_name.data(),
                   method.name.data(), kernel_unit_name(unit).data(), n.edge_rays, n.vertex_rays, n.edge_leaks,
                   n.vertex_leaks);
      std::printf("%-13s %-15s %9zu rays: %zu leaked at edges, %zu at vertices\n", mc.name, method.name.data(),
                  n.edge_rays + n.vertex_rays, n.edge_leaks, n.vertex_leaks);
      std::fflush(f);
    }
  }
  std::fclose(f);
}

void acne_study(const StudyOptions& options) {
  const std::size_t rays = rays_per_case(options);
  std::FILE* f = open_csv(options.out / "self_intersection.csv", "kind,method,default,scale,rule,spawned,rehits,acne_fraction");
  const KernelUnit unit = widest_unit();
  for (const Method& method : kMethods) {
    for (int k = -4; k <= 6; ++k) {
      const double scale = std::pow(10.0, k);
      for (const OffsetRule rule : {OffsetRule::zero, OffsetRule::epsilon, OffsetRule::robust}) {
        const AcneCount n = count_acne(method, unit, scale, rule, rays, 5);
        std::fprintf(f, "%s,%s,%d,%.9g,%s,%zu,%zu,%.9g\n", method.kind_name.data(), method.name.data(),
                     method.renderer_default ? 1 : 0, scale, offset_rule_name(rule).data(), n.spawned, n.rehits,
                     n.fraction());
      }
    }
    std::fflush(f);
  }
  std::fclose(f);
}

}  // namespace quiver::accuracy
