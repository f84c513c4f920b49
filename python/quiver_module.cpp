// The `quiver` Python module (pybind11): NumPy arrays in and out, checked
// by python/arguments.h, then handed to the C++ of this folder with the GIL
// released. Its API is documented in docs/PYTHON.md. Errors: quiver.ParseError (a
// ValueError) for bad scene files, with the CLI's file:line:column text;
// quiver.UsageError (a ValueError) for bad options, naming the CLI flag;
// ValueError for bad arrays or values; TypeError (OverflowError beyond
// int32) for an argument of the wrong type (python/arguments.h);
// RuntimeError for other failures.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/render_options.h"
#include "app/trace_command.h"
#include "io/parse_error.h"
#include "io/scene_loader.h"
#include "io/srgb_encoding.h"
#include "python/arguments.h"
#include "python/camera_rays.h"
#include "python/docstrings.h"
#include "python/output_buffers.h"
#include "python/python_scene.h"
#include "python/ray_queries.h"
#include "python/scene_arrays.h"
#include "python/rendered_image.h"
#include "python/scene_dict.h"
#include "python/scene_render.h"

namespace py = pybind11;

namespace quiver {
namespace {

using SceneHandle = std::shared_ptr<PythonScene>;

// intersect's and occluded's threads and simd arguments, checked as the CLI's --threads and --simd.
QueryThreads query_threads(const py::handle& threads, const std::optional<std::string>& simd) {
  RenderOptions options;
  options.threads = integer_argument(threads, "threads");
  options.simd = simd;
  check_render_options(options);
  return {options.threads, choose_isa(simd, std::getenv("QUIVER_SIMD"))};
}

// Hit points origin + t direction, in double from the float32 ray as traced
// (float64 input rounded to nearest, as the query reads it), rounded to
// float32; NaN for misses.
py::array_t<float> hit_points(const RayArrays& rays, const float* t) {
  const auto n = py::ssize_t(rays.count);
  py::array_t<float> points({n, py::ssize_t(3)});
  float* out = points.mutable_data();
  const auto component = [&](const void* column, std::size_t k) {
    return rays.type == ArrayFloat::float32 ? static_cast<const float*>(column)[k]
                                            : static_cast<float>(static_cast<const double*>(column)[k]);
  };
  for (std::size_t i = 0; i < rays.count; ++i) {
    for (std::size_t a = 0; a < 3; ++a) {
      const double o = component(rays.origins, 3 * i + a), d = component(rays.directions, 3 * i + a);
      out[3 * i + a] = std::isfinite(t[i]) ? float(o + double(t[i]) * d) : std::numeric_limits<float>::quiet_NaN();
    }
  }
  return points;
}

py::dict intersect_arrays(const PythonScene& scene, const py::handle& origins, const py::handle& directions, double tmin,
                          double tmax, const py::handle& threads, const std::optional<std::string>& simd, bool points) {
  const RayArrays rays = ray_arrays(origins, directions);
  const RayInterval interval = checked_interval(tmin, tmax);
  const QueryThreads query = query_threads(threads, simd);
  // One kept buffer (python/output_buffers.h) holds the seven columns; each
  // array holds the capsule that gives it back when the last one is freed.
  const auto n = py::ssize_t(rays.count);
  const std::size_t count = rays.count;
  static_assert(sizeof(float) == sizeof(std::int32_t));
  auto* buffer = new OutputBuffer(acquire_output_buffer(9 * count * sizeof(float)));
  const py::capsule owner(buffer, [](void* p) {
    auto* kept = static_cast<OutputBuffer*>(p);
    release_output_buffer(*kept);
    delete kept;
  });
  auto* floats = static_cast<float*>(buffer->data);
  auto* ints = reinterpret_cast<std::int32_t*>(floats + 6 * count);
  py::array_t<float> t({n}, floats, owner), u({n}, floats + count, owner), v({n}, floats + 2 * count, owner);
  py::array_t<float> normal({n, py::ssize_t(3)}, floats + 3 * count, owner);
  py::array_t<std::int32_t> primitive({n}, ints, owner), kind({n}, ints + count, owner),
      instance({n}, ints + 2 * count, owner);
  const HitColumns out{floats, ints, ints + count, floats + count, floats + 2 * count, floats + 3 * count,
                       ints + 2 * count};
  {
    py::gil_scoped_release release;
    intersect_rays(scene, rays, interval, query, out);
  }
  py::dict result;
  result["t"] = t;
  result["primitive"] = primitive;
  result["kind"] = kind;
  result["instance"] = instance;
  result["u"] = u;
  result["v"] = v;
  result["normal"] = normal;
  if (points) result["points"] = hit_points(rays, floats);
  return result;
}

// Linear values as the 8-bit sRGB codes quiver's PNG and JPEG writers store
// (io/srgb_encoding.h), in an array of the input's shape.
py::array_t<std::uint8_t> to_srgb(const py::array_t<float, py::array::c_style | py::array::forcecast>& linear) {
  py::array_t<std::uint8_t> codes(std::vector<py::ssize_t>(linear.shape(), linear.shape() + linear.ndim()));
  const float* in = linear.data();
  std::uint8_t* out = codes.mutable_data();
  const auto n = std::size_t(linear.size());
  py::gil_scoped_release release;
  srgb_bytes({in, n}, {out, n});
  return codes;
}

py::array_t<bool> occluded_arrays(const PythonScene& scene, const py::handle& origins, const py::handle& directions,
                                  double tmin, double tmax, const py::handle& threads,
                                  const std::optional<std::string>& simd) {
  const RayArrays rays = ray_arrays(origins, directions);
  const RayInterval interval = checked_interval(tmin, tmax);
  const QueryThreads query = query_threads(threads, simd);
  py::array_t<bool> blocked(py::ssize_t(rays.count));
  static_assert(sizeof(bool) == sizeof(std::uint8_t));
  auto* out = reinterpret_cast<std::uint8_t*>(blocked.mutable_data());
  {
    py::gil_scoped_release release;
    occluded_rays(scene.built, rays, interval, query, out);
  }
  return blocked;
}

SceneHandle load_file(const std::filesystem::path& path, const std::optional<double>& crease_angle,
                      bool allow_outside_paths) {
  check_crease_angle(crease_angle);
  py::gil_scoped_release release;
  SceneLoadOptions options;
  options.crease_angle_degrees = crease_angle;
  options.allow_outside_paths = allow_outside_paths;
  return std::make_shared<PythonScene>(make_python_scene(path.string(), load_scene(path.string(), options)));
}

SceneHandle scene_from_dict(const py::object& scene, const std::optional<std::filesystem::path>& base_dir,
                            const std::optional<double>& crease_angle, bool strict, bool allow_outside_paths) {
  check_crease_angle(crease_angle);
  DictSceneText text = toml_text_of_dict(scene);
  const std::filesystem::path folder = base_dir ? *base_dir : std::filesystem::current_path();
  py::gil_scoped_release release;
  return std::make_shared<PythonScene>(
      read_dict_scene(std::move(text), folder, {crease_angle, strict, allow_outside_paths}));
}

SceneHandle scene_from_python_arrays(const py::object& spheres, const py::object& vertices, const py::object& triangles) {
  std::optional<CheckedRows<FloatRows>> sphere_rows, vertex_rows;
  std::optional<CheckedRows<IndexRows>> triangle_rows;
  if (!spheres.is_none()) sphere_rows = float_rows(spheres, "spheres", 4, true);
  if (!vertices.is_none()) vertex_rows = float_rows(vertices, "vertices", 3, true);
  if (!triangles.is_none()) triangle_rows = index_rows(triangles, "triangles");
  SceneDesc desc = scene_from_arrays(rows_of(sphere_rows), rows_of(vertex_rows), rows_of(triangle_rows));
  py::gil_scoped_release release;
  return std::make_shared<PythonScene>(make_python_scene("<arrays>", std::move(desc)));
}

CameraFlags camera_flags(const py::object& look_from, const py::object& look_at, const py::object& up,
                         const std::optional<double>& fov) {
  CameraFlags flags{vector_flag(look_from, "look_from", "--look-from"), vector_flag(look_at, "look_at", "--look-at"),
                    vector_flag(up, "up", "--up"), fov};
  check_camera_flags(flags);
  return flags;
}

RenderedImage render_image(const PythonScene& scene, const py::object& width, const py::object& height,
                  std::optional<std::string> aa, const py::object& max_depth, std::optional<double> min_weight,
                  const py::handle& threads, std::optional<std::string> simd, const py::handle& seed, std::optional<std::string> aov,
                  std::optional<std::string> preset, bool two_sided, bool robust_methods, const py::object& look_from,
                  const py::object& look_at, const py::object& up, std::optional<double> fov,
                  std::optional<std::string> texture_filter) {
  RenderOptions options;
  options.width = optional_integer(width, "width");
  options.height = optional_integer(height, "height");
  if (aa) options.aa = parse_aa_flag(*aa);
  options.max_depth = optional_integer(max_depth, "max_depth");
  options.min_weight = min_weight;
  options.threads = integer_argument(threads, "threads");
  options.simd = std::move(simd);
  options.seed = parse_seed(integer_text(seed, "seed"));
  if (aov) options.aov = parse_aov_list(*aov);
  if (preset) check_preset(*preset);
  options.preset_spd = preset.has_value();
  options.two_sided = two_sided;
  options.robust_methods = robust_methods;
  if (texture_filter) options.filter_textures = parse_texture_filter(*texture_filter);
  options.camera = camera_flags(look_from, look_at, up, fov);
  RenderedImage image;
  py::gil_scoped_release release;
  image.frame = render_python_scene(scene, options);
  return image;
}

py::dict camera_ray_arrays(const PythonScene& scene, const py::object& width, const py::object& height,
                     const py::object& look_from, const py::object& look_at, const py::object& up,
                     std::optional<double> fov) {
  TraceOptions options;
  options.width = optional_integer(width, "width");
  options.height = optional_integer(height, "height");
  options.camera = camera_flags(look_from, look_at, up, fov);
  const CameraRayPlan plan = plan_camera_rays(scene.desc, options);
  const auto n = py::ssize_t(plan.ray_count());
  py::array_t<float> origins({n, py::ssize_t(3)}), directions({n, py::ssize_t(3)});
  py::array_t<std::int32_t> pixels({n, py::ssize_t(2)});
  py::array_t<std::int64_t> tile_starts(py::ssize_t(plan.tiles.size() + 1));
  fill_camera_rays(plan, origins.mutable_data(), directions.mutable_data(), pixels.mutable_data(),
                   tile_starts.mutable_data());
  py::dict result;
  result["origins"] = origins;
  result["directions"] = directions;
  result["pixels"] = pixels;
  result["tile_starts"] = tile_starts;
  result["width"] = plan.width;
  result["height"] = plan.height;
  return result;
}

}  // namespace
}  // namespace quiver

PYBIND11_MODULE(quiver, m) {
  using namespace quiver;
  using py::arg;
  m.doc() = "quiver: SIMD packet ray tracing from NumPy (docs/PYTHON.md)";
  m.attr("__version__") = QUIVER_VERSION;
  py::register_exception<ParseError>(m, "ParseError", PyExc_ValueError);
  py::register_exception<UsageError>(m, "UsageError", PyExc_ValueError);
  py::list kinds;
  for_each_kind([&]<class K>(K) { kinds.append(std::string(K::name)); });
  m.attr("KINDS") = py::tuple(kinds);

  py::class_<PythonScene, SceneHandle>(m, "Scene", docstrings::kScene)
      .def_property_readonly("name", [](const PythonScene& s) { return s.name; })
      .def_property_readonly("primitive_count", [](const PythonScene& s) { return s.built.primitive_count(); },
                             "Primitives as built (degenerate ones dropped)")
      .def_property_readonly("bounds",
                             [](const PythonScene& s) {
                               const Vec3<float>& lo = s.built.bounds_min;
                               const Vec3<float>& hi = s.built.bounds_max;
                               return py::make_tuple(py::make_tuple(lo.x, lo.y, lo.z), py::make_tuple(hi.x, hi.y, hi.z));
                             },
                             "((xmin, ymin, zmin), (xmax, ymax, zmax)) of the bounded primitives")
      .def("__repr__",
           [](const PythonScene& s) {
             return "<quiver.Scene " + s.name + ": " + std::to_string(s.built.primitive_count()) + " primitives>";
           })
      .def("intersect", &intersect_arrays, arg("origins"), arg("directions"), arg("tmin") = 0.0,
           arg("tmax") = std::numeric_limits<double>::infinity(), arg("threads") = 0, arg("simd") = py::none(),
           py::kw_only(), arg("points") = false, docstrings::kIntersect)
      .def("to_toml", &write_dict_scene, arg("path"), docstrings::kToToml)
      .def("occluded", &occluded_arrays, arg("origins"), arg("directions"), arg("tmin") = 0.0,
           arg("tmax") = std::numeric_limits<double>::infinity(), arg("threads") = 0, arg("simd") = py::none(),
           docstrings::kOccluded);

  bind_rendered_image(m);
  m.def("to_srgb", &to_srgb, arg("linear"), docstrings::kToSrgb);
  m.def("load", &load_file, arg("path"), arg("crease_angle") = py::none(), py::kw_only(),
        arg("allow_outside_paths") = false, docstrings::kLoad);
  m.def("from_dict", &scene_from_dict, arg("scene"), arg("base_dir") = py::none(), arg("crease_angle") = py::none(),
        py::kw_only(), arg("strict") = false, arg("allow_outside_paths") = false, docstrings::kFromDict);
  m.def("from_arrays", &scene_from_python_arrays, arg("spheres") = py::none(), arg("vertices") = py::none(),
        arg("triangles") = py::none(), docstrings::kFromArrays);
  m.def("render", &render_image, arg("scene"), py::kw_only(), arg("width") = py::none(), arg("height") = py::none(),
        arg("aa") = py::none(), arg("max_depth") = py::none(), arg("min_weight") = py::none(), arg("threads") = 0,
        arg("simd") = py::none(), arg("seed") = 0, arg("aov") = py::none(), arg("preset") = py::none(),
        arg("two_sided") = false, arg("robust_methods") = false, arg("look_from") = py::none(),
        arg("look_at") = py::none(), arg("up") = py::none(), arg("fov") = py::none(),
        arg("texture_filter") = py::none(), docstrings::kRender);
  m.def("camera_rays", &camera_ray_arrays, arg("scene"), py::kw_only(), arg("width") = py::none(),
        arg("height") = py::none(), arg("look_from") = py::none(), arg("look_at") = py::none(),
        arg("up") = py::none(), arg("fov") = py::none(), docstrings::kCameraRays);
}
