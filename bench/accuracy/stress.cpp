// The stress distributions of bench/accuracy/stress.h. Geometry is built in
// double, then rounded to float once (the primitive's inputs and each ray).
#include "bench/accuracy/stress.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace quiver::accuracy {
namespace {

using V = Vec3<double>;

constexpr double kPi = std::numbers::pi;

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo = 0.0, double hi = 1.0) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }

 private:
  std::mt19937_64 engine_;
};

double norm(const V& v) { return std::sqrt(dot(v, v)); }
V unit(const V& v) { return v * (1.0 / norm(v)); }
Vec3<float> to_float(const V& v) { return {float(v.x), float(v.y), float(v.z)}; }
V to_double(const Vec3<float>& v) { return {v.x, v.y, v.z}; }

V random_unit(Random& rng) {
  const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * kPi);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Two unit vectors perpendicular to unit n and to each other.
void frame(const V& n, V& t1, V& t2) {
  const V helper = std::fabs(n.x) < 0.6 ? V{1, 0, 0} : V{0, 1, 0};
  t1 = unit(cross(n, helper));
  t2 = cross(n, t1);
}

V in_plane_direction(Random& rng, const V& t1, const V& t2) {
  const double phi = rng.uniform(0.0, 2.0 * kPi);
  return t1 * std::cos(phi) + t2 * std::sin(phi);
}

// One primitive as the generator sees it: what rays need to aim at it.
struct Target {
  V center;
  double size = 1.0;
  V normal, t1, t2;          // plane, triangle, polygon: the plane's frame; cone: axis in normal
  std::array<V, 3> vertices;  // triangle
};

// What a ray generator needs to know about the distribution.
struct Aim {
  Distribution distribution;
  double parameter;  // grazing: relative distance to the silhouette or angle
  double reach;      // origin distance in sizes
};

// The star polygon's 2D vertices (radius 1 and 0.45 alternating) and its plane's slopes.
constexpr int kStarPoints = 5;
constexpr double kSlopeU = 0.5, kSlopeV = 0.25;

V polygon_point(const Target& t, double a, double b) {
  return t.center + V{a, b, kSlopeU * a + kSlopeV * b} * t.size;
}

// A direction toward a plane with the given normal: within 60 degrees of it
// (either side), or at angle `grazing` to the plane when that is positive.
V toward_plane(Random& rng, const V& normal, const V& t1, const V& t2, double grazing) {
  const V along = in_plane_direction(rng, t1, t2);
  const double side = rng.uniform() < 0.5 ? -1.0 : 1.0;
  const double angle = grazing > 0.0 ? grazing : rng.uniform(kPi / 6.0, kPi / 2.0);
  return along * std::cos(angle) + normal * (side * std::sin(angle));
}

Ray<float> ray_from(const V& through, const V& direction, double distance) {
  const V origin = through - direction * distance;
  return {to_float(origin), to_float(direction), 0.f, std::numeric_limits<float>::infinity()};
}

Ray<float> aim_ray(Kind kind, const Target& t, const Aim& aim, Random& rng) {
  const bool grazing = aim.distribution == Distribution::grazing;
  const double delta = aim.parameter;
  const double distance = aim.reach * t.size;
  switch (kind) {
    case Kind::sphere: {
      const V dir = random_unit(rng);
      V e1, e2;
      frame(dir, e1, e2);
      const double b = grazing ? 1.0 + delta * rng.uniform(-1.0, 1.0) : 1.6 * std::sqrt(rng.uniform());
      const V closest = t.center + in_plane_direction(rng, e1, e2) * (b * t.size);
      return ray_from(closest, dir, distance);
    }
    case Kind::plane: {
      const V target = t.center + in_plane_direction(rng, t.t1, t.t2) * (t.size * std::sqrt(rng.uniform()));
      V dir = toward_plane(rng, t.normal, t.t1, t.t2, grazing ? delta : 0.0);
      Ray<float> ray = ray_from(target, dir, distance);
      if (rng.uniform() < 0.3) ray.direction = -ray.direction;  // pointing away: must miss
      return ray;
    }
    case Kind::triangle: {
      // Barycentrics uniform over the triangle grown by 0.2 on each side (about 40% inside).
      double m0 = -std::log(rng.uniform(1e-300, 1.0)), m1 = -std::log(rng.uniform(1e-300, 1.0)),
             m2 = -std::log(rng.uniform(1e-300, 1.0));
      const double sum = m0 + m1 + m2;
      const double l0 = 1.6 * m0 / sum - 0.2, l1 = 1.6 * m1 / sum - 0.2, l2 = 1.6 * m2 / sum - 0.2;
      const V target = t.vertices[0] * l0 + t.vertices[1] * l1 + t.vertices[2] * l2;
      return ray_from(target, toward_plane(rng, t.normal, t.t1, t.t2, grazing ? delta : 0.0), distance);
    }
    case Kind::polygon: {
      const double r = 1.1 * std::sqrt(rng.uniform()), phi = rng.uniform(0.0, 2.0 * kPi);
      const V target = polygon_point(t, r * std::cos(phi), r * std::sin(phi));
      return ray_from(target, toward_plane(rng, t.normal, t.t1, t.t2, grazing ? delta : 0.0), distance);
    }
    case Kind::cone: break;
  }
  // Cone: a line at height f of the axis, passing b radii from it (b = +-1 is the silhouette).
  const V axis = t.normal;
  const double f = rng.uniform(0.1, 0.9);
  const double alpha = grazing ? kPi / 2.0 : rng.uniform(kPi / 6.0, 5.0 * kPi / 6.0);
  const V dir = axis * std::cos(alpha) + in_plane_direction(rng, t.t1, t.t2) * std::sin(alpha);
  const V sideways = unit(cross(axis, dir));
  const double radius = t.size * (1.0 - 0.5 * f);
  const double sign = rng.uniform() < 0.5 ? -1.0 : 1.0;
  const double b = grazing ? sign * (1.0 + delta * rng.uniform(-1.0, 1.0)) : sign * 1.6 * std::sqrt(rng.uniform());
  const V through = t.center + axis * (2.0 * t.size * f) + sideways * (b * radius);
  return ray_from(through, dir, distance);
}

// The input descriptions of a case's primitives, one list per kind.
struct PrimitiveDescs {
  std::vector<SphereDesc> spheres;
  std::vector<PlaneDesc> planes;
  std::vector<TriangleDesc> triangles;
  std::vector<PolygonDesc> polygons;
  std::vector<ConeDesc> cones;

  Primitives build(Kind kind) const {
    Primitives p;
    p.kind = kind;
    BuildReport report;
    p.spheres = build_spheres(spheres, report);
    p.planes = build_planes(planes, report);
    p.triangles = build_triangles(triangles, report);
    p.polygons = build_polygons(polygons, report);
    p.cones = build_cones(cones, report);
    return p;
  }
};

// Adds a primitive of `kind` at center with size to descs; returns its aiming data.
Target add_primitive(Kind kind, const V& center_in, double size, Random& rng, PrimitiveDescs& descs) {
  Target t;
  t.center = to_double(to_float(center_in));
  t.size = size;
  switch (kind) {
    case Kind::sphere:
      descs.spheres.push_back({to_float(t.center), float(size)});
      break;
    case Kind::plane:
      t.normal = random_unit(rng);
      frame(t.normal, t.t1, t.t2);
      descs.planes.push_back({to_float(t.center), to_float(t.normal)});
      break;
    case Kind::triangle: {
      t.normal = random_unit(rng);
      frame(t.normal, t.t1, t.t2);
      TriangleDesc desc;
      for (int k = 0; k < 3; ++k) {
        const double phi = 2.0 * kPi * k / 3.0 + rng.uniform(-0.3, 0.3), rho = rng.uniform(0.7, 1.0);
        t.vertices[std::size_t(k)] = t.center + (t.t1 * std::cos(phi) + t.t2 * std::sin(phi)) * (rho * size);
        desc.p[std::size_t(k)] = to_float(t.vertices[std::size_t(k)]);
        t.vertices[std::size_t(k)] = to_double(desc.p[std::size_t(k)]);
      }
      descs.triangles.push_back(desc);
      break;
    }
    case Kind::polygon: {
      t.normal = unit(V{-kSlopeU, -kSlopeV, 1.0});
      t.t1 = unit(V{1.0, 0.0, kSlopeU});
      t.t2 = cross(t.normal, t.t1);
      PolygonDesc desc;
      for (int k = 0; k < 2 * kStarPoints; ++k) {
        const double phi = kPi * k / kStarPoints + rng.uniform(-0.1, 0.1), rho = k % 2 == 0 ? 1.0 : 0.45;
        // x, y rounded first, z from the rounded x, y: planar up to z's rounding.
        const V p = polygon_point(t, rho * std::cos(phi), rho * std::sin(phi));
        const float x = float(p.x), y = float(p.y);
        const double z = t.center.z + kSlopeU * (double(x) - t.center.x) + kSlopeV * (double(y) - t.center.y);
        desc.vertices.push_back({x, y, float(z)});
      }
      descs.polygons.push_back(desc);
      break;
    }
    case Kind::cone: {
      t.normal = random_unit(rng);
      frame(t.normal, t.t1, t.t2);
      descs.cones.push_back({to_float(t.center), float(size), to_float(t.center + t.normal * (2.0 * size)), float(0.5 * size)});
      break;
    }
  }
  return t;
}

const V kNearOrigin{0.3, -0.2, 0.1};
const V kFarDirection{0.48, -0.6, 0.64};

}  // namespace

std::string_view distribution_name(Distribution d) {
  switch (d) {
    case Distribution::distance: return "distance";
    case Distribution::size: return "size";
    case Distribution::far: return "far";
    case Distribution::grazing: break;
  }
  return "grazing";
}

std::vector<double> sweep_parameters(Distribution d) {
  std::vector<double> p;
  switch (d) {
    case Distribution::distance:
      p.push_back(2.0);
      for (int k = 2; k <= 14; ++k) p.push_back(std::pow(10.0, k / 2.0));
      break;
    case Distribution::size:
      for (int k = -12; k <= 12; k += 2) p.push_back(std::pow(10.0, k));
      break;
    case Distribution::far:
      for (int k = 0; k <= 14; ++k) p.push_back(std::pow(10.0, k / 2.0));
      break;
    case Distribution::grazing:
      for (int k = 1; k <= 7; ++k) p.push_back(std::pow(10.0, -k));
      break;
  }
  return p;
}

Case make_case(Kind kind, Distribution distribution, double parameter, std::size_t ray_count, std::uint32_t seed) {
  Random rng(seed * 7919ULL + std::uint64_t(kind) * 104729ULL + std::uint64_t(distribution));
  V center = kNearOrigin;
  double size = 1.0, reach = 10.0;
  switch (distribution) {
    case Distribution::distance: reach = parameter; break;
    case Distribution::size:
      size = parameter;
      center = kNearOrigin * parameter;
      break;
    case Distribution::far: center = kFarDirection * parameter; break;
    case Distribution::grazing: break;
  }
  PrimitiveDescs descs;
  const Target target = add_primitive(kind, center, size, rng, descs);
  Case c{distribution, parameter, descs.build(kind), RaySoA(ray_count)};
  const Aim aim{distribution, parameter, reach};
  for (std::size_t i = 0; i < ray_count; ++i) c.rays.set(i, aim_ray(kind, target, aim, rng));
  c.rays.pad();
  return c;
}

Case make_timing_case(Kind kind, std::uint32_t seed) {
  constexpr int kPrimitives = 64;
  constexpr std::size_t kRays = 4096;
  Random rng(seed);
  PrimitiveDescs descs;
  std::vector<Target> targets;
  for (int i = 0; i < kPrimitives; ++i) {
    const V center{rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0)};
    targets.push_back(add_primitive(kind, center, rng.uniform(0.5, 1.5), rng, descs));
  }
  Case c{Distribution::distance, 30.0, descs.build(kind), RaySoA(kRays)};
  for (std::size_t i = 0; i < kRays; ++i) {
    const Target& t = targets[std::size_t(rng.uniform(0.0, double(kPrimitives) - 1e-9))];
    c.rays.set(i, aim_ray(kind, t, Aim{Distribution::distance, 30.0, 30.0 / t.size}, rng));
  }
  c.rays.pad();
  return c;
}

}  // namespace quiver::accuracy
