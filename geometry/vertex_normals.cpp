// Angle-weighted vertex normals with a crease angle (geometry/vertex_normals.h):
// face normals and corner angles in double, the corners around each vertex
// gathered in one compressed array (offsets per position), then each
// corner's weighted sum over the faces within the crease angle of its own.
// The per-face passes run in parallel (oneTBB); each writes only its own
// faces and sums a vertex's faces in corner order, so the normals are the
// same bits for any thread count.
#include "geometry/vertex_normals.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "geometry/parallel_indices.h"

namespace quiver {

namespace {

struct Face {
  Vec3<double> normal{0.0, 0.0, 0.0};  // unit; zero for a degenerate face
  std::array<double, 3> angle{};       // radians at each corner
  bool valid() const { return normal.x != 0.0 || normal.y != 0.0 || normal.z != 0.0; }
};

Vec3<double> widened(const Vec3<float>& p) { return {double(p.x), double(p.y), double(p.z)}; }

Vec3<float> narrowed(const Vec3<double>& v) { return {float(v.x), float(v.y), float(v.z)}; }

double norm(const Vec3<double>& v) { return std::sqrt(dot(v, v)); }

// The angle at a between the edges to b and c: atan2 of |e1 x e2| and
// e1.e2 keeps its digits for small and for obtuse angles alike.
double corner_angle(const Vec3<double>& a, const Vec3<double>& b, const Vec3<double>& c) {
  const Vec3<double> e1 = b - a;
  const Vec3<double> e2 = c - a;
  return std::atan2(norm(cross(e1, e2)), dot(e1, e2));
}

Face face_of(const std::array<Vec3<double>, 3>& p) {
  Face face;
  const Vec3<double> n = cross(p[1] - p[0], p[2] - p[0]);
  const double length = norm(n);
  if (!(length > 0.0) || !std::isfinite(length)) return face;
  face.normal = n / length;
  for (std::size_t k = 0; k < 3; ++k) face.angle[k] = corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
  return face;
}

}  // namespace

bool valid_crease_angle(double crease_angle_degrees) {
  return crease_angle_degrees >= 0.0 && crease_angle_degrees <= kMaxCreaseAngleDegrees;
}

void smooth_vertex_normals(std::span<const Vec3<float>> positions, std::span<const TriangleIndices> triangles,
                           double crease_angle_degrees,
                           const std::function<void(std::size_t, const CornerNormals&)>& write_smoothed) {
  if (!valid_crease_angle(crease_angle_degrees)) {
    throw std::invalid_argument("smooth_vertex_normals: the crease angle is not in [0, 180] degrees");
  }
  if (triangles.size() >= std::numeric_limits<std::uint32_t>::max() / 3) {
    throw std::length_error("smooth_vertex_normals: 2^32 / 3 triangles at most");
  }
  for (const TriangleIndices& t : triangles) {
    for (std::uint32_t i : t) {
      if (i >= positions.size()) throw std::invalid_argument("smooth_vertex_normals: a vertex index is out of range");
    }
  }
  if (crease_angle_degrees == 0.0) return;

  std::vector<Face> faces(triangles.size());
  for_each_index(triangles.size(), [&](std::size_t t) {
    const TriangleIndices& v = triangles[t];
    faces[t] = face_of({widened(positions[v[0]]), widened(positions[v[1]]), widened(positions[v[2]])});
  });

  // The corners (3 t + k) of valid faces around each position:
  // corners[first[v] .. first[v + 1]).
  std::vector<std::uint32_t> first(positions.size() + 1, 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!faces[t].valid()) continue;
    for (std::uint32_t v : triangles[t]) ++first[v + 1];
  }
  for (std::size_t v = 0; v < positions.size(); ++v) first[v + 1] += first[v];
  std::vector<std::uint32_t> corners(first.back());
  {
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (!faces[t].valid()) continue;
      for (std::size_t k = 0; k < 3; ++k) corners[next[triangles[t][k]]++] = static_cast<std::uint32_t>(3 * t + k);
    }
  }

  // Within the crease angle: the normals' dot product at least its cosine
  // (every face at 180 degrees, whatever the rounding of the dot product).
  const double min_cosine = crease_angle_degrees >= kMaxCreaseAngleDegrees
                                ? -std::numeric_limits<double>::infinity()
                                : std::cos(crease_angle_degrees * (std::numbers::pi / 180.0));
  for_each_index(triangles.size(), [&](std::size_t t) {
    const Face& face = faces[t];
    if (!face.valid()) return;
    const Vec3<float> flat = narrowed(face.normal);
    CornerNormals normals{flat, flat, flat};
    bool smoothed = false;  // some corner's normal is not the face normal
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = triangles[t][k];
      if (first[v + 1] - first[v] > kMaxSmoothedValence) continue;
      Vec3<double> sum{0.0, 0.0, 0.0};
      for (std::size_t c = first[v]; c < first[v + 1]; ++c) {
        const std::size_t s = corners[c] / 3;
        const Face& other = faces[s];
        if (s != t && dot(other.normal, face.normal) < min_cosine) continue;
        sum = sum + other.angle[corners[c] % 3] * other.normal;
      }
      const double length = norm(sum);
      if (!(length > 0.0)) continue;  // opposite faces cancelled out
      normals[k] = narrowed(sum / length);
      smoothed = smoothed || normals[k].x != flat.x || normals[k].y != flat.y || normals[k].z != flat.z;
    }
    if (smoothed) write_smoothed(t, normals);
  });
}

}  // namespace quiver
