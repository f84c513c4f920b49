// Primary rays in lanes (the contract: camera_rays.h). Compiled once per
// kernel unit; D is the unit's double lane type.
#include "integrator/camera_rays.h"

#include <algorithm>
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

}  // namespace

}  // namespace QUIVER_UNIT_NAMESPACE

template <KernelUnit U>
void camera_rays(const Camera& camera, std::span<const double> x, std::span<const double> y, RaySoA& rays) {
  using D = typename DoubleLanesOf<UnitLanes<U>>::type;
  constexpr std::size_t kWidth = width_of<D>();
  const std::size_t n = x.size();
  rays.resize(n);
  const Vec3<float> eye = camera.eye();
  std::fill_n(rays.ox.begin(), n, eye.x);
  std::fill_n(rays.oy.begin(), n, eye.y);
  std::fill_n(rays.oz.begin(), n, eye.z);
  std::fill_n(rays.tmin.begin(), n, 0.f);
  std::fill_n(rays.tmax.begin(), n, std::numeric_limits<float>::infinity());
  for (std::size_t first = 0; first < n; first += kWidth) {
    const std::size_t lanes = std::min(kWidth, n - first);
    // A partial packet: copies of its last point in the lanes past the end.
    double px[kWidth], py[kWidth];
    for (std::size_t k = 0; k < kWidth; ++k) {
      px[k] = x[first + std::min(k, lanes - 1)];
      py[k] = y[first + std::min(k, lanes - 1)];
    }
    const Vec3<D> d = unit_direction(camera, load_doubles<D>(px), load_doubles<D>(py));
    double dx[kWidth], dy[kWidth], dz[kWidth];
    store_doubles(d.x, dx);
    store_doubles(d.y, dy);
    store_doubles(d.z, dz);
    // Rounded to float, as Camera::ray.
    for (std::size_t k = 0; k < lanes; ++k) {
      rays.dx[first + k] = float(dx[k]);
      rays.dy[first + k] = float(dy[k]);
      rays.dz[first + k] = float(dz[k]);
    }
  }
  rays.pad();
}

template void camera_rays<kThisUnit>(const Camera&, std::span<const double>, std::span<const double>, RaySoA&);

}  // namespace quiver
