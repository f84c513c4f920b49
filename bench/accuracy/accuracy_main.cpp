// quiver_accuracy: the measurements behind bench/ACCURACY.md, written as CSV
// (and a JSON summary) into bench/accuracy/results/ (or --out DIR):
//   kernel_errors.csv   every method x width (kernel unit) and the double
//                       evaluation x stress case: ULPs of t, false misses/hits;
//   failure_points.csv  per method, precision and sweep, where it breaks;
//   speed.csv           tests per second per method x width (and double);
//   watertight.csv      rays leaked through closed meshes per triangle method;
//   self_intersection.csv acne fraction per scene scale and offset rule;
//   anti_aliasing.csv   RMSE against a high-sample reference and render time;
//   aa_oracle.csv       the fewest rays an adaptive sampler could spend for
//                       grid:4's RMSE (aa_oracle_study.cpp);
//   summary.json        the run's settings (units, rays per case, thresholds).
// Usage: quiver_accuracy [--out DIR] [--quick] [--only SECTION] [--aa-modes MODE,MODE,...]
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "bench/accuracy/studies.h"

int main(int argc, char** argv) {
  using namespace quiver::accuracy;
  StudyOptions options;
  options.out = std::filesystem::path(QUIVER_SOURCE_DIR) / "bench" / "accuracy" / "results";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) {
      options.out = argv[++i];
    } else if (arg == "--quick") {
      options.quick = true;
    } else if (arg == "--only" && i + 1 < argc) {
      options.only = argv[++i];
    } else if (arg == "--aa-modes" && i + 1 < argc) {
      const std::string list = argv[++i];
      for (std::size_t start = 0; start <= list.size();) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        if (comma > start) options.aa_modes.push_back(list.substr(start, comma - start));
        start = comma + 1;
      }
    } else {
      std::fprintf(stderr,
                   "usage: quiver_accuracy [--out DIR] [--quick] [--only kernels|speed|watertight|acne|aa|aa_oracle]"
                   " [--aa-modes MODE,MODE,...]\n");
      return 2;
    }
  }
  try {
    std::filesystem::create_directories(options.out);
    run_studies(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "quiver_accuracy: %s\n", e.what());
    return 1;
  }
  return 0;
}
