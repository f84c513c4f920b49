#include "integrator/wave.h"

namespace quiver {

void PathColumns::clear() {
  for (AlignedFloats* c : {&weight_r, &weight_g, &weight_b}) c->clear();
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

void PathColumns::pad() {
  for (AlignedFloats* c : {&weight_r, &weight_g, &weight_b}) pad_column(*c, count);
  pad_column(sample, count);
  key.resize(padded_size(count), count > 0 ? key[count - 1] : 0);
}

void SurfaceColumns::resize(std::size_t padded) {
  for (AlignedInts* c : {&material, &smooth}) c->assign(padded, 0);
  for (AlignedFloats* c : {&nx, &ny, &nz, &color_r, &color_g, &color_b}) c->assign(padded, 0.f);
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
  }
  for (AlignedFloats* c : {&ka, &kd, &ks, &shininess, &kr, &kt, &ior, &two_sided}) pad_column(*c, materials.size());
}

void ShadowSlot::clear() {
  rays.clear();
  point.clear();
  for (AlignedFloats* c : {&light_r, &light_g, &light_b}) c->clear();
}

int samples_per_side(const LightDesc& light) {
  const bool area = light.kind == LightDesc::Kind::rectangle || light.kind == LightDesc::Kind::sphere;
  return area ? light.samples : 1;
}

}  // namespace quiver
