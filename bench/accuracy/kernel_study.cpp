// The kernel error and speed studies: every method x kernel unit (width 1,
// 4, 8) and the double-lane evaluation, over every stress sweep, against the
// oracle; then tests per second of each on a 64-primitive case. Also
// run_studies and the CSV helper every study uses.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>

#include "bench/accuracy/measure.h"
#include "bench/accuracy/studies.h"

namespace quiver::accuracy {
namespace {

constexpr Distribution kDistributions[] = {Distribution::distance, Distribution::size, Distribution::far,
                                           Distribution::grazing};

bool same_results(const HitSoA& a, const HitSoA& b) {
  for (std::size_t i = 0; i < a.count; ++i) {
    const Hit<float> x = a.get(i), y = b.get(i);
    if (x.id != y.id || std::memcmp(&x.t, &y.t, sizeof(float)) != 0) return false;
  }
  return true;
}

void write_stats(std::FILE* f, const ErrorStats& s) {
  std::fprintf(f, "%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", s.rays, s.counted,
               s.counted_hits, s.counted_misses, s.false_miss, s.false_hit, s.false_miss_all, s.false_hit_all,
               s.both_hit, s.nonfinite, s.ulp_max, s.ulp_median, s.ulp_p99, s.relative_max, s.relative_p99, s.wrong_band);
}

std::string parameter_text(double p) {
  if (std::isnan(p)) return "never";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", p);
  return text;
}

}  // namespace

void kernel_error_study(const StudyOptions& options) {
  const std::size_t rays = rays_per_case(options);
  const std::vector<KernelUnit> units = units_by_width();
  std::FILE* errors = open_csv(options.out / "kernel_errors.csv",
                               "kind,method,default,unit,width,precision,distribution,parameter,built,rays,counted,"
                               "counted_hits,counted_misses,false_miss,false_hit,false_miss_all,false_hit_all,both_hit,"
                               "nonfinite,ulp_max,ulp_median,ulp_p99,relative_max,relative_p99,wrong_band,same_bits_as_width1");
  std::FILE* failures = open_csv(options.out / "failure_points.csv",
                                 "kind,method,default,precision,distribution,first_relative_error_over_1e-3,"
                                 "first_false_miss,first_false_hit,last_built,wrong_band,worst_relative,worst_ulp_p99,"
                                 "worst_false_miss_rate,worst_false_hit_rate");
  for (const Method& method : kMethods) {
    for (const Distribution distribution : kDistributions) {
      std::map<std::string, std::vector<SweepRow>> rows;  // by precision: float (width 1), double
      for (const double parameter : sweep_parameters(distribution)) {
        const Case c = make_case(method.kind, distribution, parameter, rays, 1);
        const bool built = c.prims.size() > 0;
        const bool every_ray = distribution == Distribution::grazing;
        const std::vector<Reference> refs = built ? run_oracle(c.rays, c.prims) : std::vector<Reference>{};
        auto row_start = [&](const char* unit, int width, const char* precision) {
          std::fprintf(errors, "%s,%s,%d,%s,%d,%s,%s,%.9g,%d,", method.kind_name.data(), method.name.data(),
                       method.renderer_default ? 1 : 0, unit, width, precision,
                       distribution_name(distribution).data(), parameter, built ? 1 : 0);
        };
        HitSoA width1;
        for (std::size_t u = 0; u < units.size(); ++u) {
          SweepRow row{parameter, built, {}};
          bool same = true;
          if (built) {
            const HitSoA hits = run_unit(method, units[u], c.rays, c.prims);
            if (u == 0) width1 = hits;
            same = same_results(width1, hits);
            row.stats = compare(refs, hits_of(hits), every_ray);
          }
          row_start(kernel_unit_name(units[u]).data(), lane_width(units[u]), "float");
          write_stats(errors, row.stats);
          std::fprintf(errors, ",%d\n", same ? 1 : 0);
          if (u == 0) rows["float"].push_back(row);
        }
        SweepRow row{parameter, built, {}};
        if (built) row.stats = compare(refs, run_double(method, c.rays, c.prims), every_ray);
        row_start("double_lanes", 1, "double");
        write_stats(errors, row.stats);
        std::fprintf(errors, ",1\n");
        rows["double"].push_back(row);
      }
      for (const auto& [precision, sweep] : rows) {
        const FailurePoint f = find_failure_point(sweep);
        std::fprintf(failures, "%s,%s,%d,%s,%s,%s,%s,%s,%s,%.9g,%.9g,%.9g,%.9g,%.9g\n", method.kind_name.data(),
                     method.name.data(), method.renderer_default ? 1 : 0, precision.c_str(),
                     distribution_name(distribution).data(), parameter_text(f.first_relative_error).c_str(),
                     parameter_text(f.first_false_miss).c_str(), parameter_text(f.first_false_hit).c_str(),
                     parameter_text(f.last_built).c_str(), f.wrong_band, f.worst_relative, f.worst_ulp_p99,
                     f.worst_false_miss_rate, f.worst_false_hit_rate);
        if (precision == "float") {
          std::printf("%-8s %-15s %-8s rel>1e-3 at %-8s false miss at %-8s false hit at %-8s band %.2g worst p99 %.3g ulp\n",
                      method.kind_name.data(), method.name.data(), distribution_name(distribution).data(),
                      parameter_text(f.first_relative_error).c_str(), parameter_text(f.first_false_miss).c_str(),
                      parameter_text(f.first_false_hit).c_str(), f.wrong_band, f.worst_ulp_p99);
        }
      }
      std::fflush(errors);
    }
  }
  std::fclose(errors);
  std::fclose(failures);
}

void speed_study(const StudyOptions& options) {
  // Interleaved rounds (every method x unit once per round), best per
  // configuration: a burst of load from other processes hits one round, not
  // one configuration.
  const double seconds = options.quick ? 0.01 : 0.05;
  const int rounds = options.quick ? 1 : 7;
  const std::vector<KernelUnit> units = units_by_width();
  std::vector<Case> cases;
  for (const Method& method : kMethods) cases.push_back(make_timing_case(method.kind, 7));
  // best[method][unit index], the last index being the double evaluation.
  std::vector<std::vector<double>> best(kMethods.size(), std::vector<double>(units.size() + 1, 0.0));
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t m = 0; m < kMethods.size(); ++m) {
      for (std::size_t u = 0; u < units.size(); ++u) {
        best[m][u] = std::max(best[m][u], tests_per_second(kMethods[m], units[u], cases[m], seconds, 1));
      }
      best[m][units.size()] =
          std::max(best[m][units.size()], double_tests_per_second(kMethods[m], cases[m], seconds, 1));
    }
  }
  std::FILE* f = open_csv(options.out / "speed.csv", "kind,method,default,unit,width,precision,rays,primitives,tests_per_second");
  for (std::size_t m = 0; m < kMethods.size(); ++m) {
    const Method& method = kMethods[m];
    for (std::size_t u = 0; u <= units.size(); ++u) {
      const bool in_double = u == units.size();
      const char* unit_name = in_double ? "double_lanes" : kernel_unit_name(units[u]).data();
      const int width = in_double ? 1 : lane_width(units[u]);
      std::fprintf(f, "%s,%s,%d,%s,%d,%s,%zu,%zu,%.6g\n", method.kind_name.data(), method.name.data(),
                   method.renderer_default ? 1 : 0, unit_name, width, in_double ? "double" : "float",
                   cases[m].rays.count, cases[m].prims.size(), best[m][u]);
      std::printf("%-8s %-15s w%d %-6s %8.1f M tests/s\n", method.kind_name.data(), method.name.data(), width,
                  in_double ? "double" : "float", best[m][u] * 1e-6);
    }
  }
  std::fclose(f);
}

std::FILE* open_csv(const std::filesystem::path& path, const char* header) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path.string());
  std::fprintf(f, "%s\n", header);
  return f;
}

void run_studies(const StudyOptions& options) {
  auto wanted = [&](const char* name) { return options.only.empty() || options.only == name; };
  // The run's settings, for readers of the CSV files.
  std::FILE* summary = std::fopen((options.out / "summary.json").c_str(), "w");
  if (!summary) throw std::runtime_error("cannot write " + (options.out / "summary.json").string());
  std::fprintf(summary, "{\n  \"quick\": %s,\n  \"only\": \"%s\",\n  \"kernel_units\": [", options.quick ? "true" : "false",
               options.only.c_str());
  const std::vector<KernelUnit> units = units_by_width();
  for (std::size_t u = 0; u < units.size(); ++u) {
    std::fprintf(summary, "%s\"%s\"", u ? ", " : "", kernel_unit_name(units[u]).data());
  }
  std::fprintf(summary,
               "],\n  \"rays_per_case\": %zu,\n  \"clear_ray_clearance\": %g,\n  \"relative_error_limit\": %g,\n"
               "  \"fixed_epsilon\": %g\n}\n",
               rays_per_case(options), kClearRay, kRelativeLimit, double(kFixedEpsilon));
  std::fclose(summary);
  if (wanted("kernels")) kernel_error_study(options);
  if (wanted("speed")) speed_study(options);
  if (wanted("watertight")) watertight_study(options);
  if (wanted("acne")) acne_study(options);
  if (wanted("aa")) anti_aliasing_study(options);
  if (wanted("aa_oracle")) aa_oracle_study(options);
}

}  // namespace quiver::accuracy
