// quiver-mpi's tile queue, kept by rank 0 (app/mpi_render.h): which tiles
// are waiting, out on which rank, or done. Tiles go out most expensive
// first (by an estimated cost), in batches of at most an eighth of a rank's
// share of the estimated cost still waiting (so the costliest tiles go out
// one by one, to different ranks) and at most 16 tiles, shrinking as the
// queue empties, down to one tile; once nothing waits, a rank left idle gets
// again a tile still out on another rank (a slow or stalled one, or one
// with tiles queued), and the first result for a tile wins. No MPI here: the queue is testable alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "integrator/render.h"

namespace quiver {

class TileSchedule {
 public:
  // tiles: the frame's tile count; done: tiles already finished (resumed
  // from a checkpoint), empty for none; costs: an estimate per tile, higher
  // first (ties in tile order); ranks: the processes, rank 0 included.
  TileSchedule(std::size_t tiles, const std::vector<bool>& done, const std::vector<double>& costs, int ranks);

  // The next batch for rank, at most max_tiles: the costliest waiting tiles,
  // up to batch_size() of them whose estimated cost adds up to at most the
  // waiting cost over 8 per rank (one tile at least); empty when none waits.
  std::vector<std::uint32_t> take(int rank, std::size_t max_tiles);
  // The most tiles a batch holds now: waiting tiles over 8 per rank, 1 to 16.
  std::size_t batch_size() const;

  // Once nothing waits: a tile out on another rank (the one given out last,
  // likely still queued there rather than half done), not done, not already
  // out on this rank, not yet given again; none if there is no such tile.
  std::optional<std::uint32_t> reissue(int rank);

  // A result from rank. True for the tile's first result (place it), false
  // for a repeat (drop it).
  bool complete(std::uint32_t tile, int rank);

  std::size_t outstanding(int rank) const { return outstanding_[std::size_t(rank)]; }
  std::size_t waiting() const { return waiting_.size(); }
  std::size_t done_count() const { return done_count_; }
  // The share of the work done: done tiles weighted as WorkDone weighs
  // their estimated cost (by count without costs), 0 to 1.
  double work_done() const { return work_.share(); }
  std::size_t tile_count() const { return state_.size(); }
  bool all_done() const { return done_count_ == state_.size(); }
  bool is_done(std::uint32_t tile) const { return state_[tile].done; }

 private:
  struct TileState {
    bool done = false;
    bool reissued = false;
    std::vector<int> ranks;  // out on these
  };
  std::vector<TileState> state_;
  std::vector<double> costs_;          // empty: unknown
  double waiting_cost_ = 0.0;
  WorkDone work_;
  std::deque<std::uint32_t> waiting_;  // most expensive first
  std::deque<std::uint32_t> given_;    // in the order they went out
  std::vector<std::size_t> outstanding_;
  std::size_t done_count_ = 0;
  int ranks_;

  double weight(std::uint32_t tile) const;
};

}  // namespace quiver
