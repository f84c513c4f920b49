// The studies quiver_accuracy runs, each writing one CSV (see accuracy_main.cpp).
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace quiver::accuracy {

struct StudyOptions {
  std::filesystem::path out;
  bool quick = false;  // fewer rays and shorter timing loops (a smoke run)
  std::string only;    // one study by name, or all when empty
  std::vector<std::string> aa_modes;  // the anti-aliasing study's modes; empty: its own list
};

// Rays per stress case (kernel errors) and per scale (self-intersection).
inline std::size_t rays_per_case(const StudyOptions& options) { return options.quick ? 2000 : 20000; }

void run_studies(const StudyOptions& options);

// Opens path for writing and writes the header line; throws std::runtime_error if it cannot.
std::FILE* open_csv(const std::filesystem::path& path, const char* header);

void kernel_error_study(const StudyOptions& options);   // kernel_errors.csv, failure_points.csv
void speed_study(const StudyOptions& options);          // speed.csv
void watertight_study(const StudyOptions& options);     // watertight.csv
void acne_study(const StudyOptions& options);           // self_intersection.csv
void anti_aliasing_study(const StudyOptions& options);  // anti_aliasing.csv
void aa_oracle_study(const StudyOptions& options);      // aa_oracle.csv

}  // namespace quiver::accuracy
