// Scene queries over many rays held as batches of RaySoA: the batches are
// spread over a ThreadArena's threads, one batch per task (oneTBB's simple
// partitioner), and each thread keeps one answer stream (HitSoA for closest
// hits, OcclusionSoA for any hit in both layers) across its batches.
// rays_of(b) gives batch b's rays: a batch the caller stored, or one it
// fills in a buffer of the calling thread's own; use(b, rays, answers) reads
// the answers before the thread takes another batch. `quiver trace`
// (app/trace_command.h) and the Python module's intersect and occluded
// (python/ray_queries.h) both query through here.
#pragma once

#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "integrator/scene_intersector.h"
#include "integrator/thread_arena.h"

namespace quiver {

// One batch's answers: the closest hits, or whether each ray is blocked.
inline void answer_batch(const SceneIntersector& intersector, const Scene& scene, const RaySoA& rays,
                         HitSoA& hits) {
  hits.reset(rays);
  intersector.closest(scene, rays, hits);
}
inline void answer_batch(const SceneIntersector& intersector, const Scene& scene, const RaySoA& rays,
                         OcclusionSoA& occlusion) {
  occlusion.reset(rays);
  intersector.occluded(scene, rays, occlusion, Layers::both);
}

// Answers (HitSoA or OcclusionSoA) for batches [0, batch_count).
template <class Answers, class RaysOf, class Use>
void query_batches(ThreadArena& arena, const SceneIntersector& intersector, const Scene& scene,
                   std::size_t batch_count, RaysOf&& rays_of, Use&& use) {
  tbb::enumerable_thread_specific<Answers> thread_answers;
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, batch_count, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          Answers& answers = thread_answers.local();
          for (std::size_t b = range.begin(); b != range.end(); ++b) {
            const RaySoA& rays = rays_of(b);
            answer_batch(intersector, scene, rays, answers);
            use(b, rays, answers);
          }
        },
        tbb::simple_partitioner());
  });
}

}  // namespace quiver
