// Whitted shading of a wave in packets (the contract: wave_shading.h).
// Compiled once per kernel unit; F is the unit's lane type.
#include "integrator/wave_shading.h"

#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "integrator/light_cone.h"
#include "integrator/optics.h"
#include "integrator/ray_differentials.h"
#include "integrator/sample_hash.h"
#include "integrator/surface_frame.h"
#include "simd/power.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Shadow rays toward a point stop this fraction short of it (relative, so
// scale-free): a light sample lying on a surface is not hidden by it.
constexpr float kShadowEndFraction = 1.f - 1e-4f;
// Keys of the reflection and refraction rays a path spawns: mix64(key ^ tag).
constexpr std::uint64_t kReflectionTag = 0x5265666cULL, kRefractionTag = 0x52667263ULL;

// A packet's lanes in memory, for the per-lane appends.
struct LaneArray {
  alignas(64) float v[kMaxLanes];
};
template <class F>
struct Vec3Lanes {
  LaneArray x, y, z;
  explicit Vec3Lanes(const Vec3<F>& a) {
    store_lanes(a.x, x.v);
    store_lanes(a.y, y.v);
    store_lanes(a.z, z.v);
  }
};


void set_vec3(AlignedFloats& x, AlignedFloats& y, AlignedFloats& z, std::size_t i, const LaneArray& lx,
              const LaneArray& ly, const LaneArray& lz, int k) {
  x[i] = lx.v[k];
  y[i] = ly.v[k];
  z[i] = lz.v[k];
}

template <class F>
void set_ray(RaySoA& rays, std::size_t i, const Vec3Lanes<F>& origin, const Vec3Lanes<F>& direction, int k,
             float tmax) {
  set_vec3(rays.ox, rays.oy, rays.oz, i, origin.x, origin.y, origin.z, k);
  set_vec3(rays.dx, rays.dy, rays.dz, i, direction.x, direction.y, direction.z, k);
  rays.tmin[i] = 0.f;
  rays.tmax[i] = tmax;
}

// Appends the shadow rays of the lanes in `bits`, in lane order.
template <class F>
void append_shadow_rays(ShadowSlot& slot, unsigned bits, std::size_t first, const Vec3<F>& origin,
                        const Vec3<F>& direction, float tmax, const Vec3<F>& light) {
  RaySoA& r = slot.rays;
  const std::size_t i = slot.grow(std::size_t(std::popcount(bits)));
  store_selected_lanes<F, 11, 1>(
      bits,
      {origin.x, origin.y, origin.z, direction.x, direction.y, direction.z, F(0.f), F(tmax), light.x, light.y,
       light.z},
      {r.ox.data() + i, r.oy.data() + i, r.oz.data() + i, r.dx.data() + i, r.dy.data() + i, r.dz.data() + i,
       r.tmin.data() + i, r.tmax.data() + i, slot.light_r.data() + i, slot.light_g.data() + i,
       slot.light_b.data() + i},
      {lane_index<F>() + IntLanes<F>(static_cast<std::int32_t>(first))}, {slot.point.data() + i});
}

// Each lane's stratified point in the unit square for sample j of an n x n
// light: in cell (j % n, j / n), jittered by its path's numbers for the
// light (`streams`, hash_stream of the path's key and the light's index).
struct SampleJitter {
  LaneArray a, b;
};
template <class F>
SampleJitter sample_jitter(const std::uint64_t* streams, int j, int n) {
  SampleJitter jitter;
  for (int k = 0; k < lane_count<F>; ++k) {
    jitter.a.v[k] = (float(j % n) + stream_uniform(streams[k], 2 * std::uint64_t(j))) / float(n);
    jitter.b.v[k] = (float(j / n) + stream_uniform(streams[k], 2 * std::uint64_t(j) + 1)) / float(n);
  }
  return jitter;
}

// The light sample's direction from each lane's origin (not unit) and the
// end of its shadow ray; area lights at each lane's jittered point.
template <class F>
Vec3<F> light_sample_direction(const LightDesc& light, const SampleJitter& jitter, const Vec3<F>& origin,
                               float& tmax) {
  tmax = kShadowEndFraction;
  switch (light.kind) {
    case LightDesc::Kind::point:
    case LightDesc::Kind::spot: return Vec3<F>(light.position) - origin;
    case LightDesc::Kind::directional: tmax = kInfinity; return Vec3<F>(-light.direction);
    case LightDesc::Kind::rectangle:
    case LightDesc::Kind::sphere: break;
  }
  const LaneArray& a = jitter.a;
  const LaneArray& b = jitter.b;
  if (light.kind == LightDesc::Kind::rectangle) {
    return Vec3<F>(light.position) + Vec3<F>(light.edge_u) * load_lanes<F>(a.v) +
           Vec3<F>(light.edge_v) * load_lanes<F>(b.v) - origin;
  }
  // Sphere: the silhouette disk facing the point, by the concentric map
  // (Shirley and Chiu 1997); cos and sin from libm, one lane at a time.
  LaneArray along_t1, along_t2;
  for (int k = 0; k < lane_count<F>; ++k) {
    const float sx = 2.f * a.v[k] - 1.f, sy = 2.f * b.v[k] - 1.f;
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
    along_t1.v[k] = r * std::cos(phi);
    along_t2.v[k] = r * std::sin(phi);
  }
  const Vec3<F> center(light.position);
  const Vec3<F> axis = normalize(center - origin);
  Vec3<F> t1, t2;
  tangent_axes(axis, t1, t2);
  const Vec3<F> on_disk =
      center + (t1 * load_lanes<F>(along_t1.v) + t2 * load_lanes<F>(along_t2.v)) * F(light.radius);
  return on_disk - origin;
}

// The differentials of a packet's reflection and refraction rays
// (ray_differentials.h): their origins change as the hit point does, their
// directions with the incident direction and the shading normal. The
// normal's stored change is in the primitive's orientation, so it turns
// with the normal; where a ray leaves through the geometric normal instead
// (the shading normal would bend it behind the surface) that normal's
// change is taken as 0.
template <class F>
struct SpawnedDifferentials {
  Vec3Lanes<F> point_dx, point_dy, reflected_dx, reflected_dy, refracted_dx, refracted_dy;
};

template <class F>
SpawnedDifferentials<F> spawned_differentials(const WaveShadingInput& in, std::size_t first, const SurfaceFrame<F>& s,
                                              const Vec3<F>& oriented_normal, const Vec3<F>& incident,
                                              const Mask<F>& mirrored_outward, const F& eta,
                                              const Mask<F>& refract_through_geometric,
                                              const Vec3<F>& along_shading, const Vec3<F>& along_geometric) {
  const Vec3<F> none(F(0.f), F(0.f), F(0.f));
  const F turn = select(dot(s.shading, oriented_normal) < F(0.f), F(-1.f), F(1.f));
  auto reflected = [&](const Vec3<F>& d_incident, const Vec3<F>& d_normal) {
    return select(mirrored_outward, reflect_differential(incident, d_incident, s.shading, d_normal * turn),
                  reflect_differential(incident, d_incident, s.geometric, none));
  };
  auto refracted = [&](const Vec3<F>& d_incident, const Vec3<F>& d_normal) {
    return select(refract_through_geometric,
                  refract_differential(incident, d_incident, s.geometric, none, eta, along_geometric),
                  refract_differential(incident, d_incident, s.shading, d_normal * turn, eta, along_shading));
  };
  const Vec3<F> d_incident_x = in.differentials->direction_dx.load<F>(first);
  const Vec3<F> d_incident_y = in.differentials->direction_dy.load<F>(first);
  const Vec3<F> d_normal_x = in.surfaces->normal_dx.load<F>(first);
  const Vec3<F> d_normal_y = in.surfaces->normal_dy.load<F>(first);
  return {Vec3Lanes<F>(in.surfaces->point_dx.load<F>(first)),
          Vec3Lanes<F>(in.surfaces->point_dy.load<F>(first)),
          Vec3Lanes<F>(reflected(d_incident_x, d_normal_x)),
          Vec3Lanes<F>(reflected(d_incident_y, d_normal_y)),
          Vec3Lanes<F>(refracted(d_incident_x, d_normal_x)),
          Vec3Lanes<F>(refracted(d_incident_y, d_normal_y))};
}

// Largest weight above 0 and at least the cut-off.
template <class F>
Mask<F> worth_casting(const Vec3<F>& weight, float min_weight) {
  const F largest = max_component(weight);
  return (largest > F(0.f)) & (largest >= F(min_weight));
}

// A packet's hits as shading reads them: the surface frame (its error
// with the instance's), the material, the colour and the path weight.
template <class F>
struct PacketHits {
  Mask<F> hit_mask;
  Hit<F> hit;
  Vec3<F> weight;
  Mask<F> smooth;
  Vec3<F> interpolated;
  SurfaceFrame<F> s;
  Vec3<F> color;
  IntLanes<F> material;
  Vec3<F> direction;  // the ray's, as stored
  Vec3<F> incident;   // the ray's unit direction; set once some lane hits
  Vec3<F> origin;     // the point offset to the geometric normal's side; set once some lane hits
  Vec3<F> lift;       // SurfaceMapping::shadow_lift
  Mask<F> liftable;   // smooth, with a lift toward the side the ray came from
};

template <class F>
PacketHits<F> load_packet_hits(const WaveShadingInput& in, std::size_t first) {
  const Mask<F> active = first_lanes<F>(in.rays->count - first);
  const Ray<F> ray = in.rays->load<F>(first);
  const SurfaceColumns& columns = *in.surfaces;
  PacketHits<F> h;
  h.hit = in.hits->load<F>(first);
  h.hit_mask = active & nonzero_lanes(h.hit.id - IntLanes<F>(kNoHit));
  h.weight = load_vec3<F>(in.paths->weight_r, in.paths->weight_g, in.paths->weight_b, first);
  h.smooth = nonzero_lanes(load_int_lanes<F>(columns.smooth.data() + first));
  h.interpolated = load_vec3<F>(columns.nx, columns.ny, columns.nz, first);
  h.lift = columns.shadow_lift.load<F>(first);
  h.s = surface_frame(ray, h.hit, h.smooth, h.interpolated);
  h.s.error = h.s.error + columns.error.load<F>(first);
  h.color = load_vec3<F>(columns.color_r, columns.color_g, columns.color_b, first);
  h.material = load_int_lanes<F>(columns.material.data() + first);
  h.direction = ray.direction;
  return h;
}

// Each light sample's contribution I_i (kd (N.L) colour + ks (N.H)^n) times
// the path weight, appended with its shadow ray to the sample slot's
// stream where the lit surface faces the light.
template <class F>
void shade_lights(const WaveShadingInput& in, const WaveAppendTargets& to, WaveShadingOutput& out, std::size_t first,
                  const PacketHits<F>& h,
                  const Mask<F>& lit, const F& kd, const F& ks) {
  constexpr int W = lane_count<F>;
  const Scene& scene = *in.scene;
  const SurfaceFrame<F>& s = h.s;
  const F shininess = gather_lanes<F>(in.materials->shininess.data(), h.material);
  const Vec3<F> to_eye = -h.incident;
  std::size_t slot = 0;
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const LightDesc& light = scene.lights[l];
    const int n = samples_per_side(light);
    const Vec3<F> intensity(light.color / float(n * n));
    const bool spot = light.kind == LightDesc::Kind::spot;
    const Vec3<float> spot_axis = spot ? normalize(light.direction) : Vec3<float>{0.f, 0.f, 0.f};
    const bool area = light.is_area();
    // Each lane's numbers for this light, drawn from its path's key.
    std::uint64_t streams[kMaxLanes] = {};
    if (area) {
      for (int k = 0; k < W; ++k) streams[k] = hash_stream(in.paths->key[first + std::size_t(k)] ^ in.seed, l);
    }
    for (int j = 0; j < n * n; ++j, ++slot) {
      float tmax;
      const SampleJitter jitter = area ? sample_jitter<F>(streams, j, n) : SampleJitter{};
      Vec3<F> direction = light_sample_direction(light, jitter, h.origin, tmax);
      const Vec3<F> to_light = normalize(direction);
      const F n_dot_l = dot(s.shading, to_light);
      // Near the terminator the shadow ray leaves from the lifted point (wholly where the face turns
      // from the light, which the ray from there then decides).
      const F share = terminator_lift_share(n_dot_l, dot(s.geometric, to_light));
      const Mask<F> lifted = h.liftable & (n_dot_l > F(0.f)) & (share > F(0.f));
      Vec3<F> from = h.origin;
      if (any(lifted)) {
        from = select(lifted, lifted_origin(s.position, s.error, h.lift * share, s.geometric), h.origin);
        direction = select(lifted, light_sample_direction(light, jitter, from, tmax), direction);
      }
      // No shadow ray where the shading faces away from the light, nor where the face does unless lifted.
      Mask<F> cast = lit & (n_dot_l > F(0.f)) & (lifted | (dot(s.geometric, to_light) > F(0.f)));
      const Vec3<F> half = normalize(to_light + to_eye);
      const F n_dot_h = max(dot(s.shading, half), F(0.f));
      const F specular = select((ks > F(0.f)) & (n_dot_h > F(0.f)), ks * pow_lanes(n_dot_h, shininess), F(0.f));
      // I_i * (kd (N.L) colour + ks (N.H)^n), times the path weight.
      const Vec3<F> reflected = h.color * (kd * n_dot_l) + Vec3<F>(specular, specular, specular);
      Vec3<F> contribution = mul(h.weight, mul(intensity, reflected));
      if (spot) contribution = contribution * spot_light_share(light, spot_axis, to_light);
      // SPD: a shadow ray wherever the surface faces the light, even when it adds nothing.
      if (!in.spawn_every_ray) cast = cast & (max_component(contribution) > F(0.f));
      const unsigned bits = lane_bits(cast);
      out.counts.light_issued += W;
      out.counts.light_active += std::popcount(bits);
      if (bits == 0) continue;
      out.counts.shadow_uncompacted += W;
      append_shadow_rays((*to.slots)[slot], bits, first, from, direction, tmax, contribution);
    }
  }
}

// The reflection and refraction rays a packet casts: their lanes, weights
// and directions (Snell through the shading normal, else through the
// geometric one; total internal reflection folds kt into the reflection).
template <class F>
struct SecondaryRays {
  unsigned reflection_bits = 0, refraction_bits = 0;
  Vec3<F> reflect_weight, refract_weight;
  F eta;
  Mask<F> retry;  // refracted through the geometric normal
  Vec3<F> along_shading, along_geometric, refracted;
};

template <class F>
SecondaryRays<F> secondary_rays(const WaveShadingInput& in, const PacketHits<F>& h) {
  const MaterialTable& table = *in.materials;
  const F kr = gather_lanes<F>(table.kr.data(), h.material);
  const F kt = gather_lanes<F>(table.kt.data(), h.material);
  const F ior = gather_lanes<F>(table.ior.data(), h.material);
  const SurfaceFrame<F>& s = h.s;
  SecondaryRays<F> r;
  r.reflect_weight = h.weight * kr;
  r.refract_weight = mul(h.weight, h.color * kt);
  // Snell through the shading normal, else (bent behind the surface) the geometric one.
  const Mask<F> transmissive = kt > F(0.f);
  r.eta = select(s.entering, F(1.f) / ior, ior);
  Mask<F> through_shading, through_geometric;
  r.along_shading = refract(h.incident, s.shading, r.eta, through_shading);
  r.retry = and_not(through_shading, dot(r.along_shading, s.geometric) < F(0.f));
  r.along_geometric = refract(h.incident, s.geometric, r.eta, through_geometric);
  r.refracted = select(r.retry, r.along_geometric, r.along_shading);
  const Mask<F> transmitted = (r.retry & through_geometric) | and_not(through_shading, r.retry);
  // Total internal reflection: the transmitted share kt is reflected. Like
  // the kr share, it crosses no surface, so the colour (a filter where light
  // refracts through the surface, entering or leaving) does not multiply
  // it: through a tinted prism that folds a ray twice inside, the sky is
  // kt^4 C^2, not kt^4 C^4, as POV-Ray gives it.
  const Mask<F> total_internal = and_not(transmissive, transmitted);
  r.reflect_weight = select(total_internal, r.reflect_weight + h.weight * kt, r.reflect_weight);
  r.refract_weight = select(total_internal, Vec3<F>(F(0.f), F(0.f), F(0.f)), r.refract_weight);
  // Fresnel: of the transmitted share, F is reflected (uncoloured, as above), 1 - F refracted.
  const Mask<F> fresnel = transmissive & transmitted & (gather_lanes<F>(table.fresnel.data(), h.material) > F(0.f));
  if (any(fresnel)) {
    const F reflectance = fresnel_reflectance(h.incident, select(r.retry, s.geometric, s.shading), r.eta);
    r.reflect_weight = select(fresnel, r.reflect_weight + h.weight * (kt * reflectance), r.reflect_weight);
    r.refract_weight = select(fresnel, r.refract_weight * (F(1.f) - reflectance), r.refract_weight);
  }
  // SPD (rules 8 and 9): a reflection ray off every reflective or
  // transmissive hit (a transmitter with Ks 0 too, its weight then 0 unless
  // totally internally reflected) and a refraction ray through every
  // transmissive one, with no weight test.
  const Mask<F> cast_reflection = h.hit_mask & (in.spawn_every_ray ? (kr > F(0.f)) | transmissive
                                                                     : worth_casting(r.reflect_weight, in.min_weight));
  Mask<F> cast_refraction = h.hit_mask & transmissive & transmitted;
  if (!in.spawn_every_ray) cast_refraction = cast_refraction & worth_casting(r.refract_weight, in.min_weight);
  r.reflection_bits = lane_bits(cast_reflection);
  r.refraction_bits = lane_bits(cast_refraction);
  return r;
}

// Appends the packet's secondary rays to the next wave, by lane, a lane's
// reflection before its refraction, with their paths and differentials.
template <class F>
void append_secondary_rays(const WaveShadingInput& in, const WaveAppendTargets& to, WaveShadingOutput& out,
                           std::size_t first,
                           const PacketHits<F>& h, const SecondaryRays<F>& sr) {
  constexpr int W = lane_count<F>;
  const SurfaceFrame<F>& s = h.s;
  const unsigned reflection_bits = sr.reflection_bits, refraction_bits = sr.refraction_bits;
  const Vec3<F> mirrored = reflect(h.incident, s.shading);
  const Mask<F> mirrored_outward = dot(mirrored, s.geometric) > F(0.f);
  const Vec3<F> reflected = select(mirrored_outward, mirrored, reflect(h.incident, s.geometric));
  if (reflection_bits != 0) out.counts.next_uncompacted += W;
  if (refraction_bits != 0) out.counts.next_uncompacted += W;
  out.counts.reflection += std::popcount(reflection_bits);
  out.counts.refraction += std::popcount(refraction_bits);
  // Appended by lane, a lane's reflection before its refraction.
  const Vec3Lanes<F> outside(h.origin), inside(offset_origin(s.position, s.error, -s.geometric));
  const Vec3Lanes<F> reflected_lanes(reflected), refracted_lanes(sr.refracted);
  const Vec3Lanes<F> reflect_weights(sr.reflect_weight), refract_weights(sr.refract_weight);
  RaySoA& r = *to.next_rays;
  PathColumns& p = *to.next_paths;
  std::size_t i = grow_spawned(std::size_t(std::popcount(reflection_bits) + std::popcount(refraction_bits)), r, p,
                               to.next_differentials);
  std::optional<SpawnedDifferentials<F>> spawned;
  if (in.differentials != nullptr) {
    spawned = spawned_differentials(in, first, s, select(h.smooth, h.interpolated, h.hit.ng), h.incident,
                                    mirrored_outward, sr.eta, sr.retry, sr.along_shading, sr.along_geometric);
  }
  DifferentialColumns* const next_differentials = to.next_differentials;
  auto append = [&](std::size_t parent, int k, const Vec3Lanes<F>& from, const Vec3Lanes<F>& direction,
                    const Vec3Lanes<F>& weights, std::uint64_t tag, const Vec3Lanes<F>* direction_dx,
                    const Vec3Lanes<F>* direction_dy) {
    set_ray(r, i, from, direction, k, kInfinity);
    p.sample[i] = in.paths->sample[parent];
    set_vec3(p.weight_r, p.weight_g, p.weight_b, i, weights.x, weights.y, weights.z, k);
    p.key[i] = mix64(in.paths->key[parent] ^ tag);
    if (spawned) {
      DifferentialColumns& d = *next_differentials;
      const Vec3Lanes<F>& point_dx = spawned->point_dx;
      const Vec3Lanes<F>& point_dy = spawned->point_dy;
      set_vec3(d.origin_dx.x, d.origin_dx.y, d.origin_dx.z, i, point_dx.x, point_dx.y, point_dx.z, k);
      set_vec3(d.origin_dy.x, d.origin_dy.y, d.origin_dy.z, i, point_dy.x, point_dy.y, point_dy.z, k);
      set_vec3(d.direction_dx.x, d.direction_dx.y, d.direction_dx.z, i, direction_dx->x, direction_dx->y,
               direction_dx->z, k);
      set_vec3(d.direction_dy.x, d.direction_dy.y, d.direction_dy.z, i, direction_dy->x, direction_dy->y,
               direction_dy->z, k);
      d.centre_x[i] = in.differentials->centre_x[parent];
      d.centre_y[i] = in.differentials->centre_y[parent];
    }
    ++i;
  };
  for (unsigned bits = reflection_bits | refraction_bits; bits != 0; bits &= bits - 1) {
    const int k = std::countr_zero(bits);
    const std::size_t parent = first + std::size_t(k);
    if ((reflection_bits >> k & 1u) != 0) {
      append(parent, k, outside, reflected_lanes, reflect_weights, kReflectionTag,
             spawned ? &spawned->reflected_dx : nullptr, spawned ? &spawned->reflected_dy : nullptr);
    }
    if ((refraction_bits >> k & 1u) != 0) {
      append(parent, k, inside, refracted_lanes, refract_weights, kRefractionTag,
             spawned ? &spawned->refracted_dx : nullptr, spawned ? &spawned->refracted_dy : nullptr);
    }
  }
}

template <class F>
void shade_packet(const WaveShadingInput& in, const WaveAppendTargets& to, WaveShadingOutput& out, std::size_t first) {
  const Scene& scene = *in.scene;
  const MaterialTable& table = *in.materials;
  PacketHits<F> h = load_packet_hits<F>(in, first);
  out.counts.hits += std::popcount(lane_bits(h.hit_mask));

  // Ambient ka Ia colour where a surface is hit; on a miss, what the ray sees (the background or an area light).
  const F ka = gather_lanes<F>(table.ka.data(), h.material);
  const Vec3<F> ambient = mul(h.weight, mul(Vec3<F>(scene.ambient), h.color) * ka);
  const SurfaceColumns& columns = *in.surfaces;
  const Vec3<F> seen = columns.seen.x.empty() ? Vec3<F>(scene.background)
                                              : columns.seen.load<F>(first);
  const Vec3<F> emitted = select(h.hit_mask, ambient, mul(h.weight, seen));
  store_lanes(emitted.x, out.emitted_r.data() + first);
  store_lanes(emitted.y, out.emitted_g.data() + first);
  store_lanes(emitted.z, out.emitted_b.data() + first);
  if (none(h.hit_mask)) return;
  h.incident = normalize(h.direction);
  h.origin = offset_origin(h.s.position, h.s.error, h.s.geometric);
  // A lift toward the side the ray came from moves the shadow rays' start; one the other way (a smooth
  // surface seen from behind) does not.
  h.liftable = h.hit_mask & h.smooth & (dot(h.lift, h.s.geometric) > F(0.f));

  const F kd = gather_lanes<F>(table.kd.data(), h.material);
  const F ks = gather_lanes<F>(table.ks.data(), h.material);
  // A one-sided surface seen from behind gets the ambient term only.
  const Mask<F> two_sided = gather_lanes<F>(table.two_sided.data(), h.material) > F(0.f);
  const Mask<F> lit = h.hit_mask & (two_sided | h.s.entering) & ((kd > F(0.f)) | (ks > F(0.f)));
  if (any(lit)) shade_lights(in, to, out, first, h, lit, kd, ks);
  if (!in.spawn) return;
  const SecondaryRays<F> secondary = secondary_rays(in, h);
  if ((secondary.reflection_bits | secondary.refraction_bits) == 0) return;
  append_secondary_rays(in, to, out, first, h, secondary);
}

}  // namespace

}  // namespace QUIVER_UNIT_NAMESPACE

template <KernelUnit U>
void shade_wave(const WaveShadingInput& in, const WaveAppendTargets& to, WaveShadingOutput& out) {
  using F = UnitLanes<U>;
  const std::size_t padded = in.rays->ox.size();
  out.emitted_r.resize(padded);
  out.emitted_g.resize(padded);
  out.emitted_b.resize(padded);
  for (std::size_t first = 0; first < in.rays->count; first += std::size_t(lane_count<F>)) {
    shade_packet<F>(in, to, out, first);
  }
}

template void shade_wave<kThisUnit>(const WaveShadingInput&, const WaveAppendTargets&, WaveShadingOutput&);

}  // namespace quiver
