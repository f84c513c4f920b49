#include "integrator/tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace quiver {

namespace {

std::size_t padded_to(std::size_t n, std::size_t w) { return (n + w - 1) / w * w; }

std::size_t light_slot_count(const Scene& scene) {
  std::size_t slots = 0;
  for (const LightDesc& l : scene.lights) slots += std::size_t(samples_per_side(l) * samples_per_side(l));
  return slots;
}

// The distance to the hit at t along a ray of any direction length.
float distance_along(const Ray<float>& ray, float t) { return t * std::sqrt(dot(ray.direction, ray.direction)); }

}  // namespace

bool rays_carry_differentials(const Scene& scene, const TraceSettings& settings) {
  return settings.filter_textures && !scene.textures.empty();
}

Tracer::Tracer(const Scene& scene, const SceneIntersector& intersector, const TraceSettings& settings)
    : scene_(scene),
      intersector_(intersector),
      settings_(settings),
      width_(std::size_t(intersector.lanes())),
      differentials_(rays_carry_differentials(scene, settings)),
      area_lights_(has_area_lights(scene)),
      materials_(scene.materials),
      shade_wave_(with_kernel_unit(intersector.unit(),
                                   [](auto u) -> ShadeWaveFunction { return &shade_wave<decltype(u)::value>; })),
      camera_rays_(with_kernel_unit(intersector.unit(),
                                    [](auto u) -> CameraRaysFunction { return &camera_rays<decltype(u)::value>; })),
      camera_direction_changes_(with_kernel_unit(intersector.unit(),
                                                 [](auto u) -> CameraDirectionChangesFunction {
                                                   return &camera_direction_changes<decltype(u)::value>;
                                                 })),
      see_area_lights_(with_kernel_unit(intersector.unit(),
                                        [](auto u) -> SeeAreaLightsFunction {
                                          return &see_area_lights<decltype(u)::value>;
                                        })),
      hit_footprints_(with_kernel_unit(intersector.unit(),
                                       [](auto u) -> HitFootprintsFunction {
                                         return &hit_footprints<decltype(u)::value>;
                                       })),
      slots_(light_slot_count(scene)),
      occlusion_(slots_.size()),
      transmittance_(slots_.size()) {}

void Tracer::trace(const Camera& camera, const FilmSamples& film, std::span<Vec3<float>> colors, TraceStats& stats,
                   std::span<FirstSurface> surfaces) {
  std::fill(colors.begin(), colors.end(), Vec3<float>(0.f, 0.f, 0.f));
  start_at_camera(camera, film, stats);
  PhaseClock clock(settings_.time_phases);
  bool one_ray_per_sample = true;  // until a ray spawns two
  for (int depth = 0; rays_.count > 0; ++depth) {
    hits_.reset(rays_);
    clock.charge(stats.phases.shading);
    intersector_.closest(scene_, rays_, hits_);
    clock.charge(stats.phases.intersection);
    next_rays_.clear();
    next_paths_.clear();
    next_differentials_.clear();
    for (ShadowSlot& slot : slots_) slot.open(rays_.count);
    resolve_surfaces();
    if (depth == 0 && !surfaces.empty()) record_first_surfaces(surfaces);
    shade(depth);
    // The ambient terms (the background on a miss), in ray order.
    for (std::size_t i = 0; i < rays_.count; ++i) {
      Vec3<float>& out = colors[std::size_t(paths_.sample[i])];
      out = out + Vec3<float>(shaded_.emitted_r[i], shaded_.emitted_g[i], shaded_.emitted_b[i]);
    }
    count_shading(depth, stats);
    clock.charge(stats.phases.shading);
    resolve_shadows(colors, shaded_.counts.shadow_uncompacted, one_ray_per_sample, stats);
    one_ray_per_sample = one_ray_per_sample && shaded_.counts.refraction == 0;
    clock.charge(stats.phases.shadows);
    next_wave(depth, stats);
  }
  clock.charge(stats.phases.shading);
}

void Tracer::start_at_camera(const Camera& camera, const FilmSamples& film, TraceStats& stats) {
  const std::size_t n = film.size();
  camera_rays_(camera, film.x, film.y, rays_);
  paths_.start_at_camera(n);
  for (std::size_t i = 0; i < n; ++i) paths_.key[i] = sample_key(film.x[i], film.y[i], settings_.seed);
  paths_.pad();
  differentials_of_rays_.clear();
  if (differentials_) {
    // A pinhole: the origin does not change. Without footprints, nothing changes.
    DifferentialColumns& d = differentials_of_rays_;
    d.resize(n);
    if (film.footprints) {
      camera_direction_changes_(camera, film.x, film.y, film.spacing, d.direction_dx, d.direction_dy);
      for (std::size_t i = 0; i < n; ++i) {
        d.centre_x[i] = static_cast<float>((film.cell_x[i] - film.x[i]) / film.spacing[i]);
        d.centre_y[i] = static_cast<float>((film.cell_y[i] - film.y[i]) / film.spacing[i]);
      }
    }
    d.pad(rays_.count);
  }
  stats.rays.primary += n;
  WaveLanes& primary = stats.wave(0);
  primary.active += n;
  primary.issued_compacted += padded_to(n, width_);
  primary.issued_uncompacted += padded_to(n, width_);
}

FirstSurface first_surface(const Ray<float>& ray, float t, std::uint32_t material) {
  FirstSurface s;
  s.depth = distance_along(ray, t);
  s.material = static_cast<std::int32_t>(material);
  return s;
}

void Tracer::record_first_surfaces(std::span<FirstSurface> surfaces) const {
  for (std::size_t i = 0; i < rays_.count; ++i) {
    const std::int32_t id = hits_.id[i];
    surfaces[std::size_t(paths_.sample[i])] =
        id == kNoHit ? FirstSurface{}
                     : first_surface(rays_.get(i), hits_.t[i], static_cast<std::uint32_t>(surfaces_.material[i]));
  }
}

void Tracer::shade(int depth) {
  shaded_.counts = {};
  const WaveAppendTargets to{&slots_, &next_rays_, &next_paths_, differentials_ ? &next_differentials_ : nullptr};
  const WaveShadingInput in{.scene = &scene_,
                            .materials = &materials_,
                            .rays = &rays_,
                            .hits = &hits_,
                            .paths = &paths_,
                            .surfaces = &surfaces_,
                            .differentials = differentials_ ? &differentials_of_rays_ : nullptr,
                            .spawn = depth < settings_.max_depth,
                            .min_weight = settings_.min_weight,
                            .seed = settings_.seed,
                            .spawn_every_ray = settings_.spawn_every_ray};
  shade_wave_(in, to, shaded_);
}

void Tracer::count_shading(int depth, TraceStats& stats) const {
  if (depth == 0) stats.rays.primary_hits += shaded_.counts.hits;
  stats.shading_active += shaded_.counts.hits;
  stats.light_sample_active += shaded_.counts.light_active;
  stats.light_sample_issued += shaded_.counts.light_issued;
  stats.rays.reflection += shaded_.counts.reflection;
  stats.rays.refraction += shaded_.counts.refraction;
}

void Tracer::next_wave(int depth, TraceStats& stats) {
  if (next_rays_.count > 0) {
    WaveLanes& next = stats.wave(std::size_t(depth) + 1);
    next.active += next_rays_.count;
    next.issued_compacted += padded_to(next_rays_.count, width_);
    next.issued_uncompacted += shaded_.counts.next_uncompacted;
  }
  std::swap(rays_, next_rays_);
  std::swap(paths_, next_paths_);
  std::swap(differentials_of_rays_, next_differentials_);
  rays_.pad();
  paths_.pad();
  if (differentials_) differentials_of_rays_.pad(rays_.count);
}

void Tracer::resolve_surfaces() {
  surfaces_.resize(rays_.ox.size(), differentials_);
  if (area_lights_) {
    Vec3Columns& seen = surfaces_.seen;
    seen.x.assign(rays_.ox.size(), scene_.background.x);
    seen.y.assign(rays_.ox.size(), scene_.background.y);
    seen.z.assign(rays_.ox.size(), scene_.background.z);
    see_area_lights_(scene_, rays_, hits_, seen);
  }
  if (differentials_) {
    hit_footprints_(rays_, hits_, differentials_of_rays_, surfaces_.point_dx, surfaces_.point_dy);
  }
  for (std::size_t i = 0; i < rays_.count; ++i) {
    const std::int32_t id = hits_.id[i];
    if (id == kNoHit) continue;
    if (differentials_) {
      resolve_surface_with_footprint(i);
      continue;
    }
    if (scene_.is_plain(id)) {
      // A plain surface: its material's colour.
      const std::uint32_t material = scene_.material_of_id[std::size_t(id)];
      const Vec3<float>& color = scene_.materials[material].color;
      surfaces_.material[i] = static_cast<std::int32_t>(material);
      surfaces_.color_r[i] = color.x;
      surfaces_.color_g[i] = color.y;
      surfaces_.color_b[i] = color.z;
      continue;
    }
    store_surface(i, surface_detail(scene_, rays_.get(i), hits_.get(i)));
  }
}

void Tracer::store_surface(std::size_t i, const SurfaceDetail& d) {
  surfaces_.material[i] = static_cast<std::int32_t>(d.material_index);
  if (d.smooth) {
    surfaces_.smooth[i] = 1;
    surfaces_.nx[i] = d.interpolated.x;
    surfaces_.ny[i] = d.interpolated.y;
    surfaces_.nz[i] = d.interpolated.z;
    surfaces_.shadow_lift.set(i, d.shadow_lift);
  }
  surfaces_.color_r[i] = d.color.x;
  surfaces_.color_g[i] = d.color.y;
  surfaces_.color_b[i] = d.color.z;
  if (d.ref.instance >= 0) surfaces_.error.set(i, d.instance_error);
}

void Tracer::resolve_surface_with_footprint(std::size_t i) {
  const DifferentialColumns& r = differentials_of_rays_;
  const PointDifferentials footprint{surfaces_.point_dx.get(i), surfaces_.point_dy.get(i), r.centre_x[i],
                                     r.centre_y[i]};
  const SurfaceDetail d = surface_detail(scene_, rays_.get(i), hits_.get(i), &footprint);
  store_surface(i, d);
  surfaces_.normal_dx.set(i, d.normal_change[0]);
  surfaces_.normal_dy.set(i, d.normal_change[1]);
}

void Tracer::resolve_shadows(std::span<Vec3<float>> colors, std::uint64_t uncompacted, bool one_ray_per_sample,
                             TraceStats& stats) {
  std::size_t total = 0;
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    ShadowSlot& slot = slots_[s];
    const std::size_t n = slot.rays.count;
    if (n == 0) continue;
    slot.rays.pad();
    total += n;
    stats.shadow.issued_compacted += padded_to(n, width_);
    occlusion_[s].reset(slot.rays);
    charge_time_of(stats.phases.shadow_walks, settings_.time_phases,
                   [&] { intersector_.occluded(scene_, slot.rays, occlusion_[s], Layers::opaque); });
    transmittance_[s].assign(n, Vec3<float>(1.f, 1.f, 1.f));
    if (scene_.has_transmissive()) transmit(s, stats.phases.shadow_walks);
  }
  stats.rays.shadow += total;
  stats.shadow.active += total;
  stats.shadow.issued_uncompacted += uncompacted;
  if (total == 0) return;
  // The light seen, by ray and then slot. While every sample has one ray in
  // the wave (no refraction spawned yet), slot after slot adds to each
  // sample in that same order.
  slot_lights_.clear();
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    const ShadowSlot& slot = slots_[s];
    slot_lights_.push_back({occlusion_[s].occluded.data(), slot.point.data(), slot.light_r.data(),
                            slot.light_g.data(), slot.light_b.data(), transmittance_[s].data(), slot.rays.count});
  }
  const std::int32_t* const sample = paths_.sample.data();
  const auto add = [&](const SlotLight& l, std::size_t k, Vec3<float>& out) {
    out = out + mul(Vec3<float>(l.r[k], l.g[k], l.b[k]), l.transmittance[k]);
  };
  if (one_ray_per_sample) {
    for (const SlotLight& l : slot_lights_) {
      for (std::size_t k = 0; k < l.count; ++k) {
        if (l.occluded[k] == 0) add(l, k, colors[std::size_t(sample[l.point[k]])]);
      }
    }
    return;
  }
  // Else rays merged from the slots (each slot's rays are in ray order).
  cursor_.assign(slots_.size(), 0);
  for (std::size_t i = 0; i < rays_.count; ++i) {
    for (std::size_t s = 0; s < slot_lights_.size(); ++s) {
      const SlotLight& l = slot_lights_[s];
      std::size_t& k = cursor_[s];
      if (k >= l.count || std::size_t(l.point[k]) != i) continue;
      if (l.occluded[k] == 0) add(l, k, colors[std::size_t(sample[i])]);
      ++k;
    }
  }
}

void Tracer::transmit(std::size_t s, std::uint64_t& walk_time) {
  // Each transmissive surface crossed scales the light by its kt times its
  // colour, until none is left. Each crossing is sought along copies of the
  // rays still lit, from their last crossing on; the first along the slot's
  // own rays when at most an eighth are occluded (those given the empty
  // range (0, -1)), sparing the copies: with more, their dead lanes in the
  // packets cost more than the copies.
  ShadowSlot& slot = slots_[s];
  std::vector<Vec3<float>>& transmittance = transmittance_[s];
  AlignedInts& occluded = occlusion_[s].occluded;
  // Ray k crossed the surface of hit j of `rays`: false once no light is left.
  const auto cross = [&](const RaySoA& rays, std::size_t j, std::uint32_t k) {
    const std::int32_t id = transit_hits_.id[j];
    // A plain surface's colour is its material's; others need the hit's detail.
    Vec3<float> filter;
    if (scene_.is_plain(id)) {
      const MaterialDesc& material = scene_.materials[scene_.material_of_id[std::size_t(id)]];
      filter = material.color * material.kt;
    } else {
      const SurfaceDetail d = surface_detail(scene_, rays.get(j), transit_hits_.get(j));
      filter = d.color * d.material->kt;
    }
    transmittance[k] = mul(transmittance[k], filter);
    if (!(max_component(transmittance[k]) > 0.f)) {
      occluded[k] = 1;
      return false;
    }
    transit_tmin_[k] = transit_hits_.t[j];
    return true;
  };
  const std::size_t count = slot.rays.count;
  // The lit rays' indices, written without a branch per ray.
  transit_index_.resize(count);
  std::size_t lit = 0;
  for (std::size_t k = 0; k < count; ++k) {
    transit_index_[lit] = static_cast<std::uint32_t>(k);
    lit += occluded[k] == 0 ? 1 : 0;
  }
  transit_index_.resize(lit);
  transit_tmin_.assign(count, 0.f);
  if (8 * lit >= 7 * count) {
    for (std::size_t k = 0; k < count; ++k) slot.rays.tmax[k] = occluded[k] != 0 ? -1.f : slot.rays.tmax[k];
    transit_hits_.reset(slot.rays);
    charge_time_of(walk_time, settings_.time_phases,
                   [&] { intersector_.closest(scene_, slot.rays, transit_hits_, Layers::transmissive); });
    std::size_t kept = 0;
    for (const std::uint32_t k : transit_index_) {
      if (transit_hits_.id[k] != kNoHit && cross(slot.rays, k, k)) transit_index_[kept++] = k;
    }
    transit_index_.resize(kept);
  }
  while (!transit_index_.empty()) {
    const std::size_t n = transit_index_.size();
    transit_rays_.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      const std::uint32_t k = transit_index_[j];
      transit_rays_.ox[j] = slot.rays.ox[k];
      transit_rays_.oy[j] = slot.rays.oy[k];
      transit_rays_.oz[j] = slot.rays.oz[k];
      transit_rays_.dx[j] = slot.rays.dx[k];
      transit_rays_.dy[j] = slot.rays.dy[k];
      transit_rays_.dz[j] = slot.rays.dz[k];
      transit_rays_.tmin[j] = transit_tmin_[k];
      transit_rays_.tmax[j] = slot.rays.tmax[k];
    }
    transit_rays_.pad();
    transit_hits_.reset(transit_rays_);
    charge_time_of(walk_time, settings_.time_phases,
                   [&] { intersector_.closest(scene_, transit_rays_, transit_hits_, Layers::transmissive); });
    std::size_t kept = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const std::uint32_t k = transit_index_[j];
      if (transit_hits_.id[j] != kNoHit && cross(transit_rays_, j, k)) transit_index_[kept++] = k;
    }
    transit_index_.resize(kept);
  }
}

void Tracer::first_hits(std::span<const Ray<float>> rays, std::span<FirstSurface> out) {
  rays_.clear();
  for (const Ray<float>& r : rays) rays_.push(r);
  rays_.pad();
  hits_.reset(rays_);
  intersector_.closest(scene_, rays_, hits_);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Hit<float> h = hits_.get(i);
    if (h.id == kNoHit) {
      out[i] = FirstSurface{};
      continue;
    }
    const SurfacePoint s = surface_at(scene_, rays[i], h);
    const PrimitiveOrigin& o = scene_.origin(s.ref);
    out[i] = first_surface(rays[i], h.t, s.material_index);
    out[i].normal = s.shading;
    out[i].kind = static_cast<std::int32_t>(o.kind);
    const std::uint64_t id = scene_.object_id(s.ref);
    out[i].id = static_cast<std::int32_t>(std::min<std::uint64_t>(id, std::numeric_limits<std::int32_t>::max()));
  }
}

}  // namespace quiver
