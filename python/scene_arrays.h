// A scene from NumPy arrays: spheres as (N, 4) rows of centre x, y, z and
// radius, triangles as (V, 3) vertex positions plus (F, 3) vertex indices
// per face. Every primitive gets one default material (white, ka 0.1,
// kd 0.9); there is no camera or light (a render adds the default view,
// scene/auto_view.h). A primitive's index in its array is the `primitive`
// that intersect reports.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "io/ply_reader.h"
#include "python/ray_arrays.h"
#include "scene/scene_desc.h"

namespace quiver {

// A C-contiguous 2D array of float32 or float64.
struct FloatRows {
  const void* data = nullptr;
  std::size_t rows = 0, columns = 0;
  ArrayFloat type = ArrayFloat::float32;
  double at(std::size_t row, std::size_t column) const;
};

// A C-contiguous (F, 3) array of int32 or int64.
struct IndexRows {
  const void* data = nullptr;
  std::size_t rows = 0;
  bool int64 = false;
  std::int64_t at(std::size_t row, std::size_t column) const;
};

// Throws std::invalid_argument naming the array and element: a value not
// finite in float32, a radius not > 0, an index outside [0, V), triangles
// without vertices (or the reverse), or no primitive at all.
SceneDesc scene_from_arrays(const std::optional<FloatRows>& spheres, const std::optional<FloatRows>& vertices,
                            const std::optional<IndexRows>& triangles);

// A dict scene's mesh from arrays (python/scene_dict.h) as the PLY mesh
// written for it: vertices (V, 3) and triangles (F, 3) as above, normals
// (V, 3) and uvs (V, 2) when given. Throws std::invalid_argument naming the
// element ("<where>.vertices[3, 1]") for a value not finite in float32, an
// index outside [0, V), rows of normals or uvs other than V, or more than
// the PLY reader's kMaxObjVertices vertices or kMaxObjTriangles triangles.
PlyMesh ply_of_arrays(const FloatRows& vertices, const IndexRows& triangles, const std::optional<FloatRows>& normals,
                      const std::optional<FloatRows>& uvs, const std::string& where);

}  // namespace quiver
