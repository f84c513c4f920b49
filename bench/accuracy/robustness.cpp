// Kernel-level robustness counters (bench/accuracy/measure.h).
// Watertightness: rays from inside a closed mesh aimed exactly at points of
// shared edges (a float point of the segment) and at shared vertices; a ray
// that hits no face leaked.
// Self-intersection: at a scene scale (the size sweep's case: primitive of
// size S at S (0.3, -0.2, 0.1), rays from 10 S away), every hit point
// p = o + t d (float, as integrator/surface.cpp computes it) spawns a ray
// into the hemisphere of the side the ray came from, by three rules:
//   zero:     origin p, tmin = 0;
//   epsilon:  origin p, tmin = 1e-4 (a fixed scene epsilon, unit direction);
//   robust:   origin offset_origin(p, hit_point_error(o, d, t), side normal),
//             tmin = 0 (integrator/optics.h, what the renderer does).
// Every primitive here bounds a convex region and only hits from outside
// are used, so any re-hit of the same primitive is acne.
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "bench/accuracy/measure.h"
#include "integrator/optics.h"

namespace quiver::accuracy {
namespace {

Vec3<float> random_unit(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    const double x = u(rng), y = u(rng), z = u(rng), n = x * x + y * y + z * z;
    if (n > 1e-6 && n <= 1.0) {
      const double s = 1.0 / std::sqrt(n);
      return {float(x * s), float(y * s), float(z * s)};
    }
  }
}

}  // namespace

LeakCount count_leaks(const Method& method, KernelUnit unit, const ClosedMesh& mesh, const OriginSampler& origins,
                      std::size_t ray_count, std::uint32_t seed) {
  Primitives prims;
  prims.kind = method.kind;
  BuildReport report;
  if (method.kind == Kind::triangle) {
    prims.triangles = build_triangles(mesh.triangles(), report);
  } else if (method.kind == Kind::polygon) {
    prims.polygons = build_polygons(mesh.polygons(), report);
  } else {
    throw std::invalid_argument("leaks are counted for triangle and polygon methods");
  }
  if (prims.size() != mesh.faces.size()) throw std::runtime_error("a closed mesh lost faces in the builder");
  const auto edges = mesh.edges();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> along(0.f, 1.f);
  LeakCount count;
  constexpr std::size_t kChunk = std::size_t(1) << 18;
  RaySoA rays(kChunk);
  std::vector<char> at_vertex(kChunk);
  for (std::size_t done = 0; done < ray_count; done += kChunk) {
    const std::size_t n = std::min(kChunk, ray_count - done);
    rays.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3<float> origin = origins(rng);
      // Two thirds at edges, one third at vertices.
      Vec3<float> target;
      at_vertex[i] = (done + i) % 3 == 2;
      if (at_vertex[i]) {
        target = mesh.positions[std::size_t(rng() % mesh.positions.size())];
      } else {
        const auto& [a, b] = edges[std::size_t(rng() % edges.size())];
        const Vec3<float> pa = mesh.positions[a], pb = mesh.positions[b];
        target = pa + (pb - pa) * along(rng);
      }
      rays.push({origin, target - origin, 0.f, std::numeric_limits<float>::infinity()});
    }
    rays.pad();
    const OcclusionSoA occlusion = run_unit_occluded(method, unit, rays, prims);
    for (std::size_t i = 0; i < n; ++i) {
      ++(at_vertex[i] ? count.vertex_rays : count.edge_rays);
      if (occlusion.occluded[i] == 0) ++(at_vertex[i] ? count.vertex_leaks : count.edge_leaks);
    }
  }
  return count;
}

OriginSampler ball_origins(const Vec3<float>& center, float inner) {
  return [center, inner](std::mt19937_64& rng) {
    std::uniform_real_distribution<float> reach(0.f, inner);
    return center + random_unit(rng) * reach(rng);
  };
}

AcneCount count_acne(const Method& method, KernelUnit unit, double scale, OffsetRule rule, std::size_t ray_count,
                     std::uint32_t seed) {
  const Case c = make_case(method.kind, Distribution::size, scale, ray_count, seed);
  AcneCount count;
  if (c.prims.size() == 0) return count;
  const HitSoA first = run_unit(method, unit, c.rays, c.prims);
  std::mt19937_64 rng(seed);
  RaySoA spawned;
  for (std::size_t i = 0; i < c.rays.count; ++i) {
    const Hit<float> hit = first.get(i);
    if (hit.id == kNoHit) continue;
    const Ray<float> ray = c.rays.get(i);
    const Vec3<float> unit_normal = normalize(hit.ng);
    // Only hits from outside (the convex side); for a plane, triangle or polygon either side is outside.
    const bool from_front = dot(ray.direction, unit_normal) < 0.f;
    if (!from_front && (method.kind == Kind::sphere || method.kind == Kind::cone)) continue;
    const Vec3<float> side = from_front ? unit_normal : -unit_normal;
    const Vec3<float> p = ray.origin + ray.direction * hit.t;
    Vec3<float> direction = random_unit(rng);
    if (dot(direction, side) < 0.f) direction = -direction;
    Ray<float> next{p, direction, 0.f, std::numeric_limits<float>::infinity()};
    if (rule == OffsetRule::epsilon) next.tmin = kFixedEpsilon;
    if (rule == OffsetRule::robust) next.origin = offset_origin(p, hit_point_error(ray.origin, ray.direction, hit.t), side);
    spawned.push(next);
  }
  spawned.pad();
  count.spawned = spawned.count;
  const HitSoA again = run_unit(method, unit, spawned, c.prims);
  count.rehits = again.hit_count();
  return count;
}

std::string_view offset_rule_name(OffsetRule rule) {
  switch (rule) {
    case OffsetRule::zero: return "zero";
    case OffsetRule::epsilon: return "epsilon";
    case OffsetRule::robust: break;
  }
  return "robust";
}

}  // namespace quiver::accuracy
