#include "integrator/surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "integrator/texture.h"

namespace quiver {

namespace {

constexpr float kInvTwoPi = float(0.5 / std::numbers::pi);
constexpr float kInvPi = float(1.0 / std::numbers::pi);

double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// (s, t) with p = a + s e + t f + s t g for a quad a, b, c, d in 2D
// (e = b - a, f = d - a, g = a - b + c - d): t from the quadratic
// cross(h - t f, e + t g) = 0, s from the better-conditioned axis.
void inverse_bilinear(const double q[4][2], double px, double py, float& s_out, float& t_out) {
  const double ex = q[1][0] - q[0][0], ey = q[1][1] - q[0][1];
  const double fx = q[3][0] - q[0][0], fy = q[3][1] - q[0][1];
  const double gx = q[0][0] - q[1][0] + q[2][0] - q[3][0], gy = q[0][1] - q[1][1] + q[2][1] - q[3][1];
  const double hx = px - q[0][0], hy = py - q[0][1];
  const double k2 = cross2(gx, gy, fx, fy);
  const double k1 = cross2(ex, ey, fx, fy) + cross2(hx, hy, gx, gy);
  const double k0 = cross2(hx, hy, ex, ey);
  double t;
  if (std::fabs(k2) <= 1e-12 * std::fabs(k1)) {
    t = k1 != 0.0 ? -k0 / k1 : 0.0;  // a parallelogram: linear
  } else {
    const double w = std::sqrt(std::max(k1 * k1 - 4.0 * k0 * k2, 0.0));
    const double t1 = (-k1 - w) / (2.0 * k2), t2 = (-k1 + w) / (2.0 * k2);
    t = (t1 >= -1e-6 && t1 <= 1.0 + 1e-6) ? t1 : t2;
  }
  const double dx = ex + gx * t, dy = ey + gy * t;
  const double s = std::fabs(dx) >= std::fabs(dy) ? (dx != 0.0 ? (hx - fx * t) / dx : 0.0)
                                                  : (hy - fy * t) / dy;
  s_out = float(s);
  t_out = float(t);
}

}  // namespace

namespace {

// d(atan2(y, x)) for a change (dx, dy) of (x, y), over 2 pi: the change of a
// longitude u.
float longitude_change(float x, float y, float dx, float dy) {
  return (x * dy - y * dx) / (x * x + y * y) * kInvTwoPi;
}

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

// The rounding error of an instance's hit beyond the world ray's: the ray
// carried in (W o and W d, each a 3-term sum per row, bounded with the same
// ulps as hit_point_error), the hit in the instance's coordinates, both
// taken back by |M|.
Vec3<float> instance_error(const Scene& scene, std::size_t row, const Ray<float>& ray, float t) {
  const AffineTransform& to_object = scene.instances.world_to_object[row];
  const AffineTransform to_object_abs = absolute(to_object);
  const Vec3<float> origin = apply_point(to_object, ray.origin);
  const Vec3<float> direction = apply_vector(to_object, ray.direction);
  const Vec3<float> abs_origin{std::fabs(ray.origin.x), std::fabs(ray.origin.y), std::fabs(ray.origin.z)};
  const Vec3<float> abs_direction{std::fabs(ray.direction.x), std::fabs(ray.direction.y), std::fabs(ray.direction.z)};
  const float e = kOffsetErrorUlps * std::numeric_limits<float>::epsilon();
  const Vec3<float> carried = apply_point(to_object_abs, abs_origin) + apply_vector(to_object_abs, abs_direction) * t;
  const Vec3<float> in_object = hit_point_error(origin, direction, t) + carried * e;
  return apply_vector(absolute(scene.instances.object_to_world[row]), in_object);
}

// A hit as the kinds' mappings read it: the primitive, whether its
// material is textured, the point (in the instance's coordinates for an
// instance) and its change per film axis (zero without a footprint).
struct MappedHit {
  const Scene& scene;
  const Hit<float>& hit;
  const GeometryLayer& g;
  std::uint32_t i;
  bool textured;
  const PointDifferentials* footprint;
  Vec3<float> position;
  Vec3<float> dp[2];
  bool instanced;
  std::size_t row;
};

// Each kind's mapping (map_surface, reached through the list of kinds) sets
// s's (u, v) (where textured), its shading normal and the normal's change,
// and du, dv: (u, v)'s change per film axis.

void map_surface(SphereKind, const MappedHit& m, SurfaceDetail& s, float du[2], float dv[2]) {
  const GeometryLayer& g = m.g;
  const std::uint32_t i = m.i;
  const bool textured = m.textured;
  const PointDifferentials* const footprint = m.footprint;
  const Vec3<float>* const dp = m.dp;
  Vec3<float>* const dn[2] = {&s.normal_dx, &s.normal_dy};
  if (!textured && footprint == nullptr) return;
  const Vec3<float> c{g.store<SphereKind>().cx[i], g.store<SphereKind>().cy[i], g.store<SphereKind>().cz[i]};
  const Vec3<float> d = normalize(m.position - c);
  if (textured) {
    s.u = 0.5f + std::atan2(-d.z, d.x) * kInvTwoPi;
    s.v = 0.5f + std::asin(std::clamp(d.y, -1.f, 1.f)) * kInvPi;
  }
  if (footprint == nullptr) return;
  for (int a = 0; a < 2; ++a) {
    // The unit outward normal d's change: dp less its radial part, over r.
    const Vec3<float> dd = (dp[a] - d * dot(d, dp[a])) * g.store<SphereKind>().inv_r[i];
    *dn[a] = dd;
    du[a] = longitude_change(d.x, -d.z, dd.x, -dd.z);
    dv[a] = dd.y / std::sqrt(std::max(1.f - d.y * d.y, 0.f)) * kInvPi;
  }
}

void map_surface(PlaneKind, const MappedHit& m, SurfaceDetail& s, float du[2], float dv[2]) {
  if (!m.textured) return;
  const Vec3<float>* const dp = m.dp;
  Vec3<float> t1, t2;
  tangent_axes(normalize(m.hit.ng), t1, t2);
  s.u = dot(m.position, t1);
  s.v = dot(m.position, t2);
  for (int a = 0; a < 2; ++a) {
    du[a] = dot(dp[a], t1);
    dv[a] = dot(dp[a], t2);
  }
}

void map_surface(TriangleKind, const MappedHit& m, SurfaceDetail& s, float du[2], float dv[2]) {
  const Hit<float>& hit = m.hit;
  const std::uint32_t i = m.i;
  const PointDifferentials* const footprint = m.footprint;
  const Vec3<float>* const dp = m.dp;
  Vec3<float>* const dn[2] = {&s.normal_dx, &s.normal_dy};
  const TriangleSoA& tri = m.scene.triangles_of(s.ref);
  const float w0 = 1.f - hit.u - hit.v;
  double db1[2] = {0.0, 0.0}, db2[2] = {0.0, 0.0};
  if (footprint != nullptr) {
    const Vec3<float> v0 = tri.vertex(i, 0);
    for (int a = 0; a < 2; ++a) barycentric_change(tri.vertex(i, 1) - v0, tri.vertex(i, 2) - v0, dp[a], db1[a], db2[a]);
  }
  for (int a = 0; a < 2; ++a) {
    du[a] = float(db1[a]);
    dv[a] = float(db2[a]);
  }
  if (tri.has_uvs()) {
    const auto a = tri.uv(i, 0), b = tri.uv(i, 1), c = tri.uv(i, 2);
    s.u = w0 * a[0] + hit.u * b[0] + hit.v * c[0];
    s.v = w0 * a[1] + hit.u * b[1] + hit.v * c[1];
    for (int k = 0; k < 2 && footprint != nullptr; ++k) {
      du[k] = float(db1[k] * (double(b[0]) - a[0]) + db2[k] * (double(c[0]) - a[0]));
      dv[k] = float(db1[k] * (double(b[1]) - a[1]) + db2[k] * (double(c[1]) - a[1]));
    }
  }
  if (!tri.has_normals()) return;
  // An instance's normals in world space (not unit: interpolation commutes with the map).
  const auto world_normal = [&](int k) {
    return m.instanced ? apply_normal(m.scene.instances.world_to_object[m.row], tri.normal(i, k)) : tri.normal(i, k);
  };
  const Vec3<float> n0 = world_normal(0), n1 = world_normal(1), n2 = world_normal(2);
  const Vec3<float> n = n0 * w0 + n1 * hit.u + n2 * hit.v;
  if (!(dot(n, n) > 0.f)) return;
  s.smooth = true;
  s.interpolated = normalize(n);
  // The unit normal's change: the interpolation's, less its part along the normal, over |n|.
  const float length = std::sqrt(dot(n, n));
  for (int a = 0; a < 2 && footprint != nullptr; ++a) {
    const Vec3<float> change = (n1 - n0) * float(db1[a]) + (n2 - n0) * float(db2[a]);
    *dn[a] = (change - s.interpolated * dot(s.interpolated, change)) / length;
  }
}

void map_surface(PolygonKind, const MappedHit& m, SurfaceDetail& s, float du[2], float dv[2]) {
  const Hit<float>& hit = m.hit;
  const std::uint32_t i = m.i;
  const PointDifferentials* const footprint = m.footprint;
  const Vec3<float>* const dp = m.dp;
  const PolygonSoA& p = m.g.store<PolygonKind>();
  const int axis_u = p.axis_u[i], axis_v = p.axis_v[i];
  for (int a = 0; a < 2; ++a) {
    du[a] = dp[a][axis_u];
    dv[a] = dp[a][axis_v];
  }
  if (!m.textured || p.vertex_count[i] != 4) return;
  double quad[4][2];
  for (int k = 0; k < 4; ++k) {
    quad[k][0] = p.pu[p.first_vertex[i] + k];
    quad[k][1] = p.pv[p.first_vertex[i] + k];
  }
  inverse_bilinear(quad, hit.u, hit.v, s.u, s.v);
  // The bilinear map's change by a finite difference over the footprint.
  for (int a = 0; a < 2 && footprint != nullptr; ++a) {
    float u_moved, v_moved;
    inverse_bilinear(quad, double(hit.u) + du[a], double(hit.v) + dv[a], u_moved, v_moved);
    du[a] = u_moved - s.u;
    dv[a] = v_moved - s.v;
  }
}

void map_surface(ConeKind, const MappedHit& m, SurfaceDetail& s, float du[2], float dv[2]) {
  if (!m.textured) return;
  const std::uint32_t i = m.i;
  const Vec3<float>& position = m.position;
  const Vec3<float>* const dp = m.dp;
  const ConeSoA& c = m.g.store<ConeKind>();
  const Vec3<float> axis{c.ax[i], c.ay[i], c.az[i]};
  const Vec3<float> base{c.bx[i], c.by[i], c.bz[i]};
  const Vec3<float> radial = position - base - axis * dot(position - base, axis);
  Vec3<float> t1, t2;
  tangent_axes(axis, t1, t2);
  s.u = 0.5f + std::atan2(dot(radial, t2), dot(radial, t1)) * kInvTwoPi;
  s.v = m.hit.u;
  for (int a = 0; a < 2; ++a) {
    const Vec3<float> radial_change = dp[a] - axis * dot(dp[a], axis);
    du[a] = longitude_change(dot(radial, t1), dot(radial, t2), dot(radial_change, t1), dot(radial_change, t2));
    dv[a] = dot(dp[a], axis) / c.height[i];
  }
}

// The material's colour at the point: times its texture where textured,
// filtered over the footprint when there is one.
Vec3<float> surface_colour(const Scene& scene, const SurfaceDetail& s, const MappedHit& m, const float du[2],
                           const float dv[2]) {
  const PointDifferentials* const footprint = m.footprint;
  const Vec3<float>& position = m.position;
  const Vec3<float>* const dp = m.dp;
  if (!m.textured) return s.material->color;
  if (footprint == nullptr) {
    return mul(evaluate(scene.textures[*s.material->texture], s.u, s.v, position), s.material->color);
  }
  // The footprint's centre, to first order on the surface (a centred
  // footprint keeps the point's bits, whatever the differentials).
  const float cx = footprint->centre_x, cy = footprint->centre_y;
  const bool shifted = cx != 0.f || cy != 0.f;
  const float u = shifted ? std::fma(cy, du[1], std::fma(cx, du[0], s.u)) : s.u;
  const float v = shifted ? std::fma(cy, dv[1], std::fma(cx, dv[0], s.v)) : s.v;
  const Vec3<float> centre = shifted ? position + dp[0] * cx + dp[1] * cy : position;
  const TextureFootprint f{du[0], dv[0], du[1], dv[1], dp[0], dp[1]};
  return mul(evaluate_filtered(scene.textures[*s.material->texture], u, v, centre, f), s.material->color);
}

}  // namespace

SurfaceDetail surface_detail(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit,
                             const PointDifferentials* footprint) {
  SurfaceDetail s;
  s.ref = scene.locate(hit.id);
  const bool instanced = s.ref.instance >= 0;
  const std::size_t row = instanced ? std::size_t(s.ref.instance) : 0;
  s.smooth = false;
  s.u = hit.u;
  s.v = hit.v;
  s.material_index = scene.origin(s.ref).material;
  s.material = &scene.materials[s.material_index];
  // Texture coordinates only for textured materials (atan2 and asin are dear).
  const bool textured = s.material->texture.has_value();
  MappedHit m{scene,
              hit,
              scene.layer(s.ref.transmissive),
              s.ref.local,
              textured,
              footprint,
              textured || footprint != nullptr ? hit_position(ray, hit.t) : Vec3<float>(0.f, 0.f, 0.f),
              {footprint != nullptr ? footprint->dx : Vec3<float>(0.f, 0.f, 0.f),
               footprint != nullptr ? footprint->dy : Vec3<float>(0.f, 0.f, 0.f)},
              instanced,
              row};
  if (instanced) {
    const AffineTransform& to_object = scene.instances.world_to_object[row];
    m.position = apply_point(to_object, m.position);
    for (Vec3<float>& d : m.dp) d = apply_vector(to_object, d);
    s.instance_error = instance_error(scene, row, ray, hit.t);
  }
  // Per film axis (x, y): the change of (u, v).
  float du[2] = {0.f, 0.f}, dv[2] = {0.f, 0.f};
  visit_kind(s.ref.kind, [&](auto kind) { map_surface(kind, m, s, du, dv); });
  s.color = surface_colour(scene, s, m, du, dv);
  return s;
}

SurfacePoint surface_at(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit) {
  const SurfaceDetail d = surface_detail(scene, ray, hit);
  SurfaceFrame<float> frame = surface_frame(ray, hit, d.smooth, d.interpolated);
  frame.error = frame.error + d.instance_error;
  return {frame, d};
}

}  // namespace quiver
