// Golden images: the built-in scene and every io/examples scene (one seed
// effect each) rendered small and compared with the EXR references in
// tests/data/golden. Tolerance: at most 0.5% of the channel values may
// differ by more than 0.02 and the mean absolute difference must stay below
// 0.002, which leaves room for another libm's last-bit differences in
// atan2/pow (a texel or edge decision may flip) but not for a changed effect.
// QUIVER_UPDATE_GOLDEN=1 rewrites the references instead (then the test
// reports that it wrote them and skips).
// The references are the renderer's own output, so they catch change, not
// wrongness: beside them, each golden scene's render is checked against
// pixels computed here from the scene's numbers (Golden.*Independently):
// an unshadowed Phong pixel, a pixel in full shadow (ambient only) and a
// mirror pixel reflecting the background, with tolerances derived from the
// float arithmetic's rounding.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "scene/default_scene.h"
#include "integrator/camera.h"
#include "integrator/render.h"
#include "io/image_output.h"
#include "io/scene_loader.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(QUIVER_TEST_DATA_DIR) / "golden";
const fs::path kExamplesDir = fs::path(QUIVER_TEST_DATA_DIR) / ".." / ".." / "io" / "examples";

Framebuffer render_small(const SceneDesc& desc) {
  const Scene scene = build_scene(desc, {});
  RenderSettings settings;
  settings.width = 64;
  settings.height = std::max(1, 64 * desc.camera->height / desc.camera->width);
  settings.aa = parse_anti_aliasing("grid:2");
  settings.isa = best_supported_isa();
  settings.trace.max_depth = desc.render.max_depth.value_or(5);
  return render(scene, settings).image;
}

std::vector<float> read_rgb(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, rgb.data());
  return rgb;
}

void check_against_golden(const std::string& name, const SceneDesc& desc) {
  const Framebuffer image = render_small(desc);
  const fs::path golden = kGoldenDir / (name + ".exr");
  if (const char* update = std::getenv("QUIVER_UPDATE_GOLDEN"); update && std::string(update) == "1") {
    fs::create_directories(kGoldenDir);
    write_image(golden, image);
    GTEST_SKIP() << "QUIVER_UPDATE_GOLDEN=1: wrote " << golden;
  }
  int w = 0, h = 0;
  const std::vector<float> reference = read_rgb(golden, w, h);
  ASSERT_FALSE(reference.empty()) << "missing golden image " << golden << " (QUIVER_UPDATE_GOLDEN=1 writes it)";
  ASSERT_EQ(w, image.width) << name;
  ASSERT_EQ(h, image.height) << name;
  std::size_t far = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double d = std::fabs(double(reference[i]) - double(image.rgb[i]));
    sum += d;
    far += d > 0.02;
  }
  EXPECT_LE(far, reference.size() / 200) << name << ": channel values off by more than 0.02";
  EXPECT_LT(sum / double(reference.size()), 0.002) << name << ": mean absolute difference";
}

TEST(Golden, BuiltInScene) { check_against_golden("default", default_scene()); }

TEST(Golden, EveryExampleScene) {
  std::size_t examples = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(kExamplesDir)) {
    if (e.path().extension() != ".toml") continue;
    ++examples;
    SCOPED_TRACE(e.path().filename().string());
    check_against_golden(e.path().stem().string(), load_scene(e.path()));
  }
  EXPECT_GE(examples, 7u) << "io/examples should hold a scene per seed effect";
}

// ---- independent pixel values ------------------------------------------------

using V3 = Vec3<double>;
constexpr double kEps = 0x1p-24;  // float's unit roundoff
// Classification margin: a ray decided to miss or hit something passes it by
// at least this relative distance, so float rounding (~1e-6) cannot flip it.
constexpr double kMargin = 1e-3;

V3 wide(const Vec3<float>& v) { return {v.x, v.y, v.z}; }
double norm(const V3& v) { return std::sqrt(dot(v, v)); }
V3 unit_of(const V3& v) { return v * (1.0 / norm(v)); }
V3 times(const V3& a, const V3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

struct Ball {
  V3 c;
  double r;
};

// Distance from c to the segment o + s d, s in [0, s_end] (s_end may be inf).
double segment_distance(const V3& o, const V3& d, double s_end, const V3& c) {
  const double s = std::clamp(dot(c - o, d) / dot(d, d), 0.0, s_end);
  return norm(o + d * s - c);
}

// The scene in double: planes and spheres exactly, every other primitive
// as a ball around it (so a ray that keeps clear of the ball misses it).
struct AnalyticScene {
  const SceneDesc& desc;
  std::vector<Ball> others;

  explicit AnalyticScene(const SceneDesc& d) : desc(d) {
    const auto ball_of = [](const std::vector<V3>& points, double pad) {
      V3 c{0, 0, 0};
      for (const V3& p : points) c = c + p * (1.0 / double(points.size()));
      double r = 0.0;
      for (const V3& p : points) r = std::max(r, norm(p - c));
      return Ball{c, r + pad};
    };
    for (const SceneCone& c : d.cones) {
      others.push_back(ball_of({wide(c.cone.base), wide(c.cone.apex)},
                               std::max(std::fabs(c.cone.base_radius), std::fabs(c.cone.apex_radius))));
    }
    for (const SceneTriangle& t : d.triangles) others.push_back(ball_of({wide(t.triangle.p[0]), wide(t.triangle.p[1]), wide(t.triangle.p[2])}, 0.0));
    for (const ScenePolygon& g : d.polygons) {
      std::vector<V3> points;
      for (const Vec3<float>& v : g.polygon.vertices) points.push_back(wide(v));
      others.push_back(ball_of(points, 0.0));
    }
    for (const SceneInstance& instance : d.instances) {
      for (const SceneTriangle& t : d.meshes[instance.mesh].triangles) {
        std::vector<V3> points;
        for (const Vec3<float>& v : t.triangle.p) points.push_back(apply_point(instance.object_to_world, wide(v)));
        others.push_back(ball_of(points, 0.0));
      }
    }
  }

  struct Hit {
    bool sphere = false;
    std::size_t index = 0;
    double t = 0.0;
  };
  // The nearest plane or sphere hit along o + t d (unit d), t in (0, t_end),
  // when it is decided with margin: nothing else within kMargin of it, the
  // ray clear of every ball before it and of every sphere's silhouette.
  // nullopt: undecided; a Hit with t = inf: the ray meets nothing.
  std::optional<Hit> cast(const V3& o, const V3& d, double t_end) const {
    std::vector<Hit> hits;
    for (std::size_t i = 0; i < desc.planes.size(); ++i) {
      const V3 n = unit_of(wide(desc.planes[i].plane.normal));
      const double along = dot(d, n), gap = dot(wide(desc.planes[i].plane.point) - o, n);
      if (std::fabs(gap) < kMargin) return std::nullopt;  // starts on it
      if (std::fabs(along) < kMargin) continue;             // parallel enough: it never reaches it here
      if (gap / along > 0.0) hits.push_back({false, i, gap / along});
    }
    for (std::size_t i = 0; i < desc.spheres.size(); ++i) {
      const V3 c = wide(desc.spheres[i].sphere.center);
      const double r = desc.spheres[i].sphere.radius;
      const double along = dot(c - o, d), miss2 = dot(c - o, c - o) - along * along;
      if (std::fabs(std::sqrt(std::max(miss2, 0.0)) - r) < kMargin * r) return std::nullopt;  // grazes it
      if (miss2 > r * r) continue;
      const double half = std::sqrt(r * r - miss2);
      if (along - half > kMargin) hits.push_back({true, i, along - half});
      else if (along + half > kMargin) return std::nullopt;  // starts inside or on it
    }
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t; });
    Hit nearest{false, 0, std::numeric_limits<double>::infinity()};
    if (!hits.empty() && hits[0].t < t_end) nearest = hits[0];
    if (hits.size() > 1 && hits[1].t - hits[0].t < kMargin) return std::nullopt;
    for (const Ball& b : others) {
      if (segment_distance(o, d, std::min(nearest.t, t_end), b.c) < b.r + kMargin) return std::nullopt;
    }
    return nearest;
  }
};

// One camera sample's value computed here, and its error bound.
struct Expected {
  V3 rgb{0, 0, 0};
  V3 tolerance{0, 0, 0};
  enum class Kind { lit, shadow, mirror } kind = Kind::lit;
};

// Local Whitted shading of an untextured surface at p (unit normal n facing
// the viewer, unit view ray d, t its distance from o), lights decided with
// margin; nullopt where a light's visibility is undecided. Error bounds:
// the renderer's hit point is off by <= 16 eps (|o| + t) (t within a few
// ulp, then o + t d), so its normal by that over r (spheres) plus 4 eps; it
// aims at the light from the shadow ray's origin, moved off the surface by
// <= 64 float ulps of |o|_1 + t |d|_1 (integrator/optics.h: 128 eps), so its
// light direction is off by twice their sum over the light's distance; the
// Phong sums take <= 8 roundings (8 eps of each term) and pow is within
// (2 s |log2 x| + 4) eps (simd/power.h).
std::optional<Expected> shade_locally(const AnalyticScene& scene, const V3& o, const V3& d, double t, const V3& p,
                                      const V3& n, double radius, const MaterialDesc& m) {
  const SceneDesc& desc = scene.desc;
  const V3 color = wide(m.color);
  const double dp = 16.0 * kEps * (norm(o) + t);
  const double dn = (radius > 0.0 ? dp / radius : 0.0) + 4.0 * kEps;
  const double offset = 128.0 * kEps * (std::fabs(o.x) + std::fabs(o.y) + std::fabs(o.z) +
                                        t * (std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z)));
  Expected e;
  e.rgb = times(wide(desc.ambient), color) * double(m.ka);
  e.tolerance = e.rgb * (8.0 * kEps);
  bool blocked_any = false, lit_any = false;
  for (const LightDesc& light : desc.lights) {
    if (light.kind != LightDesc::Kind::point && light.kind != LightDesc::Kind::directional) return std::nullopt;
    const bool point = light.kind == LightDesc::Kind::point;
    const V3 toward = point ? wide(light.position) - p : -wide(light.direction);
    const double distance = point ? norm(toward) : std::numeric_limits<double>::infinity();
    const V3 l = unit_of(toward);
    const double n_dot_l = dot(n, l);
    if (n_dot_l < kMargin && n_dot_l > -kMargin) return std::nullopt;  // nearly edge-on: sign undecided
    if (n_dot_l < 0.0) continue;
    // Opaque spheres block with margin; the shadow ray must otherwise keep clear.
    bool blocked = false;
    for (const SceneSphere& s : desc.spheres) {
      const V3 c = wide(s.sphere.center);
      const double gap = segment_distance(p, l, distance, c), r = s.sphere.radius;
      const bool ends_outside = norm(p - c) > r * (1 + kMargin) && (!point || norm(wide(light.position) - c) > r * (1 + kMargin));
      if (gap < r * (1 - kMargin) && ends_outside && desc.materials[s.material].kt == 0.f) blocked = true;
    }
    const std::optional<AnalyticScene::Hit> along = scene.cast(p + n * kMargin, l, distance);
    if (!blocked && (!along || along->t < distance)) return std::nullopt;  // neither clear nor surely blocked
    if (blocked) {
      blocked_any = true;
      continue;
    }
    lit_any = true;
    const V3 intensity = wide(light.color);
    const double dl = (point ? 2.0 * (dp + offset) / distance : 0.0) + 4.0 * kEps;
    const V3 diffuse = times(intensity, color) * (double(m.kd) * n_dot_l);
    e.rgb = e.rgb + diffuse;
    e.tolerance = e.tolerance + times(intensity, color) * (double(m.kd) * (dn + dl + 8.0 * kEps));
    const V3 half_sum = l - d;
    const double n_dot_h = dot(n, unit_of(half_sum)), s = m.shininess;
    if (m.ks > 0.f && n_dot_h > 0.0) {
      const double specular = double(m.ks) * std::pow(n_dot_h, s);
      const double dh = 2.0 * (dl + 4.0 * kEps) / norm(half_sum);
      const double slope = double(m.ks) * s * std::pow(n_dot_h, s - 1.0) * (dn + dh);
      const double rounding = specular * ((2.0 * s * std::fabs(std::log2(n_dot_h)) + 4.0 + 8.0) * kEps);
      e.rgb = e.rgb + intensity * specular;
      e.tolerance = e.tolerance + intensity * (slope + rounding);
    }
  }
  e.kind = blocked_any && !lit_any ? Expected::Kind::shadow : Expected::Kind::lit;
  return e;
}

// The value of the camera sample through film point (x, y), computed here,
// where every decision it involves is taken with margin.
std::optional<Expected> expected_sample(const AnalyticScene& scene, const Camera& camera, double x, double y) {
  const SceneDesc& desc = scene.desc;
  const Ray<float> ray = camera.ray(x, y);
  const V3 o = wide(ray.origin), d = unit_of(wide(ray.direction));
  const std::optional<AnalyticScene::Hit> hit = scene.cast(o, d, std::numeric_limits<double>::infinity());
  if (!hit || std::isinf(hit->t)) return std::nullopt;
  const V3 p = o + d * hit->t;
  const std::size_t material = hit->sphere ? desc.spheres[hit->index].material : desc.planes[hit->index].material;
  const MaterialDesc& m = desc.materials[material];
  if (m.texture || m.kt > 0.f) return std::nullopt;
  double radius = 0.0;
  V3 n;
  if (hit->sphere) {
    radius = desc.spheres[hit->index].sphere.radius;
    n = (p - wide(desc.spheres[hit->index].sphere.center)) * (1.0 / radius);
  } else {
    n = unit_of(wide(desc.planes[hit->index].plane.normal));
    if (dot(n, d) > 0.0) n = -n;  // two-sided: the normal faces the viewer
  }
  std::optional<Expected> e = shade_locally(scene, o, d, hit->t, p, n, radius, m);
  if (!e || m.kr == 0.f) return e;
  // A mirror: kr times the background, where the reflected ray meets nothing.
  const V3 reflected = d - n * (2.0 * dot(d, n));
  const std::optional<AnalyticScene::Hit> beyond = scene.cast(p + n * kMargin, reflected, std::numeric_limits<double>::infinity());
  if (!beyond || !std::isinf(beyond->t) || desc.render.max_depth.value_or(5) < 1) return std::nullopt;
  const V3 sky = wide(desc.background) * double(m.kr);
  e->rgb = e->rgb + sky;
  e->tolerance = e->tolerance + sky * (4.0 * kEps);
  e->kind = Expected::Kind::mirror;
  return e;
}

// Every pixel of the golden render whose four grid:2 samples are all
// decided is compared with the mean of their values computed here; returns
// how many pixels of each kind were compared.
std::map<Expected::Kind, std::size_t> check_independently(const SceneDesc& desc) {
  const Framebuffer image = render_small(desc);
  const Camera camera(*desc.camera, image.width, image.height);
  const AnalyticScene scene(desc);
  std::map<Expected::Kind, std::size_t> compared;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      V3 sum{0, 0, 0}, tolerance{0, 0, 0};
      std::optional<Expected::Kind> kind;
      bool decided = true;
      for (int j = 0; j < 4 && decided; ++j) {
        const std::optional<Expected> e = expected_sample(scene, camera, x + (j % 2 + 0.5) / 2, y + (j / 2 + 0.5) / 2);
        decided = e.has_value() && (!kind || *kind == e->kind);
        if (!decided) break;
        kind = e->kind;
        sum = sum + e->rgb * 0.25;
        tolerance = tolerance + e->tolerance * 0.25;
      }
      if (!decided) continue;
      // The mean of four: three sums and a scale, 4 eps of the value.
      tolerance = tolerance + sum * (4.0 * kEps);
      const std::size_t at = (std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3;
      EXPECT_NEAR(image.rgb[at], sum.x, tolerance.x) << "pixel " << x << ", " << y << " red";
      EXPECT_NEAR(image.rgb[at + 1], sum.y, tolerance.y) << "pixel " << x << ", " << y << " green";
      EXPECT_NEAR(image.rgb[at + 2], sum.z, tolerance.z) << "pixel " << x << ", " << y << " blue";
      ++compared[*kind];
    }
  }
  return compared;
}

// Which kinds of pixel each golden scene must offer for the independent
// check. Every decided pixel of every scene is compared; the last four
// scenes offer none (every surface there is textured or transmissive, or
// lit by an area light, whose values are not computed here), nor does the
// built-in scene (an area light).
TEST(Golden, ScenesAgreeWithPixelsComputedIndependently) {
  struct Want {
    std::size_t lit, shadow, mirror;
  };
  const std::map<std::string, Want> wanted = {
      {"shadows_hard", {1, 1, 0}},   {"reflection_depth", {0, 0, 1}}, {"transparent_shadows", {1, 0, 0}},
      {"mesh_include", {1, 0, 0}},   {"instances", {1, 0, 0}},        {"glass_tir", {0, 0, 0}},
      {"textures", {0, 0, 0}},       {"adaptive_aa", {0, 0, 0}},      {"shadows_soft", {0, 0, 0}},
  };
  for (const auto& [name, want] : wanted) {
    SCOPED_TRACE(name);
    const std::map<Expected::Kind, std::size_t> compared = check_independently(load_scene(kExamplesDir / (name + ".toml")));
    const auto count = [&](Expected::Kind k) { return compared.count(k) ? compared.at(k) : std::size_t{0}; };
    EXPECT_GE(count(Expected::Kind::lit), want.lit) << "unshadowed Phong pixels compared";
    EXPECT_GE(count(Expected::Kind::shadow), want.shadow) << "pixels in full shadow compared";
    EXPECT_GE(count(Expected::Kind::mirror), want.mirror) << "mirror pixels compared";
  }
}

}  // namespace
}  // namespace quiver
