// Counters a render reports. Ray kinds follow the SPD procedure: primary
// (eye) rays and how many hit, shadow rays actually cast (none toward a
// light the surface faces away from), reflection rays (also the one cast at
// total internal reflection) and refraction rays.
// Lane utilisation per wave: active lanes / lanes issued. "Compacted" is
// what quiver issues (every wave packed into full packets: ceil(n / W) * W
// lanes); "uncompacted" is what a per-packet masked recursion would issue:
// W lanes for every parent packet and child ray kind with any active lane.
// Shading lanes: the same ratio for the packets that shade the waves'
// hits and for their light sample iterations.
// Phase times are thread time in nanoseconds, summed over threads.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

namespace quiver {

struct RayCounts {
  std::uint64_t primary = 0, primary_hits = 0, shadow = 0, reflection = 0, refraction = 0;
  std::uint64_t total() const { return primary + shadow + reflection + refraction; }
};

struct WaveLanes {
  std::uint64_t active = 0, issued_compacted = 0, issued_uncompacted = 0;
};

// Where a frame's time goes. camera_and_film: a tile's work outside the
// tracer (camera samples, anti-aliasing decisions, AOV first hits,
// writing pixels);
// intersection: closest hits of the eye and secondary waves; shading:
// surface points, materials, textures, lights and the rays they spawn;
// shadows: the shadow waves (any-hit, transparent shadows, adding the light).
// shadow_walks, a part of shadows: the any-hit and transparent-shadow walks
// themselves, so intersection + shadow_walks is the time the BVH walks and
// kernels take, the part of a frame no bookkeeping can save. Timed only
// when TraceSettings::time_phases asks (else all 0).
struct PhaseTimes {
  std::uint64_t camera_and_film = 0, intersection = 0, shading = 0, shadows = 0;
  std::uint64_t shadow_walks = 0;
  std::uint64_t total() const { return camera_and_film + intersection + shading + shadows; }
  std::uint64_t walks() const { return intersection + shadow_walks; }
};

// Adds the time since the last call (or construction) to a phase's
// counter; a clock that is off reads no time and charges nothing.
class PhaseClock {
 public:
  explicit PhaseClock(bool on) : on_(on) {
    if (on_) last_ = std::chrono::steady_clock::now();
  }
  void charge(std::uint64_t& phase) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    phase += static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(now - last_).count());
    last_ = now;
  }

 private:
  bool on_;
  std::chrono::steady_clock::time_point last_;
};

// Runs `work` and, when timing, adds the time it took to `phase`.
template <class Work>
void charge_time_of(std::uint64_t& phase, bool timing, Work&& work) {
  PhaseClock clock(timing);
  work();
  clock.charge(phase);
}

struct TraceStats {
  RayCounts rays;
  PhaseTimes phases;
  std::vector<WaveLanes> waves;  // index = bounce depth (0: primary)
  WaveLanes shadow;              // all shadow waves together
  // Lanes of the shading packets with a hit. The shading packets are the
  // waves' packets, so they issue what the waves issue.
  std::uint64_t shading_active = 0;
  // Light sample iterations (packet x sample, packets with a lit lane):
  // active = lanes casting a shadow ray; no uncompacted form.
  std::uint64_t light_sample_active = 0, light_sample_issued = 0;

  void add(const TraceStats& other);
  WaveLanes& wave(std::size_t depth);
};

}  // namespace quiver
