#include "integrator/tracer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include "integrator/optics.h"

namespace quiver {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Shadow rays toward a point stop this fraction short of it (relative, so
// scale-free): a light sample lying on a surface is not hidden by it.
constexpr float kShadowEndFraction = 1.f - 1e-4f;

std::uint64_t mix64(std::uint64_t z) {
  // SplitMix64's finaliser.
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t float_bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

Vec3<float> mul(const Vec3<float>& a, const Vec3<float>& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
float max_component(const Vec3<float>& a) { return std::max(a.x, std::max(a.y, a.z)); }
std::size_t padded_to(std::size_t n, std::size_t w) { return (n + w - 1) / w * w; }

// Shadow rays per side of a light's sample grid: n x n for area lights, one ray otherwise.
int samples_per_side(const LightDesc& light) {
  const bool area = light.kind == LightDesc::Kind::rectangle || light.kind == LightDesc::Kind::sphere;
  return area ? light.samples : 1;
}

}  // namespace

std::uint64_t sample_key(double x, double y, std::uint64_t seed) {
  return mix64(mix64(mix64(seed) ^ float_bits(x)) ^ float_bits(y));
}

float hash_uniform(std::uint64_t key, std::uint64_t a, std::uint64_t b) {
  const std::uint64_t h = mix64(mix64(key ^ mix64(a + 0x9e3779b97f4a7c15ULL)) ^ b);
  return float(h >> 40) * 0x1p-24f;  // 24 bits: exactly representable, < 1
}

Tracer::Tracer(const Scene& scene, const SceneIntersector& intersector, const TraceSettings& settings)
    : scene_(scene), intersector_(intersector), settings_(settings), width_(std::size_t(intersector.lanes())) {
  light_slots_ = 0;
  for (const LightDesc& l : scene.lights) light_slots_ += samples_per_side(l) * samples_per_side(l);
}

void Tracer::trace(std::span<const CameraSample> samples, std::span<Vec3<float>> colors, TraceStats& stats) {
  std::fill(colors.begin(), colors.end(), Vec3<float>(0.f, 0.f, 0.f));
  rays_.clear();
  paths_.clear();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    rays_.push(samples[i].ray);
    paths_.push_back({static_cast<std::uint32_t>(i), {1.f, 1.f, 1.f}, samples[i].key});
  }
  rays_.pad();
  stats.rays.primary += samples.size();
  WaveLanes& primary = stats.wave(0);
  primary.active += samples.size();
  primary.issued_compacted += padded_to(samples.size(), width_);
  primary.issued_uncompacted += padded_to(samples.size(), width_);

  PhaseClock clock;
  for (int depth = 0; rays_.count > 0; ++depth) {
    hits_.reset(rays_);
    clock.charge(stats.phases.shading);
    intersector_.closest(scene_, rays_, hits_);
    clock.charge(stats.phases.intersection);
    next_rays_.clear();
    next_paths_.clear();
    child_parent_.clear();
    child_kind_.clear();
    shadow_rays_.clear();
    shadow_paths_.clear();
    shadow_parent_.clear();
    shadow_slot_.clear();
    for (std::size_t i = 0; i < rays_.count; ++i) shade(i, rays_.get(i), hits_.get(i), colors, depth, stats);
    clock.charge(stats.phases.shading);
    resolve_shadows(colors, stats);
    clock.charge(stats.phases.shadows);
    if (next_rays_.count > 0) {
      WaveLanes& next = stats.wave(std::size_t(depth) + 1);
      next.active += next_rays_.count;
      next.issued_compacted += padded_to(next_rays_.count, width_);
      count_uncompacted(next);
    }
    std::swap(rays_, next_rays_);
    std::swap(paths_, next_paths_);
    rays_.pad();
  }
  clock.charge(stats.phases.shading);
}

void Tracer::shade(std::size_t i, const Ray<float>& ray, const Hit<float>& hit, std::span<Vec3<float>> colors,
                   int depth, TraceStats& stats) {
  const Path& path = paths_[i];  // a reference: children record its index
  Vec3<float>& out = colors[path.sample];
  if (hit.id == kNoHit) {
    out = out + mul(path.weight, scene_.background);
    return;
  }
  if (depth == 0) ++stats.rays.primary_hits;
  const SurfacePoint s = surface_at(scene_, ray, hit);
  const MaterialDesc& m = *s.material;
  const Vec3<float> color = surface_color(scene_, s);
  const Vec3<float> incident = normalize(ray.direction);
  // Ambient: ka * Ia * colour.
  out = out + mul(path.weight, mul(scene_.ambient, color) * m.ka);
  // A one-sided surface seen from behind gets the ambient term only.
  if ((m.two_sided || s.entering) && (m.kd > 0.f || m.ks > 0.f)) add_direct_light(path, s, color, -incident);
  if (depth < settings_.max_depth) spawn_secondary(path, s, color, incident, stats);
}

void Tracer::add_direct_light(const Path& path, const SurfacePoint& s, const Vec3<float>& color,
                              const Vec3<float>& to_eye) {
  const MaterialDesc& m = *s.material;
  const Vec3<float> origin = offset_origin(s.position, s.error, s.geometric);
  int slot = 0;
  for (std::size_t l = 0; l < scene_.lights.size(); ++l) {
    const LightDesc& light = scene_.lights[l];
    const int n = samples_per_side(light);
    const Vec3<float> intensity = light.color / float(n * n);
    for (int j = 0; j < n * n; ++j, ++slot) {
      // Stratified jitter for area lights: a point in cell (j % n, j / n) of an n x n grid.
      auto jittered = [&](int cell, std::uint64_t dimension) {
        return (float(cell) + hash_uniform(path.key ^ settings_.seed, l, dimension)) / float(n);
      };
      Vec3<float> direction;
      float tmax = kShadowEndFraction;
      switch (light.kind) {
        case LightDesc::Kind::point: direction = light.position - origin; break;
        case LightDesc::Kind::directional:
          direction = -light.direction;
          tmax = kInfinity;
          break;
        case LightDesc::Kind::rectangle: {
          const float a = jittered(j % n, 2 * j), b = jittered(j / n, 2 * j + 1);
          direction = light.position + light.edge_u * a + light.edge_v * b - origin;
          break;
        }
        case LightDesc::Kind::sphere: {
          // The silhouette disk facing the point, by the concentric map.
          const Vec3<float> axis = normalize(light.position - origin);
          Vec3<float> t1, t2;
          tangent_axes(axis, t1, t2);
          const float sx = 2.f * jittered(j % n, 2 * j) - 1.f, sy = 2.f * jittered(j / n, 2 * j + 1) - 1.f;
          float r = 0.f, phi = 0.f;
          if (sx != 0.f || sy != 0.f) {
            const float quarter = float(std::numbers::pi / 4.0);
            if (std::fabs(sx) > std::fabs(sy)) {
              r = sx;
              phi = quarter * (sy / sx);
            } else {
              r = sy;
              phi = 2.f * quarter - quarter * (sx / sy);
            }
          }
          const Vec3<float> on_disk =
              light.position + (t1 * (r * std::cos(phi)) + t2 * (r * std::sin(phi))) * light.radius;
          direction = on_disk - origin;
          break;
        }
      }
      const Vec3<float> to_light = normalize(direction);
      const float n_dot_l = dot(s.shading, to_light);
      // No shadow ray where the surface faces away from the light.
      if (!(n_dot_l > 0.f) || !(dot(s.geometric, to_light) > 0.f)) continue;
      const Vec3<float> half = normalize(to_light + to_eye);
      const float n_dot_h = std::max(dot(s.shading, half), 0.f);
      const float specular = m.ks > 0.f && n_dot_h > 0.f ? m.ks * std::pow(n_dot_h, m.shininess) : 0.f;
      // I_i * (kd (N.L) colour + ks (N.H)^n), times the path weight.
      const Vec3<float> reflected = color * (m.kd * n_dot_l) + Vec3<float>(specular, specular, specular);
      const Vec3<float> contribution = mul(path.weight, mul(intensity, reflected));
      if (!(max_component(contribution) > 0.f)) continue;
      shadow_rays_.push({origin, direction, 0.f, tmax});
      shadow_paths_.push_back({path.sample, contribution});
      shadow_parent_.push_back(static_cast<std::uint32_t>(&path - paths_.data()));
      shadow_slot_.push_back(static_cast<std::uint16_t>(std::min(slot, 65535)));
    }
  }
}

void Tracer::spawn_secondary(const Path& path, const SurfacePoint& s, const Vec3<float>& color,
                             const Vec3<float>& incident, TraceStats& stats) {
  const MaterialDesc& m = *s.material;
  Vec3<float> reflect_weight = path.weight * m.kr;
  Vec3<float> refract_weight = mul(path.weight, color * m.kt);
  std::optional<Vec3<float>> refracted;
  if (m.kt > 0.f) {
    const float eta = s.entering ? 1.f / m.ior : m.ior;
    refracted = refract(incident, s.shading, eta);
    if (refracted && !(dot(*refracted, s.geometric) < 0.f)) refracted = refract(incident, s.geometric, eta);
    if (!refracted) {
      // Total internal reflection: the transmitted share is reflected.
      reflect_weight = reflect_weight + refract_weight;
      refract_weight = {0.f, 0.f, 0.f};
    }
  }
  auto worth_casting = [&](const Vec3<float>& w) {
    const float largest = max_component(w);
    return largest > 0.f && largest >= settings_.min_weight;
  };
  const auto parent = static_cast<std::uint32_t>(&path - paths_.data());
  if (worth_casting(reflect_weight)) {
    Vec3<float> direction = reflect(incident, s.shading);
    if (!(dot(direction, s.geometric) > 0.f)) direction = reflect(incident, s.geometric);
    next_rays_.push({offset_origin(s.position, s.error, s.geometric), direction, 0.f, kInfinity});
    next_paths_.push_back({path.sample, reflect_weight, mix64(path.key ^ 0x5265666cULL)});
    child_parent_.push_back(parent);
    child_kind_.push_back(static_cast<std::uint8_t>(RayKind::reflection));
    ++stats.rays.reflection;
  }
  if (refracted && worth_casting(refract_weight)) {
    next_rays_.push({offset_origin(s.position, s.error, -s.geometric), *refracted, 0.f, kInfinity});
    next_paths_.push_back({path.sample, refract_weight, mix64(path.key ^ 0x52667263ULL)});
    child_parent_.push_back(parent);
    child_kind_.push_back(static_cast<std::uint8_t>(RayKind::refraction));
    ++stats.rays.refraction;
  }
}

void Tracer::resolve_shadows(std::span<Vec3<float>> colors, TraceStats& stats) {
  const std::size_t n = shadow_rays_.count;
  if (n == 0) return;
  shadow_rays_.pad();
  stats.rays.shadow += n;
  stats.shadow.active += n;
  stats.shadow.issued_compacted += padded_to(n, width_);
  // Uncompacted: W lanes per parent packet and light sample slot in use.
  {
    std::vector<std::uint64_t> seen;
    std::uint64_t issued = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint64_t tag = (std::uint64_t(shadow_parent_[k] / width_) << 16) | shadow_slot_[k];
      if (std::find(seen.begin(), seen.end(), tag) == seen.end()) {
        // Tags arrive grouped by parent packet: forget older packets.
        if (!seen.empty() && (seen.back() >> 16) != (tag >> 16)) seen.clear();
        seen.push_back(tag);
        issued += width_;
      }
    }
    stats.shadow.issued_uncompacted += issued;
  }
  occlusion_.reset(shadow_rays_);
  intersector_.occluded(scene_, shadow_rays_, occlusion_, Layers::opaque);

  transmittance_.assign(n, Vec3<float>(1.f, 1.f, 1.f));
  if (scene_.transmissive.primitive_count() > 0) {
    // Transparent shadows: each transmissive surface crossed scales the
    // light by its kt times its colour, until none is left.
    transit_index_.clear();
    for (std::size_t k = 0; k < n; ++k) {
      if (occlusion_.occluded[k] == 0) transit_index_.push_back(static_cast<std::uint32_t>(k));
    }
    std::vector<float> tmin(n, 0.f);
    while (!transit_index_.empty()) {
      transit_rays_.clear();
      for (std::uint32_t k : transit_index_) {
        Ray<float> r = shadow_rays_.get(k);
        r.tmin = tmin[k];
        transit_rays_.push(r);
      }
      transit_rays_.pad();
      transit_hits_.reset(transit_rays_);
      intersector_.closest(scene_, transit_rays_, transit_hits_, Layers::transmissive);
      std::size_t kept = 0;
      for (std::size_t j = 0; j < transit_index_.size(); ++j) {
        const std::uint32_t k = transit_index_[j];
        const Hit<float> h = transit_hits_.get(j);
        if (h.id == kNoHit) continue;
        const SurfacePoint s = surface_at(scene_, transit_rays_.get(j), h);
        transmittance_[k] = mul(transmittance_[k], surface_color(scene_, s) * s.material->kt);
        if (!(max_component(transmittance_[k]) > 0.f)) {
          occlusion_.occluded[k] = 1;
          continue;
        }
        tmin[k] = h.t;
        transit_index_[kept++] = k;
      }
      transit_index_.resize(kept);
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (occlusion_.occluded[k] != 0) continue;
    Vec3<float>& out = colors[shadow_paths_[k].sample];
    out = out + mul(shadow_paths_[k].contribution, transmittance_[k]);
  }
}

void Tracer::count_uncompacted(WaveLanes& lanes) {
  // W lanes per parent packet and child kind with any ray.
  std::uint64_t issued = 0;
  std::size_t last_packet = std::numeric_limits<std::size_t>::max();
  bool kinds[3] = {false, false, false};
  for (std::size_t k = 0; k < child_parent_.size(); ++k) {
    const std::size_t packet = child_parent_[k] / width_;
    if (packet != last_packet) {
      kinds[0] = kinds[1] = kinds[2] = false;
      last_packet = packet;
    }
    bool& seen = kinds[child_kind_[k]];
    if (!seen) {
      seen = true;
      issued += width_;
    }
  }
  lanes.issued_uncompacted += issued;
}

void Tracer::first_hits(std::span<const Ray<float>> rays, std::span<FirstHit> out) {
  rays_.clear();
  for (const Ray<float>& r : rays) rays_.push(r);
  rays_.pad();
  hits_.reset(rays_);
  intersector_.closest(scene_, rays_, hits_);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Hit<float> h = hits_.get(i);
    if (h.id == kNoHit) {
      out[i] = {kInfinity, {0.f, 0.f, 0.f}, kNoKind, -1};
      continue;
    }
    const SurfacePoint s = surface_at(scene_, rays[i], h);
    const PrimitiveOrigin& o = scene_.origin(s.ref);
    out[i] = {h.t * std::sqrt(dot(rays[i].direction, rays[i].direction)), s.shading,
              static_cast<std::int32_t>(o.kind), static_cast<std::int32_t>(o.index)};
  }
}

}  // namespace quiver
