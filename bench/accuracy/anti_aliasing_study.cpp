// Anti-aliasing: RMSE of each mode's image against a high-sample reference
// (jitter:16, 256 stratified rays per pixel, another seed, with the same
// texture filter), against render time, with textures point-sampled and, in
// scenes with textures, box-filtered (--texture-filter box), on the scenes
// of anti_aliasing_scenes.h. One thread, the widest ISA, so the times
// compare within the run.
#include <cstdio>
#include <string>
#include <vector>

#include "bench/accuracy/anti_aliasing_scenes.h"
#include "bench/accuracy/studies.h"

namespace quiver::accuracy {

void anti_aliasing_study(const StudyOptions& options) {
  const std::vector<SceneCase> scenes = anti_aliasing_scenes(options);
  const std::vector<std::string> default_modes = {"none",          "grid:2",         "grid:3",          "grid:4",
                         "jitter:2",      "jitter:3",       "jitter:4",        "adaptive:0.3:3",
                         "adaptive:0.1:3", "adaptive:0.03:3", "adaptive:0.01:3", "corners",
                         "refine:0.1:4",   "refine:0.05:4",   "refine:0.03:4",   "refine:0.02:4",
                         "refine:0.08:8",  "refine:0.04:8",   "refine:0.02:8",   "refine:0.01:8",
                         "refine:0.05:4:grid", "refine:0.02:4:grid", "refine:0.01:4:grid",
                         "refine:0.04:8:grid", "refine:0.02:8:grid", "refine:0.01:8:grid"};
  const std::vector<std::string>& modes = options.aa_modes.empty() ? default_modes : options.aa_modes;
  std::FILE* f = open_csv(options.out / "anti_aliasing.csv",
                          "scene,width,height,mode,texture_filter,render_ms,camera_rays,rmse,reference_mode,reference_ms");
  for (const SceneCase& sc : scenes) {
    const Scene scene = build_scene(sc.desc, SceneBuildOptions{});
    for (const bool filter : {false, true}) {
      if (filter && sc.desc.textures.empty()) continue;  // the same image
      const char* filter_name = filter ? "box" : "none";
      RenderSettings settings = anti_aliasing_settings(sc, filter);
      settings.trace.seed = 12345;
      settings.aa = parse_anti_aliasing("jitter:16");
      const RenderResult reference = render(scene, settings);
      settings.trace.seed = 0;
      for (const std::string& mode_text : modes) {
        const char* mode = mode_text.c_str();
        settings.aa = parse_anti_aliasing(mode);
        const RenderResult r = render(scene, settings);
        const double error = rmse(r.image, reference.image);
        std::fprintf(f, "%s,%d,%d,%s,%s,%.3f,%llu,%.9g,jitter:16,%.3f\n", sc.name.c_str(), sc.width, sc.height, mode,
                     filter_name, r.render_ms, static_cast<unsigned long long>(r.stats.rays.primary), error,
                     reference.render_ms);
        std::printf("%-14s %-16s %-4s %8.1f ms  RMSE %.5f\n", sc.name.c_str(), mode, filter_name, r.render_ms, error);
        std::fflush(f);
      }
    }
  }
  std::fclose(f);
}

}  // namespace quiver::accuracy
