#include "tests/support/study_streams.h"

namespace quiver {

SceneStreams study_scene_streams(KernelUnit unit, SphereMethod sphere) {
  SceneStreams s = product_scene_streams(unit, sphere);
  with_kernel_unit(unit, [&](auto u) {
    constexpr KernelUnit U = decltype(u)::value;
    s.kinds.of<SphereKind>().tree = study_sphere_bvh_streams<U>(sphere);
    s.kinds.of<TriangleKind>().tree = study_triangle_bvh_streams<U>(TriangleMethod::watertight);
    s.kinds.of<PolygonKind>().tree = study_polygon_bvh_streams<U>(PolygonMethod::crossing);
    s.kinds.of<ConeKind>().tree = study_cone_bvh_streams<U>(ConeMethod::quadric);
    s.instance_bvh = study_instance_bvh_streams<U>();
  });
  return s;
}

}  // namespace quiver
