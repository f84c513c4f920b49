// scene.intersect and scene.occluded without Python: the rays of RayArrays
// answered in batches (integrator/ray_batches.h, as `quiver trace`) over
// every thread asked for, each batch read from the arrays and its answers
// written to the output columns by the thread that traced it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "python/python_scene.h"
#include "python/ray_arrays.h"
#include "scene/scene.h"
#include "simd/isa.h"

namespace quiver {

struct QueryThreads {
  int threads = 0;  // 0: every core
  Isa isa = Isa::scalar;
};

// Output columns of count rays each (normal: count x 3), row-major.
// A hit: t (along the direction as given, in its units), the primitive's
// kind (PrimitiveKind) and index in its kind's input list, the kernel's
// (u, v), the unit geometric normal as the primitive orients it. A miss:
// t = inf, kind = primitive = -1, u = v = 0, normal = 0.
struct HitColumns {
  float* t;
  std::int32_t* primitive;
  std::int32_t* kind;
  float* u;
  float* v;
  float* normal;
  std::int32_t* instance;  // the [[instances]] entry hit (its index in the file), -1 off instances
};

// Closest hits in (tmin, tmax). Throws std::invalid_argument naming the
// first bad ray (ray_arrays.h) after the query.
void intersect_rays(const PythonScene& scene, const RayArrays& rays, const RayInterval& interval,
                    const QueryThreads& threads, const HitColumns& out);

// blocked[i] = 1 when something lies in (tmin, tmax) along ray i, else 0.
// Throws as intersect_rays.
void occluded_rays(const Scene& scene, const RayArrays& rays, const RayInterval& interval,
                   const QueryThreads& threads, std::uint8_t* blocked);

}  // namespace quiver
