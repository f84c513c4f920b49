#include "app/scene_broadcast.h"

#include <mpi.h>

#include <algorithm>
#include <cstddef>
#include <type_traits>

#include "scene/scene_fields.h"

namespace quiver {

namespace {

// MPI counts are ints: a long field goes in pieces of at most 1 GiB.
constexpr std::size_t kPieceBytes = std::size_t{1} << 30;

// An archive (scene/scene_fields.h) over MPI_Bcast from rank 0: rank 0's
// reads its scene, every other rank's fills its own.
template <bool Reading>
struct BroadcastArchive {
  static constexpr bool kReading = Reading;

  void bytes(void* data, std::size_t size) {
    auto* at = static_cast<std::byte*>(data);
    while (size > 0) {
      const std::size_t piece = std::min(size, kPieceBytes);
      MPI_Bcast(at, static_cast<int>(piece), MPI_BYTE, 0, MPI_COMM_WORLD);
      at += piece;
      size -= piece;
    }
  }
  // Rank 0's lengths describe its own scene, built by this same program.
  void count(std::size_t& n, std::size_t) { bytes(&n, sizeof n); }
};

struct Timings {
  double load_ms, build_ms;
};

// The plan, the timings and the scene through the archive, in that order on every rank.
template <class Archive>
void transfer_prepared(Archive archive, PreparedRender& prepared, Timings& timings) {
  archive.bytes(&prepared.plan, sizeof prepared.plan);
  archive.bytes(&timings, sizeof timings);
  transfer_scene(archive, prepared.scene);
}

}  // namespace

void broadcast_prepared_render(PreparedRender& prepared, int rank, Isa isa) {
  static_assert(std::is_trivially_copyable_v<RenderPlan>);
  Timings timings{prepared.load_ms, prepared.build_ms};
  if (rank == 0) {
    transfer_prepared(BroadcastArchive<false>{}, prepared, timings);
    return;
  }
  transfer_prepared(BroadcastArchive<true>{}, prepared, timings);
  prepared.plan.settings.isa = isa;
  prepared.load_ms = timings.load_ms;
  prepared.build_ms = timings.build_ms;
}

}  // namespace quiver
