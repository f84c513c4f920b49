// Error statistics and timing loops of bench/accuracy/measure.h.
#include "bench/accuracy/measure.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace quiver::accuracy {
namespace {

// The q-quantile (0..1) of values, nearest rank; 0 for none.
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const std::size_t rank = std::min(values.size() - 1, std::size_t(q * double(values.size() - 1) + 0.5));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(rank), values.end());
  return values[rank];
}

// Best tests per second of `pass` (which performs `tests` tests) over repeats.
template <class Pass>
double best_rate(Pass&& pass, double tests, double seconds, int repeats) {
  using Clock = std::chrono::steady_clock;
  double best = 0.0;
  pass();  // warm caches
  for (int r = 0; r < repeats; ++r) {
    std::size_t passes = 0;
    const auto start = Clock::now();
    double elapsed = 0.0;
    do {
      pass();
      ++passes;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < seconds);
    best = std::max(best, tests * double(passes) / elapsed);
  }
  return best;
}

}  // namespace

std::vector<DoubleHit> hits_of(const HitSoA& hits) {
  std::vector<DoubleHit> out(hits.count);
  for (std::size_t i = 0; i < hits.count; ++i) {
    const Hit<float> h = hits.get(i);
    out[i] = {h.id != kNoHit, double(h.t), h.id};
  }
  return out;
}

ErrorStats compare(const std::vector<Reference>& references, const std::vector<DoubleHit>& results,
                   bool count_every_ray) {
  ErrorStats s;
  s.rays = references.size();
  std::vector<double> ulps, relatives;
  for (std::size_t i = 0; i < references.size(); ++i) {
    const Reference& ref = references[i];
    const DoubleHit& got = results[i];
    if (ref.hit && !got.hit) ++s.false_miss_all;
    if (!ref.hit && got.hit) ++s.false_hit_all;
    if (ref.hit != got.hit) s.wrong_band = std::max(s.wrong_band, ref.clearance);
    if (!count_every_ray && ref.clearance < kClearRay) continue;
    ++s.counted;
    ++(ref.hit ? s.counted_hits : s.counted_misses);
    if (ref.hit && !got.hit) ++s.false_miss;
    if (!ref.hit && got.hit) ++s.false_hit;
    if (ref.hit && got.hit) {
      ++s.both_hit;
      if (!std::isfinite(got.t)) {
        ++s.nonfinite;
        continue;
      }
      ulps.push_back(ulp_error(got.t, ref.t));
      relatives.push_back(std::fabs(got.t - ref.t) / std::fabs(ref.t));
    }
  }
  if (!ulps.empty()) {
    s.ulp_max = *std::max_element(ulps.begin(), ulps.end());
    s.relative_max = *std::max_element(relatives.begin(), relatives.end());
    s.ulp_median = quantile(ulps, 0.5);
    s.ulp_p99 = quantile(ulps, 0.99);
    s.relative_p99 = quantile(relatives, 0.99);
  }
  return s;
}

std::vector<SweepRow> run_sweep(const Method& method, Distribution distribution, std::optional<KernelUnit> unit,
                                std::size_t ray_count, std::uint32_t seed) {
  std::vector<SweepRow> rows;
  for (const double parameter : sweep_parameters(distribution)) {
    const Case c = make_case(method.kind, distribution, parameter, ray_count, seed);
    SweepRow row{parameter, c.prims.size() > 0, {}};
    if (row.built) {
      const std::vector<DoubleHit> results =
          unit ? hits_of(run_unit(method, *unit, c.rays, c.prims)) : run_double(method, c.rays, c.prims);
      row.stats = compare(run_oracle(c.rays, c.prims), results, distribution == Distribution::grazing);
    }
    rows.push_back(row);
  }
  return rows;
}

FailurePoint find_failure_point(const std::vector<SweepRow>& rows) {
  FailurePoint f;
  for (const SweepRow& row : rows) {
    if (!row.built) continue;
    const ErrorStats& s = row.stats;
    f.last_built = row.parameter;
    if (std::isnan(f.first_relative_error) && s.relative_max > kRelativeLimit) f.first_relative_error = row.parameter;
    if (std::isnan(f.first_false_miss) && s.false_miss > 0) f.first_false_miss = row.parameter;
    if (std::isnan(f.first_false_hit) && s.false_hit > 0) f.first_false_hit = row.parameter;
    f.wrong_band = std::max(f.wrong_band, s.wrong_band);
    f.worst_relative = std::max(f.worst_relative, s.relative_max);
    f.worst_ulp_p99 = std::max(f.worst_ulp_p99, s.ulp_p99);
    f.worst_false_miss_rate = std::max(f.worst_false_miss_rate, s.false_miss_rate());
    f.worst_false_hit_rate = std::max(f.worst_false_hit_rate, s.false_hit_rate());
  }
  return f;
}

double tests_per_second(const Method& method, KernelUnit unit, const Case& c, double seconds, int repeats) {
  HitSoA hits(c.rays);
  const double tests = double(c.rays.count) * double(c.prims.size());
  return best_rate([&] { hits = run_unit(method, unit, c.rays, c.prims); }, tests, seconds, repeats);
}

double double_tests_per_second(const Method& method, const Case& c, double seconds, int repeats) {
  std::vector<DoubleHit> hits;
  const double tests = double(c.rays.count) * double(c.prims.size());
  return best_rate([&] { hits = run_double(method, c.rays, c.prims); }, tests, seconds, repeats);
}

}  // namespace quiver::accuracy
