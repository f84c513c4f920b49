#include "python/ray_queries.h"

#include <atomic>
#include <limits>
#include <stdexcept>

#include <tbb/enumerable_thread_specific.h>

#include "integrator/ray_batches.h"

namespace quiver {

namespace {

// Answers every batch of rays with Answers (HitSoA or OcclusionSoA); use(first
// ray index, batch rays, answers) writes them out.
template <class Answers, class Use>
void query_arrays(const Scene& scene, const RayArrays& arrays, const RayInterval& interval,
                  const QueryThreads& threads, Use&& use) {
  ThreadArena arena(threads.threads);
  const SceneIntersector intersector(kernel_unit_for(threads.isa));
  tbb::enumerable_thread_specific<RaySoA> thread_rays;
  std::atomic<std::size_t> first_bad{arrays.count};
  query_batches<Answers>(
      arena, intersector, scene, batch_count(arrays.count),
      [&](std::size_t b) -> const RaySoA& {
        RaySoA& rays = thread_rays.local();
        read_ray_batch(arrays, b, interval, rays, first_bad);
        return rays;
      },
      [&](std::size_t b, const RaySoA& rays, const Answers& answers) { use(b * kRayBatchSize, rays, answers); });
  if (first_bad.load() < arrays.count) throw std::invalid_argument(bad_ray_message(arrays, first_bad.load()));
}

}  // namespace

void intersect_rays(const PythonScene& scene, const RayArrays& rays, const RayInterval& interval,
                    const QueryThreads& threads, const HitColumns& out) {
  query_arrays<HitSoA>(scene.built, rays, interval, threads, [&](std::size_t first, const RaySoA& batch, const HitSoA& hits) {
    for (std::size_t i = 0; i < batch.count; ++i) {
      const std::size_t k = first + i;
      float* normal = out.normal + 3 * k;
      if (hits.id[i] == kNoHit) {
        out.t[k] = std::numeric_limits<float>::infinity();
        out.primitive[k] = out.kind[k] = out.instance[k] = -1;
        out.u[k] = out.v[k] = 0.f;
        normal[0] = normal[1] = normal[2] = 0.f;
        continue;
      }
      const Vec3<float> n = normalize(Vec3<float>(hits.ngx[i], hits.ngy[i], hits.ngz[i]));
      out.t[k] = hits.t[i];
      const std::size_t id = std::size_t(hits.id[i]);
      if (id < scene.index_of_id.size()) {
        out.primitive[k] = scene.index_of_id[id];
        out.kind[k] = scene.kind_of_id[id];
        out.instance[k] = -1;
      } else {  // an instance's triangle: its index in its mesh
        const PrimitiveRef ref = scene.built.locate(hits.id[i]);
        out.primitive[k] = static_cast<std::int32_t>(scene.built.origin(ref).index);
        out.kind[k] = static_cast<std::int32_t>(kind_tag<TriangleKind>);
        out.instance[k] = static_cast<std::int32_t>(scene.built.instances.source[std::size_t(ref.instance)]);
      }
      out.u[k] = hits.u[i];
      out.v[k] = hits.v[i];
      normal[0] = n.x;
      normal[1] = n.y;
      normal[2] = n.z;
    }
  });
}

void occluded_rays(const Scene& scene, const RayArrays& rays, const RayInterval& interval,
                   const QueryThreads& threads, std::uint8_t* blocked) {
  query_arrays<OcclusionSoA>(scene, rays, interval, threads,
                             [&](std::size_t first, const RaySoA& batch, const OcclusionSoA& occlusion) {
                               for (std::size_t i = 0; i < batch.count; ++i) {
                                 blocked[first + i] = occlusion.occluded[i] != 0 ? 1 : 0;
                               }
                             });
}

}  // namespace quiver
