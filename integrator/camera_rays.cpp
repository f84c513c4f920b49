// Primary rays in lanes (the contract: camera_rays.h). Compiled once per
// kernel unit; D is the unit's double lane type.
#include "integrator/camera_rays.h"

#include <algorithm>
#include <array>
#include <limits>
#include <type_traits>

#include "simd/lanes.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

namespace {

// The unit's float lanes -> its double lanes (the same registers, half the lanes).
template <class F>
struct DoubleLanesOf {
  using type = double;
};
template <class A>
struct DoubleLanesOf<xsimd::batch<float, A>> {
  using type = xsimd::batch<double, A>;
};

template <class D>
constexpr std::size_t width_of() {
  if constexpr (std::is_same_v<D, double>) {
    return 1;
  } else {
    return D::size;
  }
}

template <class D>
D load_doubles(const double* p) {
  if constexpr (std::is_same_v<D, double>) {
    return *p;
  } else {
    return D::load_unaligned(p);
  }
}

template <class D>
void store_doubles(const D& v, double* p) {
  if constexpr (std::is_same_v<D, double>) {
    *p = v;
  } else {
    v.store_unaligned(p);
  }
}

// Calls packet(lanes, first, lanes of each column...) for each packet of
// n points given by equally long columns: a column's lanes loaded from
// [first, first + lanes), a partial packet's lanes past the end copies of
// its last point.
template <class D, class Packet, class... Columns>
void for_each_packet(std::size_t n, Packet&& packet, const Columns&... columns) {
  constexpr std::size_t kWidth = width_of<D>();
  for (std::size_t first = 0; first < n; first += kWidth) {
    const std::size_t lanes = std::min(kWidth, n - first);
    const auto load = [&](std::span<const double> column) {
      double v[kWidth];
      for (std::size_t k = 0; k < kWidth; ++k) v[k] = column[first + std::min(k, lanes - 1)];
      return load_doubles<D>(v);
    };
    packet(lanes, first, load(columns)...);
  }
}

// Stores v's first `lanes` lanes, rounded to float, from x, y and z on.
template <class D>
void store_rounded(const Vec3<D>& v, std::size_t lanes, float* x, float* y, float* z) {
  constexpr std::size_t kWidth = width_of<D>();
  double vx[kWidth], vy[kWidth], vz[kWidth];
  store_doubles(v.x, vx);
  store_doubles(v.y, vy);
  store_doubles(v.z, vz);
  for (std::size_t k = 0; k < lanes; ++k) {
    x[k] = float(vx[k]);
    y[k] = float(vy[k]);
    z[k] = float(vz[k]);
  }
}

}  // namespace

}  // namespace QUIVER_UNIT_NAMESPACE

template <KernelUnit U>
void camera_rays(const Camera& camera, std::span<const double> x, std::span<const double> y, RaySoA& rays) {
  using D = typename DoubleLanesOf<UnitLanes<U>>::type;
  const std::size_t n = x.size();
  rays.resize(n);
  const Vec3<float> eye = camera.eye();
  std::fill_n(rays.ox.begin(), n, eye.x);
  std::fill_n(rays.oy.begin(), n, eye.y);
  std::fill_n(rays.oz.begin(), n, eye.z);
  std::fill_n(rays.tmin.begin(), n, 0.f);
  std::fill_n(rays.tmax.begin(), n, std::numeric_limits<float>::infinity());
  for_each_packet<D>(
      n,
      [&](std::size_t lanes, std::size_t first, const D& px, const D& py) {
        // Rounded to float, as Camera::ray.
        store_rounded(unit_direction(camera, px, py), lanes, &rays.dx[first], &rays.dy[first], &rays.dz[first]);
      },
      x, y);
  rays.pad();
}

template void camera_rays<kThisUnit>(const Camera&, std::span<const double>, std::span<const double>, RaySoA&);

template <KernelUnit U>
void camera_direction_changes(const Camera& camera, std::span<const double> x, std::span<const double> y,
                              std::span<const double> spacing, Vec3Columns& along_x, Vec3Columns& along_y) {
  using D = typename DoubleLanesOf<UnitLanes<U>>::type;
  const std::size_t n = x.size();
  for (Vec3Columns* v : {&along_x, &along_y}) {
    for (AlignedFloats* c : v->columns()) c->resize(n);
  }
  for_each_packet<D>(
      n,
      [&](std::size_t lanes, std::size_t first, const D& px, const D& py, const D& side) {
        const std::array<Vec3<D>, 2> change = unit_direction_changes(camera, px, py, side);
        store_rounded(change[0], lanes, &along_x.x[first], &along_x.y[first], &along_x.z[first]);
        store_rounded(change[1], lanes, &along_y.x[first], &along_y.y[first], &along_y.z[first]);
      },
      x, y, spacing);
}

template void camera_direction_changes<kThisUnit>(const Camera&, std::span<const double>, std::span<const double>,
                                                  std::span<const double>, Vec3Columns&, Vec3Columns&);

}  // namespace quiver
