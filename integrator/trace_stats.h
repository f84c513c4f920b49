// Counters a render reports. Ray kinds follow the SPD procedure: primary
// (eye) rays and how many hit, shadow rays actually cast (none toward a
// light the surface faces away from), reflection rays (also the one cast at
// total internal reflection) and refraction rays.
// Lane utilisation per wave: active lanes / lanes issued. "Compacted" is
// what quiver issues (every wave packed into full packets: ceil(n / W) * W
// lanes); "uncompacted" is what a per-packet masked recursion would issue:
// W lanes for every parent packet and child ray kind with any active lane.
#pragma once

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

struct TraceStats {
  RayCounts rays;
  std::vector<WaveLanes> waves;  // index = bounce depth (0: primary)
  WaveLanes shadow;              // all shadow waves together

  void add(const TraceStats& other);
  WaveLanes& wave(std::size_t depth);
};

}  // namespace quiver
