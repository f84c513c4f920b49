#include "scene/auto_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "scene/camera_frame.h"

namespace quiver {

namespace {

// Minimum and maximum that order -0 below +0: the same bits whatever the
// order of the values (std::min and std::max keep the first of equals), so
// that a fold split over threads gives a sequential fold's result.
double least(double a, double b) { return b < a || (b == a && std::signbit(b)) ? b : a; }
double greatest(double a, double b) { return a < b || (a == b && !std::signbit(b)) ? b : a; }

// Ranges [lo, hi] of values along N axes (lo > hi: none yet), grown with
// least and greatest.
template <std::size_t N>
struct Ranges {
  std::array<double, N> lo, hi;
  Ranges() {
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
  }
  void include(std::size_t k, double low, double high) {
    lo[k] = least(lo[k], low);
    hi[k] = greatest(hi[k], high);
  }
};

// a's ranges grown by b's: a fold's join (Ranges or a type built on them).
template <class R>
R joined(R a, const R& b) {
  for (std::size_t k = 0; k < a.lo.size(); ++k) a.include(k, b.lo[k], b.hi[k]);
  return a;
}

// Axis-aligned bounds in double of the points fed to it (finite ones only).
struct Bounds : Ranges<3> {
  void add(const Vec3<float>& p, double margin = 0.0) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(margin)) return;
    for (int a = 0; a < 3; ++a) include(std::size_t(a), double(p[a]) - margin, double(p[a]) + margin);
  }
  bool empty() const { return lo[0] > hi[0]; }
};

Vec3<float> to_float(const Vec3<double>& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

// Corner `bits` of a box (bit k: the high side along axis k).
Vec3<double> box_corner(const Bounds& box, int bits) {
  return {bits & 1 ? box.hi[0] : box.lo[0], bits & 2 ? box.hi[1] : box.lo[1], bits & 4 ? box.hi[2] : box.lo[2]};
}

// Balls that together cover every bounded primitive: each kind's extent,
// and the corners of each instance's placed mesh box (the meshes' boxes
// found once, as the default camera visits the balls several times).
class ExtentBalls {
 public:
  static constexpr std::size_t kEntriesPerTask = 4096;
  // Triangles per block with a box of its own: small, so that a block of a
  // mesh stored ring by ring still spans a small part of it.
  static constexpr std::size_t kTrianglesPerBox = 256;

  explicit ExtentBalls(const SceneDesc& scene)
      : scene_(scene),
        mesh_bounds_(scene.meshes.size()),
        triangle_blocks_((scene.triangles.size() + kTrianglesPerBox - 1) / kTrianglesPerBox) {
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      for (const SceneTriangle& t : scene.meshes[m].triangles) {
        for (const Vec3<float>& p : t.triangle.p) mesh_bounds_[m].add(p);
      }
    }
    tbb::parallel_for(std::size_t{0}, triangle_blocks_.size(), [&](std::size_t b) {
      for (std::size_t i = b * kTrianglesPerBox; i < block_end(b); ++i) {
        for (const Vec3<float>& p : scene.triangles[i].triangle.p) triangle_blocks_[b].add(p);
      }
    });
  }

  // Folds every ball (fold(state, p, margin)) into a state that starts as
  // `none`, each kind's entries in parallel blocks joined by combine: for
  // minima and maxima only, whose bits do not depend on the order or the
  // thread count. A block of triangles whose box settled(state, box) says
  // no point inside could change the state is passed over: a sample of the
  // blocks (every kSampleStride-th) is folded first, and the state it gives
  // judges the others; the result is the whole fold's for a `settled` that
  // holds only where that is certain.
  template <class State, class Fold, class Combine, class Settled>
  State reduce_pruned(const State& none, const Fold& fold, const Combine& combine, const Settled& settled) const {
    constexpr std::size_t kSampleStride = 16;
    const auto fold_blocks = [&](bool sample, const State& judge) {
      return tbb::parallel_reduce(
          tbb::blocked_range<std::size_t>(0, triangle_blocks_.size()), none,
          [&](const tbb::blocked_range<std::size_t>& range, State state) {
            const auto add = [&](const Vec3<float>& p, double margin) { fold(state, p, margin); };
            for (std::size_t b = range.begin(); b != range.end(); ++b) {
              if ((b % kSampleStride == 0) != sample || (!sample && settled(judge, triangle_blocks_[b]))) continue;
              for (std::size_t i = b * kTrianglesPerBox; i < block_end(b); ++i) {
                TriangleKind::extent(scene_.triangles[i].triangle, add);
              }
            }
            return state;
          },
          combine);
    };
    const State sampled = combine(reduce_others(none, fold, combine), fold_blocks(true, none));
    return combine(sampled, fold_blocks(false, sampled));
  }

  // The box of every ball; the triangles' from their blocks' boxes.
  Bounds bounds() const {
    Bounds b = reduce_others(Bounds{}, [](Bounds& s, const Vec3<float>& p, double margin) { s.add(p, margin); },
                             joined<Bounds>);
    for (const Bounds& block : triangle_blocks_) b = joined(b, block);
    return b;
  }

 private:
  // One past the last triangle of block b.
  std::size_t block_end(std::size_t b) const { return std::min((b + 1) * kTrianglesPerBox, scene_.triangles.size()); }

  // reduce over every kind but triangles, and the instances' placed boxes.
  template <class State, class Fold, class Combine>
  State reduce_others(const State& none, const Fold& fold, const Combine& combine) const {
    State total = none;
    for_each_kind([&]<class K>(K) {
      if constexpr (!std::is_same_v<K, TriangleKind>) {
        const auto& entries = scene_.*SceneEntries<K>::of;
        const auto fold_block = [&](const tbb::blocked_range<std::size_t>& block, State state) {
          const auto add = [&](const Vec3<float>& p, double margin) { fold(state, p, margin); };
          for (std::size_t i = block.begin(); i != block.end(); ++i) K::extent(entries[i].*SceneEntries<K>::desc, add);
          return state;
        };
        total = combine(total, tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, entries.size(), kEntriesPerTask),
                                                    none, fold_block, combine));
      }
    });
    for (const SceneInstance& instance : scene_.instances) {
      if (instance.mesh >= mesh_bounds_.size() || mesh_bounds_[instance.mesh].empty()) continue;
      const Bounds& m = mesh_bounds_[instance.mesh];
      for (int corner = 0; corner < 8; ++corner) {
        fold(total, apply_point(instance.object_to_world, to_float(box_corner(m, corner))), 0.0);
      }
    }
    return total;
  }

  const SceneDesc& scene_;
  std::vector<Bounds> mesh_bounds_;
  std::vector<Bounds> triangle_blocks_;  // the box of each block of kTrianglesPerBox triangles
};

Vec3<double> to_double(const Vec3<float>& v) { return {double(v.x), double(v.y), double(v.z)}; }

Vec3<double> unit(const Vec3<double>& v) { return v * (1.0 / std::sqrt(dot(v, v))); }

// A triangle's corners in double and its normal scaled by twice its area.
struct TriangleArea {
  Vec3<double> a, b, c, n;
  explicit TriangleArea(const SceneTriangle& t)
      : a(to_double(t.triangle.p[0])), b(to_double(t.triangle.p[1])), c(to_double(t.triangle.p[2])),
        n(cross(b - a, c - a)) {}
  double twice_area() const { return std::sqrt(dot(n, n)); }
};

// Folds the scene's triangles (fold(state, triangle)) in fixed blocks on
// every thread, the blocks' states joined in a fixed tree: the same sums,
// to the bit, for every thread count.
template <class State, class Fold, class Join>
State fold_triangles(const SceneDesc& scene, const State& none, const Fold& fold, const Join& join) {
  constexpr std::size_t kTrianglesPerBlock = 4096;
  const auto fold_block = [&](const tbb::blocked_range<std::size_t>& block, State state) {
    for (std::size_t i = block.begin(); i != block.end(); ++i) fold(state, scene.triangles[i]);
    return state;
  };
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, scene.triangles.size(), kTrianglesPerBlock), none, fold_block, join);
}

// The faces' area in total, and on a flat base facing -axis at the box's
// lowest side along each axis (y and z), for the triangles of a mesh.
struct MeshAreas {
  double total = 0.0;
  std::array<double, 3> base{};
};

MeshAreas mesh_areas(const SceneDesc& scene, const Bounds& bounds) {
  const double flat = std::cos(2.0 * std::numbers::pi / 180.0);
  std::array<double, 3> tolerance{};
  for (const int axis : {1, 2}) tolerance[axis] = 0.01 * (bounds.hi[axis] - bounds.lo[axis]);
  const auto fold = [&](MeshAreas& areas, const SceneTriangle& t) {
    const TriangleArea f(t);
    const double twice_area = f.twice_area();
    areas.total += 0.5 * twice_area;
    for (const int axis : {1, 2}) {
      bool low = true;
      for (const Vec3<double>& p : {f.a, f.b, f.c}) low = low && p[axis] - bounds.lo[axis] <= tolerance[axis];
      if (low && twice_area > 0.0 && std::fabs(f.n[axis]) >= flat * twice_area) areas.base[axis] += 0.5 * twice_area;
    }
  };
  const auto join = [](MeshAreas a, const MeshAreas& b) {
    a.total += b.total;
    for (const int axis : {1, 2}) a.base[axis] += b.base[axis];
    return a;
  };
  return fold_triangles(scene, MeshAreas{}, fold, join);
}

// The mesh's top (vertices in the upper two fifths along up, each weighted by
// a third of its faces' areas) less its area-weighted centre, over the half
// extent of the vertices along each of the two axes across up.
std::pair<double, double> top_lean(const SceneDesc& scene, const Vec3<double>& up, const Vec3<double>& front,
                                   const Vec3<double>& side) {
  // The vertices' range along up, front and side.
  const auto extend = [&](Ranges<3>& range, const SceneTriangle& t) {
    for (const Vec3<float>& p : t.triangle.p) {
      const Vec3<double> q = to_double(p);
      const double along[3] = {dot(q, up), dot(q, front), dot(q, side)};
      for (std::size_t k = 0; k < 3; ++k) range.include(k, along[k], along[k]);
    }
  };
  const Ranges<3> range = fold_triangles(scene, Ranges<3>{}, extend, joined<Ranges<3>>);
  const double top_from = range.lo[0] + 0.6 * (range.hi[0] - range.lo[0]);
  struct Weighted {
    Vec3<double> centre{0.0, 0.0, 0.0}, top{0.0, 0.0, 0.0};
    double weight = 0.0, top_weight = 0.0;
  };
  const auto weigh = [&](Weighted& w, const SceneTriangle& t) {
    const TriangleArea f(t);
    const double share = f.twice_area() / 6.0;  // a third of the area to each corner
    for (const Vec3<double>& p : {f.a, f.b, f.c}) {
      w.centre = w.centre + p * share;
      w.weight += share;
      if (dot(p, up) >= top_from) {
        w.top = w.top + p * share;
        w.top_weight += share;
      }
    }
  };
  const auto join = [](Weighted a, const Weighted& b) {
    a.centre = a.centre + b.centre;
    a.top = a.top + b.top;
    a.weight += b.weight;
    a.top_weight += b.top_weight;
    return a;
  };
  const Weighted w = fold_triangles(scene, Weighted{}, weigh, join);
  if (!(w.weight > 0.0) || !(w.top_weight > 0.0)) return {0.0, 0.0};
  const Vec3<double> lean = w.top * (1.0 / w.top_weight) - w.centre * (1.0 / w.weight);
  const auto share = [&](double d, std::size_t k) {
    const double half = 0.5 * (range.hi[k] - range.lo[k]);
    return half > 0.0 ? d / half : 0.0;
  };
  return {share(dot(lean, front), 1), share(dot(lean, side), 2)};
}

std::string axis_name(const Vec3<double>& v) {
  for (int a = 0; a < 3; ++a) {
    if (std::fabs(v[a]) == 1.0) return {v[a] > 0.0 ? '+' : '-', "xyz"[a]};
  }
  std::ostringstream text;
  text << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return text.str();
}

}  // namespace

namespace {

// choose_default_view, with the bounds of the scene's balls when they are
// known already (else found here, if needed).
DefaultView choose_view(const SceneDesc& scene, const std::optional<Vec3<double>>& up, const Bounds* known_bounds) {
  const Vec3<double> y{0.0, 1.0, 0.0}, z{0.0, 0.0, 1.0};
  bool only_triangles = true;
  for_each_kind([&]<class K>(K) {
    if constexpr (!std::is_same_v<K, TriangleKind>) only_triangles = only_triangles && (scene.*SceneEntries<K>::of).empty();
  });
  const bool mesh = scene.triangles.size() >= kViewMeshTriangles && only_triangles;
  DefaultView view{y, z, "+y, the default", "+z, the default"};
  if (up) {
    view.up = unit(*up);
    view.up_reason = axis_name(view.up) + ", from --up";
  } else if (scene.model_up && dot(to_double(scene.model_up->axis), to_double(scene.model_up->axis)) > 0.0) {
    view.up = unit(to_double(scene.model_up->axis));
    view.up_reason = axis_name(view.up) + ", " + scene.model_up->convention;
  } else if (mesh) {
    const MeshAreas areas = mesh_areas(scene, known_bounds != nullptr ? *known_bounds : ExtentBalls(scene).bounds());
    const double least = 0.02 * areas.total;
    if (areas.base[2] >= least && areas.base[1] < least) {
      view.up = z;
      view.up_reason = "+z: the mesh stands on a flat base at its lowest z";
    }
  }
  // The default front across up: +z, or -y for an up along z.
  const Vec3<double> toward = std::fabs(dot(view.up, z)) < 0.9 ? z : Vec3<double>{0.0, -1.0, 0.0};
  view.front = unit(toward - view.up * dot(toward, view.up));
  view.front_reason = axis_name(view.front) + ", the default";
  if (mesh) {
    const Vec3<double> side = cross(view.up, view.front);
    const auto [along_front, along_side] = top_lean(scene, view.up, view.front, side);
    const bool front_axis = std::fabs(along_front) >= std::fabs(along_side);
    const double lean = front_axis ? along_front : along_side;
    if (std::fabs(lean) >= kViewLean) {
      view.front = (front_axis ? view.front : side) * (lean > 0.0 ? 1.0 : -1.0);
      view.front_reason = axis_name(view.front) + ": the mesh's top leans that way";
    }
  }
  return view;
}

}  // namespace

DefaultView choose_default_view(const SceneDesc& scene, const std::optional<Vec3<double>>& up) {
  return choose_view(scene, up, nullptr);
}

namespace {

// The default eye and the light beside it lie up to about 2.5 view
// distances from the centre: both must stay finite in float, or the error
// names the scene's file.
void check_camera_fits_float(const SceneDesc& scene, const Vec3<double>& center, double distance) {
  if (distance * 2.5 + std::sqrt(dot(center, center)) < double(std::numeric_limits<float>::max())) return;
  const std::string name = scene.source_files.empty() ? std::string("the scene") : scene.source_files.front();
  std::ostringstream size;
  size << std::setprecision(3) << distance;
  throw std::invalid_argument(name + ": expected a model that a default view can frame, found one needing a camera " +
                              size.str() + " away, too far for float; give the scene a camera, or scale it");
}

// A view direction and the image's half-extents, as tangents of the angles
// from the view axis to the outermost pixel centres across and up.
struct ViewAxes {
  Vec3<double> toward_eye, right, up;
  double tangent_across, tangent_up;
};

// The smallest distance from target along toward_eye at which each ball
// (p, margin) lies inside the four planes through the eye at the view's
// half-angles shrunk by fill: a ball at (x, y, h) in the view's axes around
// target, seen from distance d, is inside the right-hand plane when its
// centre is at least margin from it, d >= h + (x + margin sqrt(1 + t^2)) / t.
template <class Balls>
double fitting_distance(const Balls& balls, const Vec3<double>& target, const ViewAxes& axes, double fill) {
  const double tx = fill * axes.tangent_across, ty = fill * axes.tangent_up;
  const double sx = std::sqrt(1.0 + tx * tx), sy = std::sqrt(1.0 + ty * ty);
  const auto fold = [&](double& distance, const Vec3<float>& p, double margin) {
    const Vec3<double> q = to_double(p) - target;
    if (!std::isfinite(dot(q, q)) || !std::isfinite(margin)) return;
    const double h = dot(q, axes.toward_eye);
    distance = greatest(greatest(distance, h + (std::fabs(dot(q, axes.right)) + margin * sx) / tx),
                        h + (std::fabs(dot(q, axes.up)) + margin * sy) / ty);
  };
  // A box of points (margin 0) settles a distance it stays below: h + |x| / t
  // is convex, so its largest is at a corner; the pad, a billionth of the
  // terms' size, is far above their rounding.
  const auto settled = [&](const double& distance, const Bounds& box) {
    double bound = -std::numeric_limits<double>::infinity(), size = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3<double> q = box_corner(box, corner) - target;
      const double h = dot(q, axes.toward_eye), x = std::fabs(dot(q, axes.right)), y = std::fabs(dot(q, axes.up));
      bound = std::max(bound, std::max(h + x / tx, h + y / ty));
      size = std::max(size, std::fabs(h) + x / tx + y / ty);
    }
    return std::isfinite(size) && bound + 1e-9 * size < distance;
  };
  return balls.reduce_pruned(0.0, fold, greatest, settled);
}

// The target moved across the view to the middle of the balls' image seen
// from distance along toward_eye. A ball at x across and depth z, of radius
// m < z, spans the tangents (x z -+ m sqrt(x^2 + z^2 - m^2)) / (z^2 - m^2).
template <class Balls>
Vec3<double> centred_target(const Balls& balls, const Vec3<double>& target, const ViewAxes& axes, double distance) {
  using Span = Ranges<2>;  // of the tangents across and up
  const auto fold = [&](Span& span, const Vec3<float>& p, double margin) {
    const Vec3<double> q = to_double(p) - target;
    const double z = distance - dot(q, axes.toward_eye);
    if (!std::isfinite(dot(q, q)) || !std::isfinite(margin) || !(z > margin)) return;
    const double across[2] = {dot(q, axes.right), dot(q, axes.up)};
    for (std::size_t k = 0; k < 2; ++k) {
      const double x = across[k], spread = margin * std::sqrt(x * x + z * z - margin * margin);
      const double scale = 1.0 / (z * z - margin * margin);
      span.include(k, (x * z - spread) * scale, (x * z + spread) * scale);
    }
  };
  // A box of points (margin 0) in front of the eye settles a span holding
  // its tangents x / z: on a box with z > 0 they are largest and smallest at
  // corners; the pad is far above their rounding.
  const auto settled = [&](const Span& span, const Bounds& box) {
    if (!(span.lo[0] <= span.hi[0]) || !(span.lo[1] <= span.hi[1])) return false;
    Span here;
    double reach = 0.0, nearest = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3<double> q = box_corner(box, corner) - target;
      const double z = distance - dot(q, axes.toward_eye);
      if (!(z > 0.0)) return false;
      const double across[2] = {dot(q, axes.right), dot(q, axes.up)};
      for (std::size_t k = 0; k < 2; ++k) here.include(k, across[k] / z, across[k] / z);
      reach = std::max(reach, std::sqrt(dot(q, q)));
      nearest = std::min(nearest, z);
    }
    const double pad = 1e-9 * (reach + std::fabs(distance)) / nearest;
    if (!std::isfinite(pad)) return false;
    for (std::size_t k = 0; k < 2; ++k) {
      if (!(here.lo[k] - pad > span.lo[k] && here.hi[k] + pad < span.hi[k])) return false;
    }
    return true;
  };
  const Span span = balls.reduce_pruned(Span{}, fold, joined<Span>, settled);
  if (!(span.lo[0] <= span.hi[0]) || !(span.lo[1] <= span.hi[1])) return target;
  return target + axes.right * (0.5 * (span.lo[0] + span.hi[0]) * distance) +
         axes.up * (0.5 * (span.lo[1] + span.hi[1]) * distance);
}

// The unit ball at the origin, for a scene without a bounded primitive.
struct UnitBall {
  template <class State, class Fold, class Combine, class Settled>
  State reduce_pruned(const State& none, const Fold& fold, const Combine&, const Settled&) const {
    State state = none;
    fold(state, Vec3<float>{0.f, 0.f, 0.f}, 1.0);
    return state;
  }
};

}  // namespace

std::optional<DefaultView> add_default_camera(SceneDesc& scene, int width, int height,
                                              const std::optional<Vec3<double>>& up, float angle_degrees) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide) {
    throw std::invalid_argument("add_default_view: width and height must lie in [1, 65536]");
  }
  if (up && !(dot(*up, *up) > 0.0 && std::isfinite(dot(*up, *up)))) {
    throw std::invalid_argument("add_default_view: the up axis must be finite and not zero");
  }
  if (!(angle_degrees > 0.f && angle_degrees < 180.f)) {
    throw std::invalid_argument("add_default_view: the angle must lie in (0, 180) degrees");
  }
  if (scene.camera) return std::nullopt;
  const ExtentBalls primitives(scene);
  const Bounds bounds = primitives.bounds();
  const DefaultView view = choose_view(scene, up, &bounds);
  // Three-quarter view: 35 degrees round from the front towards the model's
  // left (+x for the default front +z and up +y), 25 degrees up.
  const double azimuth = 35.0 * std::numbers::pi / 180.0, elevation = 25.0 * std::numbers::pi / 180.0;
  const Vec3<double> side = cross(view.up, view.front);
  ViewAxes axes;
  axes.toward_eye = (view.front * std::cos(azimuth) + side * std::sin(azimuth)) * std::cos(elevation) +
                    view.up * std::sin(elevation);
  axes.right = unit(cross(-axes.toward_eye, view.up));
  axes.up = cross(axes.right, -axes.toward_eye);
  // CameraDesc's angle spans the outermost pixel centres of the longer side.
  const double longest = std::tan(double(angle_degrees) * std::numbers::pi / 360.0);
  const double longer = double(std::max(std::max(width, height) - 1, 1));
  axes.tangent_across = longest * double(std::max(width - 1, 1)) / longer;
  axes.tangent_up = longest * double(std::max(height - 1, 1)) / longer;

  Vec3<double> target{0.0, 0.0, 0.0};
  double distance = 0.0;
  if (bounds.empty()) {
    distance = fitting_distance(UnitBall{}, target, axes, kDefaultViewFill);
  } else {
    for (int a = 0; a < 3; ++a) target[a] = 0.5 * bounds.lo[a] + 0.5 * bounds.hi[a];
    // Fit and centre twice (moving the target changes the depths, so the
    // first centring is close, the second closer), then fit: exact for that target.
    for (int pass = 0; pass < 2; ++pass) {
      target = centred_target(primitives, target, axes, fitting_distance(primitives, target, axes, kDefaultViewFill));
    }
    distance = fitting_distance(primitives, target, axes, kDefaultViewFill);
  }
  if (!(distance > 0.0)) distance = 1.0;  // a single point
  check_camera_fits_float(scene, target, distance);
  CameraDesc camera{};
  camera.from = to_float(target + axes.toward_eye * distance);
  camera.at = to_float(target);
  camera.up = to_float(view.up);
  camera.angle_degrees = angle_degrees;
  camera.hither = 0.f;
  camera.width = width;
  camera.height = height;
  scene.camera = camera;
  return view;
}

bool add_default_lights(SceneDesc& scene) {
  if (!scene.camera) throw std::invalid_argument("add_default_lights: the scene has no camera");
  if (!scene.lights.empty()) return false;
  const CameraDesc& c = *scene.camera;
  const CameraFrame frame = camera_frame(c);
  const Vec3<double> eye = to_double(c.from);
  const double view_distance = std::sqrt(dot(to_double(c.at) - eye, to_double(c.at) - eye));
  const float largest_ambient = std::max({scene.ambient.x, scene.ambient.y, scene.ambient.z});
  if (largest_ambient == 0.f) scene.ambient = {0.1f, 0.1f, 0.1f};
  const float light = default_light_total(scene.ambient);
  LightDesc key;
  key.kind = LightDesc::Kind::point;
  key.position = to_float(eye + (frame.right + frame.up) * (0.5 * view_distance));
  key.color = Vec3<float>{1.f, 1.f, 1.f} * (kDefaultKeyShare * light);
  LightDesc fill = key;
  fill.position = c.from;
  fill.color = Vec3<float>{1.f, 1.f, 1.f} * ((1.f - kDefaultKeyShare) * light);
  scene.lights = {key, fill};
  if (!scene.background) scene.background = Vec3<float>{1.f, 1.f, 1.f} * kDefaultRigBackground;
  return true;
}

std::optional<DefaultView> add_default_view(SceneDesc& scene, int width, int height,
                                            const std::optional<Vec3<double>>& up) {
  std::optional<DefaultView> view = add_default_camera(scene, width, height, up);
  add_default_lights(scene);
  return view;
}

}  // namespace quiver
