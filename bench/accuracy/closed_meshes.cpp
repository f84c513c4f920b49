// Closed meshes of bench/accuracy/closed_meshes.h.
#include "bench/accuracy/closed_meshes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

namespace quiver::accuracy {
namespace {

using V = Vec3<double>;

V on_unit_sphere(const V& v) { return v * (1.0 / std::sqrt(dot(v, v))); }

// The 8 corners of [lo, hi]: bit 0 picks x, bit 1 y, bit 2 z.
std::vector<Vec3<float>> box_corners(const V& lo, const V& hi) {
  std::vector<Vec3<float>> corners;
  for (int i = 0; i < 8; ++i) {
    corners.push_back({float(i & 1 ? hi.x : lo.x), float(i & 2 ? hi.y : lo.y), float(i & 4 ? hi.z : lo.z)});
  }
  return corners;
}

// The box's sides as corner quads, counter-clockwise from outside.
constexpr std::array<std::array<std::uint32_t, 4>, 6> kBoxSides = {
    {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> ClosedMesh::edges() const {
  std::set<std::pair<std::uint32_t, std::uint32_t>> unique;
  for (const auto& f : faces) {
    for (std::size_t k = 0; k < f.size(); ++k) unique.insert(std::minmax(f[k], f[(k + 1) % f.size()]));
  }
  return {unique.begin(), unique.end()};
}

bool ClosedMesh::closed() const {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& f : faces) {
    for (std::size_t k = 0; k < f.size(); ++k) ++directed[{f[k], f[(k + 1) % f.size()]}];
  }
  return std::all_of(directed.begin(), directed.end(), [&](const auto& entry) {
    const auto reverse = directed.find({entry.first.second, entry.first.first});
    return entry.second == 1 && reverse != directed.end() && reverse->second == 1;
  });
}

std::vector<TriangleDesc> ClosedMesh::triangles() const {
  std::vector<TriangleDesc> out;
  for (const auto& f : faces) out.push_back({{positions[f[0]], positions[f[1]], positions[f[2]]}, {}, {}});
  return out;
}

std::vector<PolygonDesc> ClosedMesh::polygons() const {
  std::vector<PolygonDesc> out;
  for (const auto& f : faces) {
    PolygonDesc p;
    for (const std::uint32_t index : f) p.vertices.push_back(positions[index]);
    out.push_back(p);
  }
  return out;
}

ClosedMesh octasphere(int levels, const V& center, const V& scale, double jitter, std::uint32_t seed) {
  std::vector<V> unit_points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<std::array<std::uint32_t, 3>> faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                     {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint_of;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, inserted] = midpoint_of.try_emplace(key, std::uint32_t(unit_points.size()));
      if (inserted) unit_points.push_back(on_unit_sphere((unit_points[a] + unit_points[b]) * 0.5));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> finer;
    for (const auto& f : faces) {
      const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({ab, f[1], bc});
      finer.push_back({ca, bc, f[2]});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> push(1.0 - jitter, 1.0 + jitter);
  ClosedMesh mesh;
  for (const V& p : unit_points) {
    const double r = push(rng);
    mesh.positions.push_back({float(center.x + p.x * r * scale.x), float(center.y + p.y * r * scale.y),
                              float(center.z + p.z * r * scale.z)});
  }
  for (const auto& f : faces) mesh.faces.push_back({f[0], f[1], f[2]});
  return mesh;
}

ClosedMesh box_triangles(const V& lo, const V& hi) {
  ClosedMesh mesh{box_corners(lo, hi), {}};
  for (const auto& q : kBoxSides) {
    mesh.faces.push_back({q[0], q[1], q[2]});
    mesh.faces.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

ClosedMesh box_quads(const V& lo, const V& hi) {
  ClosedMesh mesh{box_corners(lo, hi), {}};
  for (const auto& q : kBoxSides) mesh.faces.push_back({q[0], q[1], q[2], q[3]});
  return mesh;
}

}  // namespace quiver::accuracy
