// The module's arguments read from Python objects, each checked before the
// C++ of this folder sees it. Arrays are read in place, never copied: they
// must be NumPy arrays of an accepted dtype in native byte order, of the
// expected shape, C-contiguous and aligned (so a typed read of every element
// is defined). Camera vectors are "x,y,z" text or three real numbers: a
// NumPy array of shape (3,) of an integer or floating dtype, or a sequence
// of three numbers read by pybind11's own std::array caster (which holds
// each item while it reads it). Anything else raises ValueError naming the
// argument and saying what was expected and what was found. Integers must
// be integers: a Python int or an object with __index__ (NumPy integers,
// 0-d integer arrays); pybind11's int caster would truncate a NumPy float
// or a size-1 array through int(), so those raise TypeError here.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>

#include "python/ray_arrays.h"
#include "simd/vec3.h"
#include "python/scene_arrays.h"

namespace quiver {

// A checked array and its rows; the array keeps the rows' memory alive.
template <class Rows>
struct CheckedRows {
  pybind11::array array;
  Rows rows;
};

// A (N, columns) array of float32 or float64 (N >= 1 unless allow_empty).
CheckedRows<FloatRows> float_rows(const pybind11::handle& object, const char* name, std::size_t columns,
                                  bool allow_empty);

// A (F, 3) array of int32 or int64 (F may be 0).
CheckedRows<IndexRows> index_rows(const pybind11::handle& object, const char* name);

// The rows of an optional checked array (nothing without one).
template <class Rows>
std::optional<Rows> rows_of(const std::optional<CheckedRows<Rows>>& checked) {
  return checked ? std::optional(checked->rows) : std::nullopt;
}

// Origins and directions: (N, 3) float rows of one dtype and one N >= 1.
// The caller's arguments keep the arrays alive while the rays are read.
RayArrays ray_arrays(const pybind11::handle& origins, const pybind11::handle& directions);

// An integer argument; TypeError for anything else, OverflowError beyond int.
int integer_argument(const pybind11::handle& value, const char* name);

// integer_argument, or nullopt for None.
std::optional<int> optional_integer(const pybind11::object& value, const char* name);

// An integer argument's decimal text, any size or sign (for parse_seed,
// whose UsageError names what it refuses); TypeError for anything else.
std::string integer_text(const pybind11::handle& value, const char* name);

// A camera flag's point or direction, or nullopt for None: "x,y,z" text or
// three numbers (written so that they read back to the same doubles), parsed
// as the CLI's `flag` (--look-from, --look-at, --up) parses it.
std::optional<Vec3<float>> vector_flag(const pybind11::object& value, const char* name, const char* flag);

}  // namespace quiver
