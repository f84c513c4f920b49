#include "geometry/soa.h"

#include <algorithm>

namespace quiver {

namespace {
template <class Column>
void pad_any(Column& column, std::size_t count) {
  column.resize(padded_size(count));
  if (count == 0) return;
  std::fill(column.begin() + static_cast<std::ptrdiff_t>(count), column.end(), column[count - 1]);
}
}  // namespace

void pad_column(AlignedFloats& column, std::size_t count) { pad_any(column, count); }
void pad_column(AlignedInts& column, std::size_t count) { pad_any(column, count); }

RaySoA::RaySoA(std::size_t n) : count(n) {
  for (AlignedFloats* c : columns()) c->assign(padded_size(n), 0.f);
}

void RaySoA::set(std::size_t i, const Ray<float>& ray) {
  ox[i] = ray.origin.x;
  oy[i] = ray.origin.y;
  oz[i] = ray.origin.z;
  dx[i] = ray.direction.x;
  dy[i] = ray.direction.y;
  dz[i] = ray.direction.z;
  tmin[i] = ray.tmin;
  tmax[i] = ray.tmax;
}

void RaySoA::clear() {
  for (AlignedFloats* c : columns()) c->clear();
  count = 0;
}

void RaySoA::push(const Ray<float>& ray) {
  ox.push_back(ray.origin.x);
  oy.push_back(ray.origin.y);
  oz.push_back(ray.origin.z);
  dx.push_back(ray.direction.x);
  dy.push_back(ray.direction.y);
  dz.push_back(ray.direction.z);
  tmin.push_back(ray.tmin);
  tmax.push_back(ray.tmax);
  ++count;
}

void RaySoA::resize(std::size_t n) {
  for (AlignedFloats* c : columns()) c->resize(padded_size(n));
  count = n;
}

Ray<float> RaySoA::get(std::size_t i) const {
  return {{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, tmin[i], tmax[i]};
}

void RaySoA::pad() {
  for (AlignedFloats* c : columns()) pad_column(*c, count);
}

HitSoA::HitSoA(const RaySoA& rays) { reset(rays); }

void HitSoA::reset(const RaySoA& rays) {
  t.assign(rays.tmax.begin(), rays.tmax.end());
  count = rays.count;
  for (AlignedFloats* c : {&u, &v, &ngx, &ngy, &ngz}) c->assign(t.size(), 0.f);
  id.assign(t.size(), kNoHit);
}

Hit<float> HitSoA::get(std::size_t i) const { return column_hit(*this, i); }

void HitSoA::set(std::size_t i, const Hit<float>& hit) { set_column_hit(*this, i, hit); }

std::size_t HitSoA::hit_count() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < count; ++i) n += id[i] != kNoHit;
  return n;
}

OcclusionSoA::OcclusionSoA(const RaySoA& rays) { reset(rays); }

void OcclusionSoA::reset(const RaySoA& rays) {
  occluded.assign(padded_size(rays.count), 0);
  count = rays.count;
}

}  // namespace quiver
