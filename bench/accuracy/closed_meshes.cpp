// Closed meshes of bench/accuracy/closed_meshes.h.
#include "bench/accuracy/closed_meshes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>

namespace quiver::accuracy {
namespace {

using V = Vec3<double>;

V on_unit_sphere(const V& v) { return v * (1.0 / std::sqrt(dot(v, v))); }

// Winding number of the closed polygon (x[k], y[k]) around (px, py), 0 also
// when the point is on an edge (only points strictly inside count).
int strict_winding(const std::vector<std::array<double, 2>>& ring, double px, double py) {
  int wn = 0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto& a = ring[k];
    const auto& b = ring[(k + 1) % ring.size()];
    const double left = (b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1]);
    const bool within = std::min(a[0], b[0]) <= px && px <= std::max(a[0], b[0]) &&
                        std::min(a[1], b[1]) <= py && py <= std::max(a[1], b[1]);
    if (left == 0 && within) return 0;
    if (a[1] <= py) {
      if (b[1] > py && left > 0) ++wn;
    } else if (b[1] <= py && left < 0) {
      --wn;
    }
  }
  return wn;
}

// Distance from (px, py) to the closed polygon's boundary.
double boundary_distance(const std::vector<std::array<double, 2>>& ring, double px, double py) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto& a = ring[k];
    const auto& b = ring[(k + 1) % ring.size()];
    const double ex = b[0] - a[0], ey = b[1] - a[1], len2 = ex * ex + ey * ey;
    const double s = std::clamp(((px - a[0]) * ex + (py - a[1]) * ey) / len2, 0.0, 1.0);
    best = std::min(best, std::hypot(px - (a[0] + s * ex), py - (a[1] + s * ey)));
  }
  return best;
}

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

Outline regular_outline(int sides, double radius) {
  Outline out;
  for (int i = 0; i < sides; ++i) {
    const double a = 2 * std::numbers::pi * i / sides;
    out.push_back({radius * std::cos(a), radius * std::sin(a)});
  }
  return out;
}

Outline star_outline(int points, double inner, double outer) {
  Outline out;
  for (int i = 0; i < 2 * points; ++i) {
    const double a = std::numbers::pi * i / points, r = i % 2 ? inner : outer;
    out.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return out;
}

Outline gear_outline(int teeth, double root, double tip) {
  Outline out;
  const double step = 2 * std::numbers::pi / teeth;
  for (int i = 0; i < teeth; ++i) {
    const double a = step * i;
    for (const auto& [share, r] : {std::pair{0.0, root}, {0.3, tip}, {0.55, tip}, {0.8, root}}) {
      out.push_back({r * std::cos(a + share * step), r * std::sin(a + share * step)});
    }
  }
  return out;
}

Prism prism(const Outline& outline, double z0, double z1, const V& offset) {
  const std::uint32_t n = std::uint32_t(outline.size());
  Prism p{{}, outline, z0, z1, offset};
  for (const double z : {z0, z1}) {
    for (const auto& [x, y] : outline) {
      p.mesh.positions.push_back({float(offset.x + x), float(offset.y + y), float(offset.z + z)});
    }
  }
  std::vector<std::uint32_t> top, bottom;
  for (std::uint32_t i = 0; i < n; ++i) {
    top.push_back(n + i);
    bottom.push_back(n - 1 - i);
    const std::uint32_t j = (i + 1) % n;
    p.mesh.faces.push_back({i, j, n + j, n + i});  // outward: the outline turns left
  }
  p.mesh.faces.push_back(top);
  p.mesh.faces.push_back(bottom);
  return p;
}

OriginSampler prism_interior(const Prism& p, double nearest) {
  // The float outline and heights, relative to nothing: checks see the stored floats.
  std::vector<std::array<double, 2>> ring;
  const std::size_t n = p.outline.size();
  for (std::size_t i = 0; i < n; ++i) ring.push_back({p.mesh.positions[i].x, p.mesh.positions[i].y});
  const double z_lo = p.mesh.positions[0].z, z_hi = p.mesh.positions[n].z;
  double lo_x = ring[0][0], hi_x = lo_x, lo_y = ring[0][1], hi_y = lo_y, shortest = hi_x - lo_x + hi_y - lo_y;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& [x, y] = ring[k];
    lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
    shortest = std::min(shortest, std::hypot(ring[(k + 1) % n][0] - x, ring[(k + 1) % n][1] - y));
  }
  const double lowest = std::log10(nearest);
  // No origin nearer to a face than `nearest` of the height or the shortest side (a tenth less for rounding).
  const double z_clear = 0.9 * nearest * (z_hi - z_lo), side_clear = 0.9 * nearest * shortest;
  return [ring, z_lo, z_hi, lo_x, hi_x, lo_y, hi_y, lowest, z_clear, side_clear](std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto log_uniform = [&](double lo_exp, double hi_exp) { return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * unit(rng)); };
    const double height = z_hi - z_lo;
    for (;;) {
      const int kind = int(rng() % 3);
      double x = lo_x + (hi_x - lo_x) * unit(rng), y = lo_y + (hi_y - lo_y) * unit(rng);
      double z = z_lo + height * unit(rng);
      if (kind == 1) {
        const double gap = height * log_uniform(lowest, std::max(lowest, -2.0));
        z = rng() % 2 ? z_lo + gap : z_hi - gap;
      } else if (kind == 2) {
        const auto& a = ring[std::size_t(rng() % ring.size())];
        const auto& b = ring[(std::size_t(&a - ring.data()) + 1) % ring.size()];
        const double s = 0.05 + 0.9 * unit(rng), ex = b[0] - a[0], ey = b[1] - a[1];
        const double inward = log_uniform(lowest, std::max(lowest, -3.0));  // of the side's length; left of a->b is inside
        x = a[0] + s * ex - inward * ey;
        y = a[1] + s * ey + inward * ex;
      }
      const Vec3<float> origin{float(x), float(y), float(z)};
      if (origin.z - z_lo >= z_clear && z_hi - origin.z >= z_clear && strict_winding(ring, origin.x, origin.y) != 0 &&
          boundary_distance(ring, origin.x, origin.y) >= side_clear) {
        return origin;
      }
    }
  };
}

}  // namespace quiver::accuracy
