// quiver-mpi's one read of the scene: rank 0 reads and builds it, then
// broadcasts the built scene, field by field in the order
// scene/scene_fields.h lists them, with its render plan, to every other
// rank, which neither reads the scene's files nor builds it. Collective over
// MPI_COMM_WORLD; needs MPI initialised; the data of each field goes
// straight from rank 0's scene into the receiving scene (no staging copy).
#pragma once

#include "app/render_job.h"

namespace quiver {

// Rank 0 sends prepared's plan, load and build times and scene; every other
// rank receives them into prepared (its desc and inputs stay empty) and keeps
// its own SIMD unit, `isa`, in the plan. Throws what allocation throws on a
// receiving rank, which then holds part of a scene: the job must end.
void broadcast_prepared_render(PreparedRender& prepared, int rank, Isa isa);

}  // namespace quiver
