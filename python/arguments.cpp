#include "python/arguments.h"

#include <pybind11/stl.h>

#include <array>
#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include "app/render_options.h"

namespace py = pybind11;

namespace quiver {

namespace {

std::string type_name(const py::handle& object) {
  return std::string(py::str(py::type::of(object).attr("__name__")));
}

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    text += (d ? ", " : "") + std::to_string(array.shape(d));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

py::array as_array(const py::handle& object, const char* name) {
  if (!py::isinstance<py::array>(object)) {
    throw std::invalid_argument(std::string(name) + ": expected a numpy.ndarray, found " + type_name(object));
  }
  return py::reinterpret_borrow<py::array>(object);
}

// The shape (rows, columns), rows >= 1 unless allow_empty, C-contiguous and
// aligned: what a read of row r, column c at data[r * columns + c] needs.
void check_rows_layout(const py::array& array, const char* name, char rows_letter, std::size_t columns,
                       bool allow_empty) {
  if (array.ndim() != 2 || array.shape(1) != py::ssize_t(columns)) {
    throw std::invalid_argument(std::string(name) + ": expected shape (" + rows_letter + ", " +
                                std::to_string(columns) + "), found " + shape_text(array));
  }
  if (!allow_empty && array.shape(0) == 0) {
    throw std::invalid_argument(std::string(name) + ": expected at least one row, found shape " + shape_text(array));
  }
  if (!(array.flags() & py::array::c_style)) {
    const std::vector<py::ssize_t> strides(array.strides(), array.strides() + array.ndim());
    throw std::invalid_argument(std::string(name) +
                                ": expected a C-contiguous array (numpy.ascontiguousarray makes one), found strides " +
                                std::string(py::str(py::tuple(py::cast(strides)))));
  }
  // NumPy's own flag: the data address is a multiple of the dtype's alignment.
  if (!array.attr("flags").attr("aligned").cast<bool>()) {
    throw std::invalid_argument(std::string(name) + ": expected an aligned array (numpy.array(x) copies it into one), " +
                                "found data not aligned for " + std::string(py::str(array.dtype())));
  }
}

// "a list of 4 items", "an array of shape (3, 1) and dtype float64", "an int".
std::string describe(const py::handle& value) {
  if (py::isinstance<py::array>(value)) {
    const auto array = py::reinterpret_borrow<py::array>(value);
    return "an array of shape " + shape_text(array) + " and dtype " + std::string(py::str(array.dtype()));
  }
  const std::string type = type_name(value);
  const std::string article = std::string_view("aeiou").find(type.front()) == std::string_view::npos ? "a " : "an ";
  const py::ssize_t length = PySequence_Check(value.ptr()) ? PySequence_Size(value.ptr()) : -1;
  if (length < 0) {
    PyErr_Clear();  // no length: described by its type alone
    return article + type;
  }
  return article + type + " of " + std::to_string(length) + " items" + (length == 3 ? ", not all real numbers" : "");
}

// Three real numbers, or a ValueError saying what value was. A NumPy array
// must have shape (3,) and an integer or floating dtype (bool, complex,
// text and object arrays are refused rather than cast); bytes and
// bytearray are refused before the caster, which would read their byte
// codes as the numbers.
std::array<double, 3> three_numbers(const py::object& value, const char* name) {
  const auto refused = [&] {
    return std::invalid_argument(std::string(name) + ": expected \"x,y,z\" or three real numbers, found " +
                                 describe(value));
  };
  if (py::isinstance<py::array>(value)) {
    const auto array = py::reinterpret_borrow<py::array>(value);
    const char kind = array.dtype().kind();
    if (array.ndim() != 1 || array.shape(0) != 3 || std::string_view("iuf").find(kind) == std::string_view::npos) {
      throw refused();
    }
  } else if (py::isinstance<py::bytes>(value) || PyByteArray_Check(value.ptr())) {
    throw refused();
  }
  try {
    return value.cast<std::array<double, 3>>();
  } catch (const py::cast_error&) {
    throw refused();
  } catch (py::error_already_set& error) {
    // A length beyond ssize_t (range(10**20)); other errors of the object's own are its own.
    if (!error.matches(PyExc_OverflowError)) throw;
    throw refused();
  }
}

// The shortest text that reads back to the same double (as Python's repr).
std::string number_text(double value) {
  std::array<char, 32> text{};
  const auto [end, error] = std::to_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc()) throw std::runtime_error("a number did not fit its text buffer");
  return std::string(text.data(), end);
}

// The value as a Python int through __index__ (never int(), which truncates).
py::object as_index(const py::handle& value, const char* name) {
  if (!PyIndex_Check(value.ptr())) {
    throw py::type_error(std::string(name) + ": expected an integer, found " + type_name(value));
  }
  auto index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) throw py::error_already_set();  // a size-1 or non-integer array: NumPy's TypeError
  return index;
}

}  // namespace

int integer_argument(const py::handle& value, const char* name) {
  const py::object index = as_index(value, name);
  try {
    return index.cast<int>();
  } catch (const py::cast_error&) {
    throw std::overflow_error(std::string(name) + ": expected an integer in the range of int32, found " +
                              std::string(py::str(index)));
  }
}

std::optional<int> optional_integer(const py::object& value, const char* name) {
  if (value.is_none()) return std::nullopt;
  return integer_argument(value, name);
}

std::string integer_text(const py::handle& value, const char* name) { return py::str(as_index(value, name)); }

CheckedRows<FloatRows> float_rows(const py::handle& object, const char* name, std::size_t columns, bool allow_empty) {
  py::array array = as_array(object, name);
  ArrayFloat type;
  if (py::isinstance<py::array_t<float>>(array)) {
    type = ArrayFloat::float32;
  } else if (py::isinstance<py::array_t<double>>(array)) {
    type = ArrayFloat::float64;
  } else {
    throw std::invalid_argument(std::string(name) + ": expected dtype float32 or float64 (native byte order), found " +
                                std::string(py::str(array.dtype())));
  }
  check_rows_layout(array, name, 'N', columns, allow_empty);
  const FloatRows rows{array.data(), std::size_t(array.shape(0)), columns, type};
  return {std::move(array), rows};
}

CheckedRows<IndexRows> index_rows(const py::handle& object, const char* name) {
  py::array array = as_array(object, name);
  const bool int64 = py::isinstance<py::array_t<std::int64_t>>(array);
  if (!int64 && !py::isinstance<py::array_t<std::int32_t>>(array)) {
    throw std::invalid_argument(std::string(name) + ": expected dtype int32 or int64 (native byte order), found " +
                                std::string(py::str(array.dtype())));
  }
  check_rows_layout(array, name, 'F', 3, true);
  const IndexRows rows{array.data(), std::size_t(array.shape(0)), int64};
  return {std::move(array), rows};
}

RayArrays ray_arrays(const py::handle& origins_object, const py::handle& directions_object) {
  const auto origins = float_rows(origins_object, "origins", 3, false);
  const auto directions = float_rows(directions_object, "directions", 3, false);
  if (origins.rows.rows != directions.rows.rows) {
    throw std::invalid_argument("origins and directions: expected the same number of rays, found shapes " +
                                shape_text(origins.array) + " and " + shape_text(directions.array));
  }
  if (origins.rows.type != directions.rows.type) {
    throw std::invalid_argument("origins and directions: expected one dtype for both, found " +
                                std::string(py::str(origins.array.dtype())) + " and " +
                                std::string(py::str(directions.array.dtype())));
  }
  return {origins.rows.data, directions.rows.data, origins.rows.rows, origins.rows.type};
}

std::optional<Vec3<float>> vector_flag(const py::object& value, const char* name, const char* flag) {
  if (value.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(value)) return parse_vector_flag(flag, value.cast<std::string>());
  const std::array<double, 3> xyz = three_numbers(value, name);
  return parse_vector_flag(flag, number_text(xyz[0]) + "," + number_text(xyz[1]) + "," + number_text(xyz[2]));
}

}  // namespace quiver
