// Error statistics of one method on one case against the oracle, and
// tests per second of a method at each width.
// Counted rays: those whose oracle clearance is at least kClearRay (1e-3 of
// the primitive's size from the other answer), so a false miss or hit among
// them is a failure, not a coin toss at the silhouette; the grazing sweep
// counts every ray (its rays are all near the silhouette on purpose).
// t errors are over counted rays that both the method and the oracle hit.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "bench/accuracy/closed_meshes.h"
#include "bench/accuracy/methods.h"
#include "bench/accuracy/stress.h"

namespace quiver::accuracy {

inline constexpr double kClearRay = 1e-3;

struct ErrorStats {
  std::size_t rays = 0, counted = 0, counted_hits = 0, counted_misses = 0;
  std::size_t false_miss = 0, false_hit = 0;          // among counted rays
  std::size_t false_miss_all = 0, false_hit_all = 0;  // among all rays
  std::size_t both_hit = 0, nonfinite = 0;            // counted rays; a hit with non-finite t
  double ulp_max = 0.0, ulp_median = 0.0, ulp_p99 = 0.0;  // float ulps of the reference t
  double relative_max = 0.0, relative_p99 = 0.0;          // |t - t_ref| / |t_ref|
  double wrong_band = 0.0;  // largest oracle clearance of a wrongly decided ray (all rays)

  double false_miss_rate() const { return counted_hits ? double(false_miss) / double(counted_hits) : 0.0; }
  double false_hit_rate() const { return counted_misses ? double(false_hit) / double(counted_misses) : 0.0; }
};

std::vector<DoubleHit> hits_of(const HitSoA& hits);

ErrorStats compare(const std::vector<Reference>& references, const std::vector<DoubleHit>& results,
                   bool count_every_ray);

// Where the width-1 float kernel (or, with no unit, the double kernel) of a
// method stands at each parameter of a sweep.
struct SweepRow {
  double parameter = 0.0;
  bool built = false;  // false: the primitive cannot be stored there (no rays run)
  ErrorStats stats;
};
std::vector<SweepRow> run_sweep(const Method& method, Distribution distribution, std::optional<KernelUnit> unit,
                                std::size_t ray_count, std::uint32_t seed);

// The first parameter (in sweep order, easy to hard) at which a method
// breaks, by three criteria; NaN where it never does within the sweep.
struct FailurePoint {
  double first_relative_error = kNever;  // relative_max > kRelativeLimit
  double first_false_miss = kNever;      // a counted ray that must hit misses
  double first_false_hit = kNever;       // a counted ray that must miss hits
  double last_built = kNever;            // the hardest parameter with a primitive
  double wrong_band = 0.0;  // largest clearance of a wrong decision anywhere in the sweep
  double worst_relative = 0.0, worst_ulp_p99 = 0.0, worst_false_miss_rate = 0.0, worst_false_hit_rate = 0.0;
  static constexpr double kNever = std::numeric_limits<double>::quiet_NaN();
};
inline constexpr double kRelativeLimit = 1e-3;
FailurePoint find_failure_point(const std::vector<SweepRow>& rows);

// Rays from inside a closed mesh (origins from `origins`) aimed exactly at
// shared edges (two thirds) and vertices (one third) through a unit's
// any-hit packets; a ray that hits no face leaked
// (bench/accuracy/robustness.cpp).
struct LeakCount {
  std::size_t edge_rays = 0, vertex_rays = 0, edge_leaks = 0, vertex_leaks = 0;
};
LeakCount count_leaks(const Method& method, KernelUnit unit, const ClosedMesh& mesh, const OriginSampler& origins,
                      std::size_t ray_count, std::uint32_t seed);
// Origins within `inner` of center (a uniform direction and distance).
OriginSampler ball_origins(const Vec3<float>& center, float inner);

// Self-intersection: re-hits of the same primitive by rays spawned from its
// hit points at a scene scale, per offset rule (robustness.cpp).
enum class OffsetRule { zero, epsilon, robust };
inline constexpr float kFixedEpsilon = 1e-4f;
std::string_view offset_rule_name(OffsetRule rule);
struct AcneCount {
  std::size_t spawned = 0, rehits = 0;
  double fraction() const { return spawned ? double(rehits) / double(spawned) : 0.0; }
};
AcneCount count_acne(const Method& method, KernelUnit unit, double scale, OffsetRule rule, std::size_t ray_count,
                     std::uint32_t seed);

// Closest-hit packet tests per second of a method in a unit on a case
// (rays x primitives per pass), best of `repeats` timed loops of at least
// `seconds` each.
double tests_per_second(const Method& method, KernelUnit unit, const Case& c, double seconds, int repeats);
// The same for the kernel template at double precision (one ray at a time).
double double_tests_per_second(const Method& method, const Case& c, double seconds, int repeats);

}  // namespace quiver::accuracy
