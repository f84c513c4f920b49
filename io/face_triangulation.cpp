#include "io/face_triangulation.h"

#include "geometry/kinds/polygon.h"

namespace quiver {

void triangulate_face(std::span<const Vec3<float>> p, std::vector<std::array<std::size_t, 3>>& triples) {
  triples.clear();
  const std::size_t n = p.size();
  auto fan = [&] {
    for (std::size_t k = 1; k + 1 < n; ++k) triples.push_back({0, k, k + 1});
  };
  if (n == 3) return fan();
  // Newell normal, then the turn at every corner against it (in double).
  const Vec3<double> normal = newell_normal(p);
  bool convex = true;
  for (std::size_t i = 0; i < n && convex; ++i) {
    const Vec3<float>& a = p[(i + n - 1) % n];
    const Vec3<float>& b = p[i];
    const Vec3<float>& c = p[(i + 1) % n];
    const Vec3<double> e1(double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z);
    const Vec3<double> e2(double(c.x) - b.x, double(c.y) - b.y, double(c.z) - b.z);
    convex = dot(cross(e1, e2), normal) >= 0.0;
  }
  if (convex) return fan();
  const PolygonDesc polygon{std::vector<Vec3<float>>(p.begin(), p.end())};
  const std::vector<std::array<Vec3<float>, 3>> triangles = triangulate_polygon(polygon);
  if (triangles.empty()) return fan();
  // Ear clipping returns the input vertices themselves: find their corners.
  auto corner_of = [&](const Vec3<float>& v) {
    for (std::size_t i = 0; i < n; ++i) {
      if (p[i].x == v.x && p[i].y == v.y && p[i].z == v.z) return i;
    }
    return std::size_t{0};
  };
  for (const auto& t : triangles) triples.push_back({corner_of(t[0]), corner_of(t[1]), corner_of(t[2])});
}

}  // namespace quiver
