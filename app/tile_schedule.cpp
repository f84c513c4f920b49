#include "app/tile_schedule.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace quiver {

TileSchedule::TileSchedule(std::size_t tiles, const std::vector<bool>& done, const std::vector<double>& costs,
                           int ranks)
    : state_(tiles), costs_(costs), outstanding_(std::size_t(std::max(ranks, 1)), 0), ranks_(std::max(ranks, 1)) {
  if (!done.empty() && done.size() != tiles) throw std::invalid_argument("TileSchedule: one done flag per tile");
  if (!costs.empty() && costs.size() != tiles) throw std::invalid_argument("TileSchedule: one cost per tile");
  std::vector<std::uint32_t> order;
  for (std::size_t t = 0; t < tiles; ++t) {
    work_.add_to_total(weight(std::uint32_t(t)));
    if (!done.empty() && done[t]) {
      state_[t].done = true;
      ++done_count_;
      work_.add_done(weight(std::uint32_t(t)));
    } else {
      order.push_back(std::uint32_t(t));
    }
  }
  if (!costs.empty()) {
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return costs[a] > costs[b]; });
  }
  waiting_.assign(order.begin(), order.end());
  if (!costs_.empty()) {
    for (const std::uint32_t t : waiting_) waiting_cost_ += std::max(costs_[t], 0.0);
  }
}

double TileSchedule::weight(std::uint32_t tile) const {
  return costs_.empty() ? 1.0 : WorkDone::weight(costs_[tile]);
}

std::size_t TileSchedule::batch_size() const {
  return std::clamp<std::size_t>(waiting_.size() / (8 * std::size_t(ranks_)), 1, 16);
}

std::vector<std::uint32_t> TileSchedule::take(int rank, std::size_t max_tiles) {
  std::vector<std::uint32_t> batch;
  const std::size_t n = std::min({batch_size(), max_tiles, waiting_.size()});
  const double budget = waiting_cost_ / (8.0 * double(ranks_));
  double cost = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t t = waiting_.front();
    const double tile_cost = costs_.empty() ? 0.0 : std::max(costs_[t], 0.0);
    if (k > 0 && cost + tile_cost > budget) break;
    cost += tile_cost;
    waiting_cost_ -= tile_cost;
    waiting_.pop_front();
    state_[t].ranks.push_back(rank);
    given_.push_back(t);
    batch.push_back(t);
  }
  outstanding_[std::size_t(rank)] += batch.size();
  return batch;
}

std::optional<std::uint32_t> TileSchedule::reissue(int rank) {
  if (!waiting_.empty()) return std::nullopt;
  while (!given_.empty() && (state_[given_.back()].done || state_[given_.back()].reissued)) given_.pop_back();
  for (auto it = given_.rbegin(); it != given_.rend(); ++it) {
    const std::uint32_t t = *it;
    TileState& s = state_[t];
    if (s.done || s.reissued) continue;
    if (std::find(s.ranks.begin(), s.ranks.end(), rank) != s.ranks.end()) continue;
    s.reissued = true;
    s.ranks.push_back(rank);
    ++outstanding_[std::size_t(rank)];
    return t;
  }
  return std::nullopt;
}

bool TileSchedule::complete(std::uint32_t tile, int rank) {
  if (tile >= state_.size()) throw std::out_of_range("TileSchedule: no tile " + std::to_string(tile));
  TileState& s = state_[tile];
  const auto it = std::find(s.ranks.begin(), s.ranks.end(), rank);
  if (it != s.ranks.end()) {
    s.ranks.erase(it);
    --outstanding_[std::size_t(rank)];
  }
  if (s.done) return false;
  s.done = true;
  ++done_count_;
  work_.add_done(weight(tile));
  // The other ranks it is out on will answer too; their answers are dropped.
  for (const int other : s.ranks) --outstanding_[std::size_t(other)];
  s.ranks.clear();
  return true;
}

}  // namespace quiver
