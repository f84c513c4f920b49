// The intersector methods the accuracy study compares, one primitive store
// per case, and three ways to run a method on it: a kernel unit's packet
// stream (float, width 1, 4 or 8; geometry/kind_streams.h), the same kernel
// template at double precision (bench/accuracy/lane64.h), and the oracle
// (bench/accuracy/oracle.h).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "bench/accuracy/oracle.h"
#include "geometry/kind_streams.h"

namespace quiver::accuracy {

enum class Kind { sphere, plane, triangle, polygon, cone };

struct Method {
  Kind kind;
  int method;  // the kind's method enum (SphereMethod, ...) as an int
  std::string_view kind_name, name;
  bool renderer_default;  // what integrator/scene_intersector.cpp uses
};

inline constexpr std::array<Method, 9> kMethods = {{
    {Kind::sphere, int(SphereMethod::algebraic), "sphere", "algebraic", false},
    {Kind::sphere, int(SphereMethod::geometric), "sphere", "geometric", false},
    {Kind::sphere, int(SphereMethod::robust), "sphere", "robust", true},
    {Kind::plane, int(PlaneMethod::seed), "plane", "seed", false},
    {Kind::plane, int(PlaneMethod::anchored), "plane", "anchored", true},
    {Kind::triangle, int(TriangleMethod::moller_trumbore), "triangle", "moller_trumbore", false},
    {Kind::triangle, int(TriangleMethod::watertight), "triangle", "watertight", true},
    {Kind::polygon, int(PolygonMethod::crossing), "polygon", "crossing", true},
    {Kind::cone, int(ConeMethod::quadric), "cone", "quadric", true},
}};

// The method named kind/name; throws std::invalid_argument for an unknown one.
const Method& find_method(std::string_view kind_name, std::string_view name);

// One case's primitives: only the store of `kind` is used.
struct Primitives {
  Kind kind = Kind::sphere;
  SphereSoA spheres;
  PlaneSoA planes;
  TriangleSoA triangles;
  PolygonSoA polygons;
  ConeSoA cones;

  std::size_t size() const;
};

// Closest hits of a kernel unit's packet stream (rays and hits in SoA).
HitSoA run_unit(const Method& method, KernelUnit unit, const RaySoA& rays, const Primitives& prims);

// Any-hit of a kernel unit's packet stream.
OcclusionSoA run_unit_occluded(const Method& method, KernelUnit unit, const RaySoA& rays, const Primitives& prims);

// The same kernel template evaluated with double lanes, one ray at a time.
struct DoubleHit {
  bool hit = false;
  double t = 0.0;
  std::int32_t id = kNoHit;
};
std::vector<DoubleHit> run_double(const Method& method, const RaySoA& rays, const Primitives& prims);

// The oracle's closest hit for every ray.
std::vector<Reference> run_oracle(const RaySoA& rays, const Primitives& prims);

// The kernel units this CPU runs, one per width (scalar_fma for width 1 where FMA exists).
std::vector<KernelUnit> units_by_width();

}  // namespace quiver::accuracy
