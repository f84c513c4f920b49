#include "geometry/kinds/triangle.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "geometry/parallel_indices.h"

namespace quiver {

namespace {

bool finite(const TriangleDesc& t) {
  for (const Vec3<float>& p : t.p) {
    if (!all_finite(p)) return false;
  }
  if (t.normals) {
    for (const Vec3<float>& n : *t.normals) {
      if (!all_finite(n)) return false;
    }
  }
  if (t.uvs) {
    for (const auto& uv : *t.uvs) {
      if (!std::isfinite(uv[0]) || !std::isfinite(uv[1])) return false;
    }
  }
  return true;
}

Vec3<double> to_double(const Vec3<float>& v) { return {v.x, v.y, v.z}; }

enum class Shape { ok, non_finite, degenerate };

Shape classify(const TriangleDesc& t) {
  if (!finite(t)) return Shape::non_finite;
  // The kernels' own edges and normal, in float: must be finite and not zero.
  const Vec3<float> e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
  const Vec3<float> ng = cross(e1, e2);
  if (!all_finite(e1) || !all_finite(e2) || !all_finite(t.p[2] - t.p[1]) || !all_finite(ng)) return Shape::non_finite;
  if (ng.x == 0.f && ng.y == 0.f && ng.z == 0.f) return Shape::degenerate;
  // Height over the longest edge, in double: 2 area / longest^2.
  const Vec3<double> a = to_double(t.p[0]), b = to_double(t.p[1]), c = to_double(t.p[2]);
  const Vec3<double> n = cross(b - a, c - a);
  const double twice_area = std::sqrt(dot(n, n));
  const double longest2 = std::max({dot(b - a, b - a), dot(c - a, c - a), dot(c - b, c - b)});
  if (!(twice_area > kMinTriangleRelativeHeight * longest2)) return Shape::degenerate;
  return Shape::ok;
}

Vec3<float> unit_or(const Vec3<float>& n, const Vec3<float>& fallback) {
  const Vec3<double> d = to_double(n);
  const double len = std::sqrt(dot(d, d));
  if (!(len > 0.0)) return fallback;
  const Vec3<double> u = d / len;
  return {float(u.x), float(u.y), float(u.z)};
}

}  // namespace

Vec3<float> TriangleSoA::vertex(std::size_t i, int k) const {
  switch (k) {
    case 0: return {v0x[i], v0y[i], v0z[i]};
    case 1: return {v1x[i], v1y[i], v1z[i]};
    default: return {v2x[i], v2y[i], v2z[i]};
  }
}

Vec3<float> TriangleSoA::normal(std::size_t i, int k) const {
  switch (k) {
    case 0: return {n0x[i], n0y[i], n0z[i]};
    case 1: return {n1x[i], n1y[i], n1z[i]};
    default: return {n2x[i], n2y[i], n2z[i]};
  }
}

std::array<float, 2> TriangleSoA::uv(std::size_t i, int k) const {
  switch (k) {
    case 0: return {uv0u[i], uv0v[i]};
    case 1: return {uv1u[i], uv1v[i]};
    default: return {uv2u[i], uv2v[i]};
  }
}

TriangleSoA build_triangles(const DescRefs<TriangleDesc>& triangles, BuildReport& report) {
  std::vector<Shape> shapes(triangles.size());
  for_each_index(triangles.size(), [&](std::size_t i) { shapes[i] = classify(triangles[i]); });
  std::vector<std::uint32_t> kept;
  kept.reserve(triangles.size());
  bool any_normals = false, any_uvs = false;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const TriangleDesc& t = triangles[i];
    switch (shapes[i]) {
      case Shape::non_finite: ++report.dropped_non_finite; break;
      case Shape::degenerate: ++report.dropped_degenerate; break;
      case Shape::ok:
        kept.push_back(static_cast<std::uint32_t>(i));
        any_normals = any_normals || t.normals.has_value();
        any_uvs = any_uvs || t.uvs.has_value();
        break;
    }
  }

  TriangleSoA soa;
  soa.count = kept.size();
  soa.source = kept;
  const std::size_t padded = padded_size(soa.count);
  AlignedFloats* vertex_columns[3][3] = {{&soa.v0x, &soa.v0y, &soa.v0z},
                                         {&soa.v1x, &soa.v1y, &soa.v1z},
                                         {&soa.v2x, &soa.v2y, &soa.v2z}};
  AlignedFloats* normal_columns[3][3] = {{&soa.n0x, &soa.n0y, &soa.n0z},
                                         {&soa.n1x, &soa.n1y, &soa.n1z},
                                         {&soa.n2x, &soa.n2y, &soa.n2z}};
  AlignedFloats* uv_columns[3][2] = {{&soa.uv0u, &soa.uv0v}, {&soa.uv1u, &soa.uv1v}, {&soa.uv2u, &soa.uv2v}};
  for (int k = 0; k < 3; ++k) {
    for (AlignedFloats* c : vertex_columns[k]) c->resize(padded);
    if (any_normals) {
      for (AlignedFloats* c : normal_columns[k]) c->resize(padded);
    }
    if (any_uvs) {
      for (AlignedFloats* c : uv_columns[k]) c->resize(padded);
    }
  }

  constexpr float kDefaultUv[3][2] = {{0.f, 0.f}, {1.f, 0.f}, {0.f, 1.f}};
  for_each_index(kept.size(), [&](std::size_t i) {
    const TriangleDesc& t = triangles[kept[i]];
    const Vec3<float> geometric = unit_or(cross(t.p[1] - t.p[0], t.p[2] - t.p[0]), {0.f, 0.f, 1.f});
    for (int k = 0; k < 3; ++k) {
      for (int axis = 0; axis < 3; ++axis) (*vertex_columns[k][axis])[i] = t.p[k][axis];
      if (any_normals) {
        const Vec3<float> n = t.normals ? unit_or((*t.normals)[k], geometric) : geometric;
        for (int axis = 0; axis < 3; ++axis) (*normal_columns[k][axis])[i] = n[axis];
      }
      if (any_uvs) {
        for (int j = 0; j < 2; ++j) (*uv_columns[k][j])[i] = t.uvs ? (*t.uvs)[k][j] : kDefaultUv[k][j];
      }
    }
  });
  for (AlignedFloats* c : soa.columns()) {
    if (!c->empty()) pad_column(*c, soa.count);
  }
  report.kept += soa.count;
  return soa;
}

std::vector<TriangleDesc> triangles_from_indexed(std::span<const Vec3<float>> positions,
                                                 std::span<const std::array<std::uint32_t, 3>> indices) {
  std::vector<TriangleDesc> out;
  out.reserve(indices.size());
  for (std::size_t i = 0; i < indices.size(); ++i) {
    TriangleDesc t;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t index = indices[i][k];
      if (index >= positions.size()) {
        throw std::out_of_range("triangle " + std::to_string(i) + " has vertex index " + std::to_string(index) +
                                " but the mesh has " + std::to_string(positions.size()) + " positions");
      }
      t.p[k] = positions[index];
    }
    out.push_back(t);
  }
  return out;
}

std::size_t TriangleSoA::memory_bytes() const {
  std::size_t bytes = bytes_of(source);
  for (const AlignedFloats* c : columns()) bytes += bytes_of(*c);
  return bytes;
}

Box primitive_box(const TriangleSoA& t, std::size_t i) {
  Box b = empty_box();
  for (int k = 0; k < 3; ++k) grow(b, t.vertex(i, k));
  return b;  // the vertices are stored exactly
}

namespace {

// The change of the barycentrics (b1, b2) of a triangle with edges e1, e2
// for a change dp of the point in its plane (least squares in double).
void barycentric_change(const Vec3<float>& e1, const Vec3<float>& e2, const Vec3<float>& dp, double& db1,
                        double& db2) {
  const Vec3<double> a(e1.x, e1.y, e1.z), b(e2.x, e2.y, e2.z), d(dp.x, dp.y, dp.z);
  const double aa = dot(a, a), ab = dot(a, b), bb = dot(b, b);
  const double da = dot(d, a), db = dot(d, b);
  const double det = aa * bb - ab * ab;
  db1 = (bb * da - ab * db) / det;
  db2 = (aa * db - ab * da) / det;
}

// The shadow terminator fix of Hanika, "Hacking the Shadow Terminator" (Ray
// Tracing Gems II, 2021): the hit point p (barycentrics b) projected onto
// the tangent plane of each vertex it lies below, p_k = p - min(0, (p -
// v_k).n_k) n_k, and those points blended with b. Returns the step from p
// to the blend, in the triangle's own coordinates; in double, so that a
// flat face (every n_k its normal) gives a step at rounding level.
Vec3<float> terminator_lift(const TriangleSoA& tri, std::uint32_t i, const float b[3]) {
  Vec3<double> v[3], n[3], p{0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const Vec3<float> vk = tri.vertex(i, k), nk = tri.normal(i, k);
    v[k] = {vk.x, vk.y, vk.z};
    n[k] = {nk.x, nk.y, nk.z};
    const double length = std::sqrt(dot(n[k], n[k]));
    n[k] = length > 0.0 ? n[k] * (1.0 / length) : Vec3<double>{0.0, 0.0, 0.0};
    p = p + v[k] * double(b[k]);
  }
  Vec3<double> lift{0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) lift = lift - n[k] * (double(b[k]) * std::min(0.0, dot(p - v[k], n[k])));
  return {float(lift.x), float(lift.y), float(lift.z)};
}

}  // namespace

// Per-vertex (u, v) (or the barycentrics) and normals, interpolated with
// the kernel's barycentrics; where normals are interpolated, the shadow
// rays' lift (terminator_lift).
void map_surface(const TriangleSoA& tri, const MappingQuery& q, SurfaceMapping& out) {
  const Hit<float>& hit = q.hit;
  const std::uint32_t i = q.index;
  const float w0 = 1.f - hit.u - hit.v;
  double db1[2] = {0.0, 0.0}, db2[2] = {0.0, 0.0};
  if (q.footprint) {
    const Vec3<float> v0 = tri.vertex(i, 0);
    for (int a = 0; a < 2; ++a) barycentric_change(tri.vertex(i, 1) - v0, tri.vertex(i, 2) - v0, q.dp[a], db1[a], db2[a]);
  }
  for (int a = 0; a < 2; ++a) {
    out.du[a] = float(db1[a]);
    out.dv[a] = float(db2[a]);
  }
  if (tri.has_uvs()) {
    const auto a = tri.uv(i, 0), b = tri.uv(i, 1), c = tri.uv(i, 2);
    out.u = w0 * a[0] + hit.u * b[0] + hit.v * c[0];
    out.v = w0 * a[1] + hit.u * b[1] + hit.v * c[1];
    for (int k = 0; k < 2 && q.footprint; ++k) {
      out.du[k] = float(db1[k] * (double(b[0]) - a[0]) + db2[k] * (double(c[0]) - a[0]));
      out.dv[k] = float(db1[k] * (double(b[1]) - a[1]) + db2[k] * (double(c[1]) - a[1]));
    }
  }
  if (!tri.has_normals()) return;
  // An instance's normals in world space (not unit: interpolation commutes with the map).
  const auto world_normal = [&](int k) {
    return q.world_to_object != nullptr ? apply_normal(*q.world_to_object, tri.normal(i, k)) : tri.normal(i, k);
  };
  const Vec3<float> n0 = world_normal(0), n1 = world_normal(1), n2 = world_normal(2);
  const Vec3<float> n = n0 * w0 + n1 * hit.u + n2 * hit.v;
  if (!(dot(n, n) > 0.f)) return;
  out.smooth = true;
  out.interpolated = normalize(n);
  const float barycentrics[3] = {w0, hit.u, hit.v};
  const Vec3<float> lift = terminator_lift(tri, i, barycentrics);
  out.shadow_lift = q.object_to_world != nullptr ? apply_vector(*q.object_to_world, lift) : lift;
  // The unit normal's change: the interpolation's, less its part along the normal, over |n|.
  const float length = std::sqrt(dot(n, n));
  for (int a = 0; a < 2 && q.footprint; ++a) {
    const Vec3<float> change = (n1 - n0) * float(db1[a]) + (n2 - n0) * float(db2[a]);
    out.normal_change[a] = (change - out.interpolated * dot(out.interpolated, change)) / length;
  }
}

}  // namespace quiver
