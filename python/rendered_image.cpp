#include "python/rendered_image.h"

#include <pybind11/numpy.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/image_output.h"
#include "python/docstrings.h"

namespace py = pybind11;

namespace quiver {
namespace {

// An (H, W) or (H, W, 3) view of one of the image's arrays, keeping the
// image alive while it lives; None for an AOV not rendered.
template <class T>
py::object view(const py::object& owner, std::vector<T>& values, int channels) {
  if (values.empty()) return py::none();
  const Framebuffer& frame = owner.cast<RenderedImage&>().frame;
  std::vector<py::ssize_t> shape{frame.height, frame.width};
  if (channels > 1) shape.push_back(channels);
  return py::array_t<T>(shape, values.data(), owner);
}

Framebuffer& frame_of(const py::object& self) { return self.cast<RenderedImage&>().frame; }

void save(const RenderedImage& image, const std::filesystem::path& path) {
  const Framebuffer& frame = image.frame;
  const bool has_aovs = !frame.depth.empty() || !frame.normal.empty() || !frame.id.empty();
  try {
    check_output_path(path, has_aovs);
  } catch (const std::runtime_error& error) {
    throw py::value_error(error.what());  // the path the CLI would refuse: a usage error
  }
  try {
    write_image(path, frame);
  } catch (const std::runtime_error& error) {
    PyErr_SetString(PyExc_OSError, error.what());
    throw py::error_already_set();
  }
}

std::string describe(const RenderedImage& image) {
  const Framebuffer& frame = image.frame;
  std::string aovs;
  const auto add = [&](bool present, const char* name) {
    if (!present) return;
    aovs += aovs.empty() ? ", aov " : ",";
    aovs += name;
  };
  add(!frame.depth.empty(), "depth");
  add(!frame.normal.empty(), "normal");
  add(!frame.id.empty(), "id");
  return "<quiver.Image " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + aovs + ">";
}

}  // namespace

void bind_rendered_image(py::module_& module) {
  py::class_<RenderedImage>(module, "Image", docstrings::kImage)
      .def_property_readonly("width", [](const RenderedImage& image) { return image.frame.width; })
      .def_property_readonly("height", [](const RenderedImage& image) { return image.frame.height; })
      .def_property_readonly("color", [](const py::object& self) { return view(self, frame_of(self).rgb, 3); },
                             "(H, W, 3) float32 linear RGB, row 0 at the top")
      .def_property_readonly("depth", [](const py::object& self) { return view(self, frame_of(self).depth, 1); },
                             "(H, W) float32 distance along the unit primary ray (inf on a miss), or None")
      .def_property_readonly("normal", [](const py::object& self) { return view(self, frame_of(self).normal, 3); },
                             "(H, W, 3) float32 unit shading normal facing the ray (0 on a miss), or None")
      .def_property_readonly("kind", [](const py::object& self) { return view(self, frame_of(self).kind, 1); },
                             "(H, W) int32 primitive kind (index into quiver.KINDS, -1 on a miss), or None")
      .def_property_readonly("id", [](const py::object& self) { return view(self, frame_of(self).id, 1); },
                             "(H, W) int32 primitive id in the whole scene (-1 on a miss), or None")
      .def("save", &save, py::arg("path"), docstrings::kImageSave)
      .def("__repr__", &describe);
}

}  // namespace quiver
