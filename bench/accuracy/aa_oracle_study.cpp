// How few rays any adaptive sampler with jittered or regular strata could
// spend to reach grid:4's RMSE (bench/ACCURACY.md, "What any adaptive
// sampler could reach"). Per scene of anti_aliasing_scenes.h (textures
// filtered where the scene has any), each pixel may take jitter:N, or
// grid:N (regular strata, as refine:T:N:grid), for N in a ladder of levels
// (1, 2, 4, 8 rays per side, or refine's 2, 4, 8); an oracle picks
// every pixel's level, greedily by the largest drop of squared error per
// added ray, until the image (the seed-0 renders of the chosen levels)
// errs no more than grid:4 against the reference (jitter:16, seed 12345).
// Two oracles: "told the error" ranks by the seed-0 errors themselves (it
// knows each draw's luck: a bound no sampler can beat), "told the expected
// error" by the mean error of kExpectationSeeds other seeds (what a perfect
// edge and noise detector would know; for regular strata every seed gives
// the same image, so the two coincide). Rays only, a pixel's final level's:
// a sampler's bookkeeping, and the coarser rays refine:T:N:grid drops, come
// on top. Every render uses all threads.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <queue>
#include <string>
#include <vector>

#include "bench/accuracy/anti_aliasing_scenes.h"
#include "bench/accuracy/studies.h"

namespace quiver::accuracy {
namespace {

constexpr int kExpectationSeeds = 4;

struct Ladder {
  const char* name;
  const char* pattern;     // "jitter" or "grid": each level's --aa mode
  std::vector<int> sides;  // rays per side of each level, increasing
};

// Per pixel and level: squared error (summed over channels).
using LevelErrors = std::vector<std::vector<double>>;  // [level][pixel]

LevelErrors level_errors(const Scene& scene, RenderSettings settings, const Ladder& ladder,
                         const Framebuffer& reference, std::uint64_t seed) {
  LevelErrors errors;
  settings.trace.seed = seed;
  for (const int side : ladder.sides) {
    settings.aa = parse_anti_aliasing(std::string(ladder.pattern) + ":" + std::to_string(side));
    const Framebuffer image = render(scene, settings).image;
    std::vector<double> e(image.rgb.size() / 3);
    for (std::size_t p = 0; p < e.size(); ++p) e[p] = pixel_squared_error(image, reference, p);
    errors.push_back(std::move(e));
  }
  return errors;
}

struct OracleOutcome {
  double rays_per_pixel;
  double rmse;
  bool reached;
};

// Greedy allocation: ranked by `ranking`, judged by `judged`, until the
// judged squared error is at most `target` (summed over pixels and channels).
OracleOutcome allocate(const std::vector<int>& sides, const LevelErrors& ranking, const LevelErrors& judged,
                       double target) {
  const std::size_t pixels = judged[0].size();
  std::vector<double> rays(sides.size());
  for (std::size_t l = 0; l < sides.size(); ++l) rays[l] = double(sides[l]) * double(sides[l]);
  std::vector<std::size_t> level(pixels, 0);
  double error = 0.0, total_rays = rays[0] * double(pixels);
  for (std::size_t p = 0; p < pixels; ++p) error += judged[0][p];
  struct Step {
    double gain;  // ranked error drop per added ray
    std::size_t pixel, level;
    bool operator<(const Step& o) const { return gain < o.gain || (gain == o.gain && pixel > o.pixel); }
  };
  const auto best_step = [&](std::size_t p, Step& step) {
    bool found = false;
    for (std::size_t m = level[p] + 1; m < sides.size(); ++m) {
      const double gain = (ranking[level[p]][p] - ranking[m][p]) / (rays[m] - rays[level[p]]);
      if (gain > 0.0 && (!found || gain > step.gain)) {
        step = {gain, p, m};
        found = true;
      }
    }
    return found;
  };
  std::priority_queue<Step> queue;
  for (std::size_t p = 0; p < pixels; ++p) {
    Step s;
    if (best_step(p, s)) queue.push(s);
  }
  while (error > target && !queue.empty()) {
    const Step s = queue.top();
    queue.pop();
    error += judged[s.level][s.pixel] - judged[level[s.pixel]][s.pixel];
    total_rays += rays[s.level] - rays[level[s.pixel]];
    level[s.pixel] = s.level;
    Step next;
    if (best_step(s.pixel, next)) queue.push(next);
  }
  return {total_rays / double(pixels), std::sqrt(error / (3.0 * double(pixels))), error <= target};
}

}  // namespace

void aa_oracle_study(const StudyOptions& options) {
  const std::vector<Ladder> ladders = {{"jitter 1,2,4,8", "jitter", {1, 2, 4, 8}},
                                       {"jitter 2,4,8", "jitter", {2, 4, 8}},
                                       {"grid 1,2,4,8", "grid", {1, 2, 4, 8}},
                                       {"grid 2,4,8", "grid", {2, 4, 8}}};
  std::FILE* f = open_csv(options.out / "aa_oracle.csv",
                          "scene,width,height,texture_filter,grid4_rmse,ladder,oracle,rays_per_pixel,share_of_grid4,"
                          "rmse,reached");
  for (const SceneCase& sc : anti_aliasing_scenes(options)) {
    const Scene scene = build_scene(sc.desc, SceneBuildOptions{});
    const bool filter = !sc.desc.textures.empty();
    RenderSettings settings = anti_aliasing_settings(sc, filter);
    settings.threads = 0;
    settings.trace.seed = 12345;
    settings.aa = parse_anti_aliasing("jitter:16");
    const Framebuffer reference = render(scene, settings).image;
    settings.trace.seed = 0;
    settings.aa = parse_anti_aliasing("grid:4");
    const Framebuffer grid = render(scene, settings).image;
    const double grid_rmse = rmse(grid, reference);
    const double target = grid_rmse * grid_rmse * double(grid.rgb.size());
    for (const Ladder& ladder : ladders) {
      const LevelErrors judged = level_errors(scene, settings, ladder, reference, 0);
      const bool regular = std::string(ladder.pattern) == "grid";  // the same image for every seed
      LevelErrors expected = regular ? judged : level_errors(scene, settings, ladder, reference, 1);
      for (std::uint64_t seed = 2; !regular && seed <= kExpectationSeeds; ++seed) {
        const LevelErrors more = level_errors(scene, settings, ladder, reference, seed);
        for (std::size_t l = 0; l < more.size(); ++l) {
          for (std::size_t p = 0; p < more[l].size(); ++p) expected[l][p] += more[l][p];
        }
      }
      const std::pair<const char*, const LevelErrors*> oracles[] = {{"told the error", &judged},
                                                                    {"told the expected error", &expected}};
      for (const auto& [oracle, ranking] : oracles) {
        const OracleOutcome o = allocate(ladder.sides, *ranking, judged, target);
        std::fprintf(f, "%s,%d,%d,%s,%.9g,\"%s\",%s,%.4f,%.4f,%.9g,%d\n", sc.name.c_str(), sc.width, sc.height,
                     filter ? "box" : "none", grid_rmse, ladder.name, oracle, o.rays_per_pixel, o.rays_per_pixel / 16.0,
                     o.rmse, o.reached ? 1 : 0);
        std::printf("%-14s ladder %-14s %-24s %6.2f rays/pixel = %.2f of grid:4's, RMSE %.5f (grid:4 %.5f)%s\n",
                    sc.name.c_str(), ladder.name, oracle, o.rays_per_pixel, o.rays_per_pixel / 16.0, o.rmse, grid_rmse,
                    o.reached ? "" : ", not reached");
        std::fflush(f);
      }
    }
  }
  std::fclose(f);
}

}  // namespace quiver::accuracy
