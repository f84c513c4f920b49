#include "integrator/wave.h"

namespace quiver {

void Vec3Columns::clear() {
  for (AlignedFloats* c : columns()) c->clear();
}

void Vec3Columns::push(const Vec3<float>& v) {
  x.push_back(v.x);
  y.push_back(v.y);
  z.push_back(v.z);
}

void Vec3Columns::pad(std::size_t count) {
  for (AlignedFloats* c : columns()) pad_column(*c, count);
}

void Vec3Columns::assign(std::size_t padded) {
  for (AlignedFloats* c : columns()) c->assign(padded, 0.f);
}

void Vec3Columns::set(std::size_t i, const Vec3<float>& v) {
  x[i] = v.x;
  y[i] = v.y;
  z[i] = v.z;
}

void DifferentialColumns::clear() {
  for (Vec3Columns* c : vectors()) c->clear();
  for (AlignedFloats* c : centres()) c->clear();
}

void DifferentialColumns::pad(std::size_t count) {
  for (Vec3Columns* c : vectors()) c->pad(count);
  for (AlignedFloats* c : centres()) pad_column(*c, count);
}

void DifferentialColumns::resize(std::size_t size) {
  for (Vec3Columns* v : vectors()) {
    for (AlignedFloats* c : v->columns()) c->resize(size);
  }
  for (AlignedFloats* c : centres()) c->resize(size);
}

void PathColumns::clear() {
  for (AlignedFloats* c : weights()) c->clear();
  sample.clear();
  key.clear();
  count = 0;
}

void PathColumns::push(std::uint32_t sample_index, const Vec3<float>& weight, std::uint64_t path_key) {
  sample.push_back(static_cast<std::int32_t>(sample_index));
  weight_r.push_back(weight.x);
  weight_g.push_back(weight.y);
  weight_b.push_back(weight.z);
  key.push_back(path_key);
  ++count;
}

void PathColumns::start_at_camera(std::size_t n) {
  sample.resize(n);
  for (std::size_t i = 0; i < n; ++i) sample[i] = static_cast<std::int32_t>(i);
  for (AlignedFloats* c : weights()) c->assign(n, 1.f);
  key.resize(n);
  count = n;
}

void PathColumns::pad() {
  for (AlignedFloats* c : weights()) pad_column(*c, count);
  pad_column(sample, count);
  key.resize(padded_size(count), count > 0 ? key[count - 1] : 0);
}

void SurfaceColumns::resize(std::size_t padded, bool differentials) {
  for (AlignedInts* c : {&material, &smooth}) c->assign(padded, 0);
  for (AlignedFloats* c : {&nx, &ny, &nz, &color_r, &color_g, &color_b}) c->assign(padded, 0.f);
  error.assign(padded);
  shadow_lift.assign(padded);
  for (Vec3Columns* c : {&point_dx, &point_dy, &normal_dx, &normal_dy}) {
    if (differentials) {
      c->assign(padded);
    } else {
      c->clear();
    }
  }
}

MaterialTable::MaterialTable(const std::vector<MaterialDesc>& scene_materials) {
  // One material at least: misses and padding lanes gather entry 0.
  const std::vector<MaterialDesc> materials = scene_materials.empty() ? std::vector<MaterialDesc>(1) : scene_materials;
  for (const MaterialDesc& m : materials) {
    ka.push_back(m.ka);
    kd.push_back(m.kd);
    ks.push_back(m.ks);
    shininess.push_back(m.shininess);
    kr.push_back(m.kr);
    kt.push_back(m.kt);
    ior.push_back(m.ior);
    two_sided.push_back(m.two_sided ? 1.f : 0.f);
    fresnel.push_back(m.fresnel ? 1.f : 0.f);
  }
  for (AlignedFloats* c : {&ka, &kd, &ks, &shininess, &kr, &kt, &ior, &two_sided, &fresnel}) {
    pad_column(*c, materials.size());
  }
}

void ShadowSlot::open(std::size_t capacity) {
  for (AlignedFloats* c : rays.columns()) c->resize(capacity);
  for (AlignedFloats* c : {&light_r, &light_g, &light_b}) c->resize(capacity);
  point.resize(capacity);
  rays.count = 0;
}

namespace {

void grow_rays(RaySoA& rays, std::size_t size) {
  for (AlignedFloats* c : rays.columns()) c->resize(size);
  rays.count = size;
}

}  // namespace

std::size_t grow_spawned(std::size_t n, RaySoA& rays, PathColumns& paths, DifferentialColumns* differentials) {
  const std::size_t first = rays.ox.size(), size = first + n;
  grow_rays(rays, size);
  for (AlignedFloats* c : paths.weights()) c->resize(size);
  paths.sample.resize(size);
  paths.key.resize(size);
  paths.count = size;
  if (differentials != nullptr) differentials->resize(size);
  return first;
}

int samples_per_side(const LightDesc& light) {
  return light.is_area() ? light.samples : 1;
}

}  // namespace quiver
