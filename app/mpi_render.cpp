#include "app/mpi_render.h"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <utility>
#include <deque>
#include <exception>
#include <filesystem>
#include <iostream>
#include <list>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/checkpoint.h"
#include "app/interrupt.h"
#include "app/mpi_stats.h"
#include "app/progress_bar.h"
#include "app/scene_broadcast.h"
#include "app/stats_json.h"
#include "app/tile_schedule.h"
#include "io/image_output.h"
#include "io/output_file.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Message tags. Rank 0 to a worker: kTagWork (tile indices as uint32; none:
// no more work). A worker to rank 0: kTagTile (uint32 tile, double ms, the
// packed tile), then kTagReport (its RankReport) once told there is no more
// work. kTagError: a failing rank's message for agree_on.
constexpr int kTagWork = 1, kTagTile = 2, kTagReport = 3, kTagError = 4;
// How long the communicating thread sleeps between polls when nothing wakes
// it: MPI's blocking calls spin, which would take a core from the renderers.
constexpr auto kPollInterval = std::chrono::milliseconds(1);

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int world_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Receives the message Iprobe found, as bytes.
std::vector<std::byte> receive_bytes(const MPI_Status& probed) {
  int count = 0;
  MPI_Get_count(&probed, MPI_BYTE, &count);
  std::vector<std::byte> bytes(std::size_t(std::max(count, 0)));
  MPI_Recv(bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}

// Non-blocking sends whose buffers live until MPI is done with them.
class Sends {
 public:
  void send(std::vector<std::byte> bytes, int to, int tag) {
    pending_.push_back({std::move(bytes), MPI_REQUEST_NULL});
    Pending& p = pending_.back();
    MPI_Isend(p.bytes.data(), int(p.bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD, &p.request);
  }
  // Frees the finished ones; true when none is left.
  bool progress() {
    for (auto it = pending_.begin(); it != pending_.end();) {
      int done = 0;
      MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
      it = done ? pending_.erase(it) : std::next(it);
    }
    return pending_.empty();
  }

 private:
  struct Pending {
    std::vector<std::byte> bytes;
    MPI_Request request;
  };
  std::list<Pending> pending_;
};

std::vector<std::byte> tile_message(std::uint32_t tile, double ms, std::size_t payload) {
  std::vector<std::byte> bytes(sizeof tile + sizeof ms);
  std::memcpy(bytes.data(), &tile, sizeof tile);
  std::memcpy(bytes.data() + sizeof tile, &ms, sizeof ms);
  bytes.reserve(bytes.size() + payload);
  return bytes;
}
constexpr std::size_t kTileHeader = sizeof(std::uint32_t) + sizeof(double);

void send_work(const std::vector<std::uint32_t>& tiles, int to) {
  MPI_Send(tiles.data(), int(tiles.size() * sizeof(std::uint32_t)), MPI_BYTE, to, kTagWork, MPI_COMM_WORLD);
}

// Tiles done in this process by its render threads, with their times.
struct LocalTile {
  std::uint32_t tile;
  double ms;
};

// The render threads of one rank, fed tile by tile; run() on a thread of
// its own, while the calling thread talks to MPI.
class RankRenderer {
 public:
  RankRenderer(FrameRenderer& renderer, Film& film) : renderer_(renderer), film_(film) {}

  // Renders what next() gives until it gives none or *stop.
  void run(const TileSource& next, const std::atomic<bool>* stop = nullptr) {
    const Clock::time_point start = Clock::now();
    renderer_.render_tiles(
        film_, next,
        [&](std::size_t tile, double ms) {
          std::lock_guard lock(mutex_);
          finished_.push_back({std::uint32_t(tile), ms});
          busy_ms_ += ms;
          woken_.notify_all();
        },
        stop);
    std::lock_guard lock(mutex_);
    render_ms_ = ms_since(start);
    ended_ = true;
    woken_.notify_all();
  }

  // Waits until a tile finished or the renderer ended, at most `wait`.
  void wait(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    woken_.wait_for(lock, wait, [&] { return !finished_.empty() || ended_; });
  }
  std::vector<LocalTile> take_finished() {
    std::lock_guard lock(mutex_);
    return std::exchange(finished_, {});
  }
  bool ended() {
    std::lock_guard lock(mutex_);
    return ended_;
  }
  double busy_ms() {
    std::lock_guard lock(mutex_);
    return busy_ms_;
  }
  double render_ms() {
    std::lock_guard lock(mutex_);
    return render_ms_;
  }
  // For a source that blocks: wakes the communicating thread's wait too.
  std::mutex& mutex() { return mutex_; }
  std::condition_variable& woken() { return woken_; }

 private:
  FrameRenderer& renderer_;
  Film& film_;
  std::mutex mutex_;
  std::condition_variable woken_;
  std::vector<LocalTile> finished_;
  double busy_ms_ = 0.0, render_ms_ = 0.0;
  bool ended_ = false;
};

RankReport own_report(const FrameRenderer& renderer, RankRenderer& rank_renderer, std::uint64_t tiles,
                      std::uint64_t repeated) {
  RankReport report;
  report.threads = renderer.threads();
  report.tiles = tiles;
  report.tiles_repeated = repeated;
  report.render_ms = rank_renderer.render_ms();
  report.busy_ms = rank_renderer.busy_ms();
  report.stats = renderer.stats();
  return report;
}

// A rank other than 0: renders the tiles rank 0 sends, sends each back as
// soon as it is done, and its report once rank 0 says there is no more.
void run_worker(FrameRenderer& renderer, double start_ms) {
  Film film = renderer.make_film();
  RankRenderer rank_renderer(renderer, film);
  std::deque<std::uint32_t> queue;
  bool no_more = false;
  std::thread render_thread([&] {
    rank_renderer.run([&]() -> std::optional<std::size_t> {
      std::unique_lock lock(rank_renderer.mutex());
      // Woken by the communicating thread when work (or the end) arrives.
      while (queue.empty() && !no_more) rank_renderer.woken().wait(lock);
      if (queue.empty()) return std::nullopt;
      const std::uint32_t t = queue.front();
      queue.pop_front();
      return t;
    });
  });
  Sends sends;
  std::uint64_t sent = 0;
  while (true) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(0, kTagWork, MPI_COMM_WORLD, &flag, &status);
    while (flag) {
      const std::vector<std::byte> bytes = receive_bytes(status);
      std::vector<std::uint32_t> tiles(bytes.size() / sizeof(std::uint32_t));
      std::memcpy(tiles.data(), bytes.data(), tiles.size() * sizeof(std::uint32_t));
      {
        std::lock_guard lock(rank_renderer.mutex());
        if (tiles.empty()) {
          no_more = true;
          queue.clear();  // every tile is done elsewhere
        }
        queue.insert(queue.end(), tiles.begin(), tiles.end());
      }
      rank_renderer.woken().notify_all();
      MPI_Iprobe(0, kTagWork, MPI_COMM_WORLD, &flag, &status);
    }
    for (const LocalTile& done : rank_renderer.take_finished()) {
      std::vector<std::byte> message = tile_message(done.tile, done.ms, renderer.tile_bytes(done.tile));
      renderer.pack_tile(film, done.tile, message);
      sends.send(std::move(message), 0, kTagTile);
      ++sent;
    }
    const bool all_sent = sends.progress();
    if (rank_renderer.ended() && all_sent) break;
    rank_renderer.wait(kPollInterval);
  }
  render_thread.join();
  // After every tile (MPI keeps one sender's messages in order); rank 0
  // counts the tiles itself, repeats apart.
  RankReport own = own_report(renderer, rank_renderer, sent, 0);
  own.start_ms = start_ms;
  const std::vector<std::byte> report = encode_rank_report(own);
  MPI_Send(report.data(), int(report.size()), MPI_BYTE, 0, kTagReport, MPI_COMM_WORLD);
}

// What rank 0 ends the render with.
struct Gathered {
  MpiJobSummary summary;
  std::vector<double> tile_ms;  // first results; NaN for resumed tiles
  std::vector<double> costs;    // the estimates the queue was ordered by
};

// Rank 0: the queue, its own render threads, the workers' results, the
// checkpoints and the progress bar.
class Coordinator {
 public:
  Coordinator(FrameRenderer& renderer, Film& film, TileSchedule& schedule, CheckpointWriter& checkpoint,
              double checkpoint_interval_s, ProgressBar& progress, int ranks)
      : renderer_(renderer),
        film_(film),
        schedule_(schedule),
        checkpoint_(checkpoint),
        interval_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(checkpoint_interval_s))),
        progress_(progress),
        ranks_(ranks),
        placed_(std::size_t(ranks), 0),
        repeated_(std::size_t(ranks), 0),
        reports_(std::size_t(ranks)),
        tile_ms_(schedule.tile_count(), std::numeric_limits<double>::quiet_NaN()) {}

  Gathered run(std::size_t resumed) {
    const Clock::time_point start = Clock::now();
    // Rank 0's threads render into a film of their own; this thread copies
    // each tile into the image when it is the first result, so a tile
    // rendered here and on a worker never writes the image twice.
    Film own_film = renderer_.make_film();
    RankRenderer own(renderer_, own_film);
    std::atomic<bool> all_done{false};
    std::thread render_thread([&] {
      own.run(
          [&]() -> std::optional<std::size_t> {
            std::lock_guard lock(schedule_mutex_);
            const std::vector<std::uint32_t> tile = schedule_.take(0, 1);
            if (!tile.empty()) return tile.front();
            return schedule_.reissue(0);  // at the end, a tile still queued on a worker
          },
          &all_done);
    });
    {
      std::lock_guard lock(schedule_mutex_);
      for (int r = 1; r < ranks_; ++r) refill(r);
    }
    last_checkpoint_ = Clock::now();
    bool told_to_end = false;
    int reported = 0;
    while (true) {
      receive(reported);
      place_own_tiles(own, own_film);
      const std::size_t done_count = hand_out_work(told_to_end, all_done);
      progress_.update(done_count, schedule_.tile_count(), schedule_.work_done());
      if (stop_requested()) interrupted(done_count);
      if (Clock::now() - last_checkpoint_ >= interval_) save();
      if (told_to_end && reported == ranks_ - 1 && own.ended()) break;
      own.wait(kPollInterval);
    }
    render_thread.join();
    progress_.finish();
    save();
    return gathered(resumed, start, own);
  }

 private:
  // The tiles rank 0's threads finished, copied into the image when they
  // are a tile's first result.
  void place_own_tiles(RankRenderer& own, const Film& own_film) {
    for (const LocalTile& done : own.take_finished()) {
      std::lock_guard lock(schedule_mutex_);
      if (schedule_.complete(done.tile, 0)) {
        CheckpointTile tile{done.tile, {}};
        renderer_.pack_tile(own_film, done.tile, tile.bytes);
        renderer_.unpack_tile(film_, done.tile, tile.bytes);
        ++placed_[0];
        tile_ms_[done.tile] = done.ms;
        unsaved_.push_back(std::move(tile));
      } else {
        ++repeated_[0];
      }
    }
  }

  // Keeps every worker fed (at the end, a tile still out elsewhere again),
  // and once every tile is done tells them, and rank 0's threads, to end.
  // Returns the tiles done.
  std::size_t hand_out_work(bool& told_to_end, std::atomic<bool>& all_done) {
    std::lock_guard lock(schedule_mutex_);
    const std::size_t done_count = schedule_.done_count();
    for (int r = 1; r < ranks_ && !told_to_end; ++r) {
      refill(r);
      if (schedule_.waiting() == 0 && schedule_.outstanding(r) == 0) {
        if (const std::optional<std::uint32_t> again = schedule_.reissue(r)) send_work({*again}, r);
      }
    }
    if (schedule_.all_done() && !told_to_end) {
      all_done = true;  // rank 0's threads start no other tile
      for (int r = 1; r < ranks_; ++r) send_work({}, r);
      told_to_end = true;
    }
    return done_count;
  }

  // The job's summary and the first results' tile times.
  Gathered gathered(std::size_t resumed, Clock::time_point start, RankRenderer& own) {
    Gathered out;
    MpiJobSummary& s = out.summary;
    s.tiles = schedule_.tile_count();
    s.tiles_resumed = resumed;
    s.render_ms = ms_since(start);
    s.checkpoint_ms = checkpoint_ms_;
    s.checkpoints = checkpoints_;
    reports_[0] = own_report(renderer_, own, placed_[0], repeated_[0]);
    for (int r = 1; r < ranks_; ++r) {
      reports_[std::size_t(r)].tiles = placed_[std::size_t(r)];
      reports_[std::size_t(r)].tiles_repeated = repeated_[std::size_t(r)];
    }
    s.ranks = std::move(reports_);
    out.tile_ms = std::move(tile_ms_);
    return out;
  }

  // Keeps up to 3 batches plus 2 tiles per thread out on worker r, sending
  // whole batches only (schedule_mutex_ held).
  void refill(int r) {
    const std::size_t target = 3 * schedule_.batch_size() + 2 * std::size_t(renderer_.threads());
    while (schedule_.waiting() > 0 && schedule_.outstanding(r) + schedule_.batch_size() <= target) {
      send_work(schedule_.take(r, target - schedule_.outstanding(r)), r);
    }
  }

  void receive(int& reported) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    while (flag) {
      std::vector<std::byte> bytes = receive_bytes(status);
      const int from = status.MPI_SOURCE;
      if (status.MPI_TAG == kTagTile) {
        std::uint32_t tile = 0;
        double ms = 0.0;
        if (bytes.size() < kTileHeader) throw std::runtime_error("rank " + std::to_string(from) + " sent a short tile");
        std::memcpy(&tile, bytes.data(), sizeof tile);
        std::memcpy(&ms, bytes.data() + sizeof tile, sizeof ms);
        std::lock_guard lock(schedule_mutex_);
        if (schedule_.complete(tile, from)) {
          const std::span<const std::byte> payload(bytes.data() + kTileHeader, bytes.size() - kTileHeader);
          renderer_.unpack_tile(film_, tile, payload);
          ++placed_[std::size_t(from)];
          tile_ms_[tile] = ms;
          unsaved_.push_back({tile, std::vector<std::byte>(payload.begin(), payload.end())});
        } else {
          ++repeated_[std::size_t(from)];
        }
      } else if (status.MPI_TAG == kTagReport) {
        reports_[std::size_t(from)] = decode_rank_report(bytes);
        ++reported;
      }
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    }
  }

  // Appends the tiles placed since the last checkpoint as one batch.
  void save() {
    const Clock::time_point start = Clock::now();
    if (!unsaved_.empty()) {
      checkpoint_.append(unsaved_);
      unsaved_.clear();
      ++checkpoints_;
    }
    checkpoint_ms_ += ms_since(start);
    last_checkpoint_ = Clock::now();
  }

  // SIGINT or SIGTERM (mpirun sends SIGTERM when another rank died): keep
  // what is done, say so, and end this process; mpirun ends the others.
  [[noreturn]] void interrupted(std::size_t done_count) {
    int code = interrupted_exit_code(interrupting_signal());
    std::string message;
    try {
      save();
      message = "interrupted by " + signal_name(interrupting_signal()) + " during the render after " +
                std::to_string(done_count) + " of " + std::to_string(schedule_.tile_count()) +
                " tiles; no image written; the checkpoint " + checkpoint_.path().string() +
                " keeps them: run again with --resume";
    } catch (const std::exception& error) {
      message = std::string("interrupted, and the checkpoint could not be saved: ") + error.what();
      code = kExitFailure;
    }
    progress_.finish();
    std::fprintf(stderr, "quiver-mpi: %s\n", message.c_str());
    std::fflush(stderr);
    std::_Exit(code);
  }

  FrameRenderer& renderer_;
  Film& film_;
  TileSchedule& schedule_;
  std::mutex schedule_mutex_;  // the schedule, between this thread and rank 0's render threads
  CheckpointWriter& checkpoint_;
  Clock::duration interval_;
  Clock::time_point last_checkpoint_;
  ProgressBar& progress_;
  int ranks_;
  std::vector<std::uint64_t> placed_, repeated_;
  std::vector<RankReport> reports_;
  std::vector<double> tile_ms_;
  std::vector<CheckpointTile> unsaved_;
  double checkpoint_ms_ = 0.0;
  std::size_t checkpoints_ = 0;
};

std::string describe() { return describe_current_exception().second; }

// MPI_Wait without spinning on a core: tests the request, sleeping between tests.
void wait_quietly(MPI_Request& request) {
  int done = 0;
  MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  while (!done) {
    std::this_thread::sleep_for(kPollInterval);
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  }
}

// A failure once the render is under way: the other ranks wait on this
// one, so the job ends here.
[[noreturn]] void abort_job(const std::string& message) {
  const int rank = world_rank();
  std::fprintf(stderr, "quiver-mpi: %s%s\n", rank == 0 ? "" : ("rank " + std::to_string(rank) + ": ").c_str(),
               message.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, kExitFailure);
  std::_Exit(kExitFailure);
}

}  // namespace

int agree_on(int exit_code, const std::string& message) {
  const int rank = world_rank(), ranks = world_size();
  int worst = 0;
  // Quietly: the other ranks may wait here while rank 0 reads and builds the scene.
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(&exit_code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD, &request);
  wait_quietly(request);
  if (worst == 0) return 0;
  const int mine = exit_code != 0 ? rank : ranks;
  int first = ranks;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (rank == 0) {
    std::string text = message;
    if (first != 0) {
      MPI_Status status;
      MPI_Probe(first, kTagError, MPI_COMM_WORLD, &status);
      const std::vector<std::byte> bytes = receive_bytes(status);
      text = "rank " + std::to_string(first) + ": " +
             std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    }
    std::fprintf(stderr, "quiver-mpi: %s\n", text.c_str());
    std::fflush(stderr);
    end_quietly_on_signal(worst);
  } else if (rank == first) {
    MPI_Send(message.data(), int(message.size()), MPI_BYTE, 0, kTagError, MPI_COMM_WORLD);
  }
  return worst;
}

namespace {

// Runs step on this rank, then every rank agrees on the outcome
// (agree_on): 0 when every rank succeeded, else the worst exit code, its
// message printed once. An exception is described as the programs do
// (describe_current_exception); as_usage_error: any exception is a usage
// error.
template <class Step>
int on_every_rank(Step&& step, bool as_usage_error = false) {
  int code = 0;
  std::string message;
  try {
    step();
  } catch (const std::exception& error) {
    std::tie(code, message) = as_usage_error ? std::pair<int, std::string>{kExitUsage, error.what()}
                                             : describe_current_exception();
  } catch (...) {
    std::tie(code, message) = describe_current_exception();
  }
  return agree_on(code, message);
}

// What the ranks set up before rendering: the checked flags, the scene, the
// frame renderer and the fingerprint of what was read; on rank 0 also the
// film, the checkpoint and the tiles it already holds.
struct MpiSetup {
  CheckedRenderArgs checked;
  fs::path checkpoint_path;
  std::optional<PreparedRender> prepared;
  std::optional<FrameRenderer> renderer;
  std::uint64_t fingerprint = 0;
  std::optional<CheckpointWriter> checkpoint;
  std::optional<Film> film;
  std::vector<bool> done;
  std::size_t resumed = 0;
};

// The flags: rank 0 also checks the files it will write.
void check_mpi_flags(const MpiRenderArgs& args, int rank, MpiSetup& setup) {
  const RenderArgs& render_args = args.render;
  if (!(args.checkpoint_interval_s > 0.0 && args.checkpoint_interval_s <= kMaxCheckpointInterval)) {
    throw UsageError("--checkpoint-interval: expected seconds in (0, " + std::to_string(int(kMaxCheckpointInterval)) +
                     "]");
  }
  const fs::path output = render_args.output.empty() ? default_output(render_args.scene) : fs::path(render_args.output);
  setup.checkpoint_path = args.checkpoint.empty() ? fs::path(output.string() + ".checkpoint") : fs::path(args.checkpoint);
  if (rank == 0) {
    setup.checked = check_render_args(render_args, std::getenv("QUIVER_SIMD"), {{"--checkpoint", setup.checkpoint_path}});
    check_output_directory(setup.checkpoint_path);
  } else {
    check_render_options(render_args.options);
    setup.checked.isa = choose_isa(render_args.options.simd, std::getenv("QUIVER_SIMD"));
    setup.checked.output = output;
  }
}

// Rank 0: the film and the checkpoint, new or resumed (its tiles unpacked
// into the film and marked done).
void open_checkpoint(const MpiRenderArgs& args, MpiSetup& setup) {
  const RenderSettings& settings = setup.prepared->plan.settings;
  const std::size_t tile_count = setup.renderer->tiles().size();
  const CheckpointKey key{setup.fingerprint, std::uint32_t(settings.width), std::uint32_t(settings.height),
                          std::uint32_t(settings.tile_size), std::uint32_t(tile_count)};
  setup.film.emplace(setup.renderer->make_film());
  if (!args.resume) {
    setup.checkpoint.emplace(CheckpointWriter::create(setup.checkpoint_path, key));
    return;
  }
  const CheckpointContents contents = read_checkpoint(setup.checkpoint_path, key);
  for (const CheckpointTile& tile : contents.tiles) {
    setup.renderer->unpack_tile(*setup.film, tile.tile, tile.bytes);
    if (!setup.done[tile.tile]) ++setup.resumed;
    setup.done[tile.tile] = true;
  }
  setup.checkpoint.emplace(CheckpointWriter::resume(setup.checkpoint_path, contents));
}

// The cost estimate: each rank its share of the tiles, summed on rank 0.
std::vector<double> estimate_tile_costs(const FrameRenderer& renderer, int rank, int ranks) {
  const std::size_t tile_count = renderer.tiles().size();
  std::vector<double> costs(tile_count, 0.0);
  std::vector<std::size_t> mine;
  for (std::size_t t = std::size_t(rank); t < tile_count; t += std::size_t(ranks)) mine.push_back(t);
  const std::vector<double> estimated = renderer.estimate_costs(mine, kTileCostStride);
  for (std::size_t k = 0; k < mine.size(); ++k) costs[mine[k]] = estimated[k];
  MPI_Reduce(rank == 0 ? MPI_IN_PLACE : costs.data(), costs.data(), int(tile_count), MPI_DOUBLE, MPI_SUM, 0,
             MPI_COMM_WORLD);
  return costs;
}

// Rank 0, every tile gathered: the image and the stats staged and
// committed, the checkpoint removed; interrupted instead, nothing written
// and the checkpoint kept (the exit code and message of that).
std::pair<int, std::string> write_outputs(const MpiRenderArgs& args, MpiSetup& setup, Gathered& gathered, int ranks) {
  const RenderArgs& render_args = args.render;
  const RenderSettings& settings = setup.prepared->plan.settings;
  setup.renderer->finish(*setup.film);
  RenderResult result;
  result.image = std::move(setup.film->image);
  result.stats = merged_trace_stats(gathered.summary.ranks);
  result.render_ms = gathered.summary.render_ms;
  result.threads = 0;
  for (const RankReport& r : gathered.summary.ranks) result.threads += r.threads;
  result.sphere_method = setup.renderer->sphere_method();
  result.tiles_total = result.tiles_done = setup.renderer->tiles().size();

  StagedOutputs staged;
  stage_image(staged, setup.checked.output, result.image);
  if (!render_args.stats.empty()) {
    nlohmann::json stats = render_stats(render_args, setup.checked, *setup.prepared, result);
    stats["mpi"] = mpi_stats_json(gathered.summary);
    if (args.tile_times) {
      nlohmann::json times = nlohmann::json::array();
      for (const double ms : gathered.tile_ms) times.push_back(std::isnan(ms) ? nlohmann::json(nullptr) : nlohmann::json(ms));
      stats["tile_ms"] = std::move(times);
      stats["tile_cost_estimate"] = gathered.costs;
      stats["tile_size"] = settings.tile_size;
    }
    stage_json_file(staged, render_args.stats, stats);
  }
  if (stop_requested()) {
    return {interrupted_exit_code(interrupting_signal()),
            "interrupted by " + signal_name(interrupting_signal()) +
                " while writing the outputs; nothing written; the checkpoint " + setup.checkpoint_path.string() +
                " holds every tile: run again with --resume"};
  }
  staged.commit();
  setup.checkpoint->remove();
  if (!render_args.quiet) {
    print_render_summary(stderr, result, settings, setup.prepared->load_ms, setup.prepared->build_ms,
                         setup.checked.output,
                         std::to_string(ranks) + " ranks, " + std::to_string(result.threads) + " threads");
  }
  return {0, ""};
}

}  // namespace

int run_mpi_render(const MpiRenderArgs& args) {
  const Clock::time_point start = Clock::now();
  const int rank = world_rank(), ranks = world_size();
  const RenderArgs& render_args = args.render;
  MpiSetup setup;
  if (int code = on_every_rank([&] { check_mpi_flags(args, rank, setup); }, true)) return code;
  if (rank == 0) install_interrupt_handlers();
  // Rank 0 alone reads and builds the scene (and fingerprints what it read, for its checkpoint).
  const auto prepare = [&] {
    if (rank != 0) return;
    const ProgressStyle status = progress_style_for(stderr, render_args.quiet);
    setup.prepared.emplace(prepare_render(render_args, setup.checked, status));
    print_scene_warnings(setup.prepared->desc);
    setup.fingerprint =
        render_fingerprint(setup.prepared->plan.settings, setup.prepared->plan.build, render_args.options.crease_angle,
                           *setup.prepared->desc.camera, setup.prepared->inputs, QUIVER_VERSION);
  };
  if (int code = on_every_rank(prepare)) return code;
  try {
    if (rank != 0) setup.prepared.emplace();
    broadcast_prepared_render(*setup.prepared, rank, setup.checked.isa);
  } catch (...) {
    abort_job(describe());
  }
  const RenderSettings& settings = setup.prepared->plan.settings;
  if (int code = on_every_rank([&] { setup.renderer.emplace(setup.prepared->scene, settings); })) return code;
  setup.done.assign(setup.renderer->tiles().size(), false);
  if (int code = on_every_rank([&] { if (rank == 0) open_checkpoint(args, setup); })) return code;

  const Clock::time_point estimate_start = Clock::now();
  const std::vector<double> costs = estimate_tile_costs(*setup.renderer, rank, ranks);
  const double estimate_ms = ms_since(estimate_start);
  const double start_ms = ms_since(start);
  if (rank != 0) {
    try {
      run_worker(*setup.renderer, start_ms);
    } catch (...) {
      abort_job(describe());
    }
    return agree_on(0, "");
  }

  set_interrupt_phase(InterruptPhase::rendering);
  Gathered gathered;
  try {
    TileSchedule schedule(setup.renderer->tiles().size(), setup.done, costs, ranks);
    ProgressBar progress(stderr, progress_style_for(stderr, render_args.quiet));
    Coordinator coordinator(*setup.renderer, *setup.film, schedule, *setup.checkpoint, args.checkpoint_interval_s,
                            progress, ranks);
    gathered = coordinator.run(setup.resumed);
  } catch (...) {
    abort_job(describe());
  }
  gathered.summary.estimate_ms = estimate_ms;
  gathered.summary.ranks[0].start_ms = start_ms;
  gathered.costs = costs;
  int code = 0;
  std::string message;
  try {
    std::tie(code, message) = write_outputs(args, setup, gathered, ranks);
  } catch (...) {
    std::tie(code, message) = describe_current_exception();
  }
  return agree_on(code, message);
}

}  // namespace quiver
