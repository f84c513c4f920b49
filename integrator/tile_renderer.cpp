#include "integrator/tile_renderer.h"

namespace quiver {

namespace {

// The supersampler's mode: the settings' when it is none, grid or jitter.
AntiAliasing supersampled_aa(const AntiAliasing& aa) {
  const bool supersampled = aa.mode == AntiAliasing::Mode::none || aa.mode == AntiAliasing::Mode::grid ||
                            aa.mode == AntiAliasing::Mode::jitter;
  return supersampled ? aa : AntiAliasing{};
}

}  // namespace

TileRenderer::TileRenderer(const TileTarget& target, std::vector<Vec3<float>>* corners)
    : target_(target), corners_(corners), supersampler_(supersampled_aa(target.settings.aa)) {}

void TileRenderer::render(const PixelTile& tile, TileWorker& w) const {
  switch (target_.settings.aa.mode) {
    case AntiAliasing::Mode::none:
    case AntiAliasing::Mode::grid:
    case AntiAliasing::Mode::jitter: supersampler_.render(target_, tile, w.batch); break;
    case AntiAliasing::Mode::corners: render_corners(target_, tile, w.batch, *corners_); break;
    case AntiAliasing::Mode::adaptive: render_adaptive(target_, tile, w.batch, w.adaptive); break;
    case AntiAliasing::Mode::refine: render_refined(target_, tile, w.batch, w.refine); break;
  }
  const RenderSettings& settings = target_.settings;
  if (settings.aov_depth || settings.aov_normal || settings.aov_id) render_aovs(tile, w);
}

void TileRenderer::render_aovs(const PixelTile& tile, TileWorker& w) const {
  const RenderSettings& settings = target_.settings;
  Framebuffer& image = target_.image;
  w.centre_rays.clear();
  for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
    for (int x = tile.x0; x < tile.x0 + tile.width; ++x) {
      w.centre_rays.push_back(target_.camera.ray(x + 0.5, y + 0.5));
    }
  }
  w.first.resize(w.centre_rays.size());
  w.batch.tracer.first_hits(w.centre_rays, w.first);
  std::size_t k = 0;
  for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
    for (int x = tile.x0; x < tile.x0 + tile.width; ++x, ++k) {
      const std::size_t p = std::size_t(y) * std::size_t(image.width) + std::size_t(x);
      const FirstSurface& f = w.first[k];
      if (settings.aov_depth) image.depth[p] = f.depth;
      if (settings.aov_normal) {
        image.normal[3 * p] = f.normal.x;
        image.normal[3 * p + 1] = f.normal.y;
        image.normal[3 * p + 2] = f.normal.z;
      }
      if (settings.aov_id) {
        image.kind[p] = f.kind;
        image.id[p] = f.id;
      }
    }
  }
}

}  // namespace quiver
