#include "integrator/surface.h"

#include <algorithm>
#include <cmath>
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

Vec3<float> material_color(const Scene& scene, const MaterialDesc& m, float u, float v, const Vec3<float>& p) {
  if (!m.texture) return m.color;
  return mul(evaluate(scene.textures[*m.texture], u, v, p), m.color);
}

}  // namespace

SurfaceDetail surface_detail(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit) {
  SurfaceDetail s;
  s.ref = scene.locate(hit.id);
  const GeometryLayer& g = scene.layer(s.ref.transmissive);
  const std::uint32_t i = s.ref.local;
  s.smooth = false;
  s.u = hit.u;
  s.v = hit.v;
  s.material_index = scene.origin(s.ref).material;
  s.material = &scene.materials[s.material_index];
  // Texture coordinates only for textured materials (atan2 and asin are dear).
  const bool textured = s.material->texture.has_value();
  const Vec3<float> position = textured ? hit_position(ray, hit.t) : Vec3<float>(0.f, 0.f, 0.f);
  switch (s.ref.kind) {
    case PrimitiveKind::sphere: {
      if (!textured) break;
      const Vec3<float> c{g.spheres.cx[i], g.spheres.cy[i], g.spheres.cz[i]};
      const Vec3<float> d = normalize(position - c);
      s.u = 0.5f + std::atan2(-d.z, d.x) * kInvTwoPi;
      s.v = 0.5f + std::asin(std::clamp(d.y, -1.f, 1.f)) * kInvPi;
      break;
    }
    case PrimitiveKind::plane: {
      if (!textured) break;
      Vec3<float> t1, t2;
      tangent_axes(normalize(hit.ng), t1, t2);
      s.u = dot(position, t1);
      s.v = dot(position, t2);
      break;
    }
    case PrimitiveKind::triangle: {
      const TriangleSoA& tri = g.triangles;
      const float w0 = 1.f - hit.u - hit.v;
      if (tri.has_uvs()) {
        const auto a = tri.uv(i, 0), b = tri.uv(i, 1), c = tri.uv(i, 2);
        s.u = w0 * a[0] + hit.u * b[0] + hit.v * c[0];
        s.v = w0 * a[1] + hit.u * b[1] + hit.v * c[1];
      }
      if (tri.has_normals()) {
        const Vec3<float> n = tri.normal(i, 0) * w0 + tri.normal(i, 1) * hit.u + tri.normal(i, 2) * hit.v;
        if (dot(n, n) > 0.f) {
          s.smooth = true;
          s.interpolated = normalize(n);
        }
      }
      break;
    }
    case PrimitiveKind::polygon: {
      const PolygonSoA& p = g.polygons;
      if (textured && p.vertex_count[i] == 4) {
        double quad[4][2];
        for (int k = 0; k < 4; ++k) {
          quad[k][0] = p.pu[p.first_vertex[i] + k];
          quad[k][1] = p.pv[p.first_vertex[i] + k];
        }
        inverse_bilinear(quad, hit.u, hit.v, s.u, s.v);
      }
      break;
    }
    case PrimitiveKind::cone: {
      if (!textured) break;
      const ConeSoA& c = g.cones;
      const Vec3<float> axis{c.ax[i], c.ay[i], c.az[i]};
      const Vec3<float> base{c.bx[i], c.by[i], c.bz[i]};
      const Vec3<float> radial = position - base - axis * dot(position - base, axis);
      Vec3<float> t1, t2;
      tangent_axes(axis, t1, t2);
      s.u = 0.5f + std::atan2(dot(radial, t2), dot(radial, t1)) * kInvTwoPi;
      s.v = hit.u;
      break;
    }
  }
  s.color = material_color(scene, *s.material, s.u, s.v, position);
  return s;
}

SurfacePoint surface_at(const Scene& scene, const Ray<float>& ray, const Hit<float>& hit) {
  const SurfaceDetail d = surface_detail(scene, ray, hit);
  return {surface_frame(ray, hit, d.smooth, d.interpolated), d};
}

}  // namespace quiver
