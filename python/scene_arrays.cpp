#include "python/scene_arrays.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace quiver {

namespace {

std::string element(const std::string& array, std::size_t row, std::size_t column) {
  return array + "[" + std::to_string(row) + ", " + std::to_string(column) + "]";
}

float finite_float(const FloatRows& rows, const std::string& name, std::size_t row, std::size_t column) {
  const double value = rows.at(row, column);
  const float rounded = static_cast<float>(value);
  if (!std::isfinite(rounded)) {
    throw std::invalid_argument(element(name, row, column) + " = " + std::to_string(value) +
                                " is not finite in float32");
  }
  return rounded;
}

Vec3<float> vertex(const FloatRows& rows, const std::string& name, std::size_t row) {
  return {finite_float(rows, name, row, 0), finite_float(rows, name, row, 1), finite_float(rows, name, row, 2)};
}

// triangles[f, c], checked to name one of `vertex_count` vertices.
std::size_t vertex_index(const IndexRows& triangles, const std::string& name, std::size_t f, std::size_t c,
                         std::size_t vertex_count) {
  const std::int64_t index = triangles.at(f, c);
  if (index < 0 || std::uint64_t(index) >= vertex_count) {
    throw std::invalid_argument(element(name, f, c) + " = " + std::to_string(index) +
                                ": expected a vertex index in [0, " + std::to_string(vertex_count) + ")");
  }
  return static_cast<std::size_t>(index);
}

}  // namespace

double FloatRows::at(std::size_t row, std::size_t column) const {
  const std::size_t k = row * columns + column;
  return type == ArrayFloat::float32 ? double(static_cast<const float*>(data)[k])
                                     : static_cast<const double*>(data)[k];
}

std::int64_t IndexRows::at(std::size_t row, std::size_t column) const {
  const std::size_t k = row * 3 + column;
  return int64 ? static_cast<const std::int64_t*>(data)[k] : std::int64_t(static_cast<const std::int32_t*>(data)[k]);
}

SceneDesc scene_from_arrays(const std::optional<FloatRows>& spheres, const std::optional<FloatRows>& vertices,
                            const std::optional<IndexRows>& triangles) {
  if (vertices.has_value() != triangles.has_value()) {
    throw std::invalid_argument("vertices and triangles: give both (positions and the faces indexing them) or neither");
  }
  SceneDesc desc;
  desc.materials.push_back(MaterialDesc{});
  if (spheres) {
    for (std::size_t i = 0; i < spheres->rows; ++i) {
      const float radius = finite_float(*spheres, "spheres", i, 3);
      if (!(radius > 0.f)) {
        throw std::invalid_argument(element("spheres", i, 3) + " = " + std::to_string(radius) +
                                    ": expected a radius > 0");
      }
      desc.spheres.push_back({{vertex(*spheres, "spheres", i), radius}, 0});
    }
  }
  if (triangles) {
    for (std::size_t i = 0; i < vertices->rows; ++i) vertex(*vertices, "vertices", i);  // every one checked
    for (std::size_t f = 0; f < triangles->rows; ++f) {
      SceneTriangle triangle{{}, 0};
      for (std::size_t c = 0; c < 3; ++c) {
        triangle.triangle.p[c] = vertex(*vertices, "vertices", vertex_index(*triangles, "triangles", f, c, vertices->rows));
      }
      desc.triangles.push_back(triangle);
    }
  }
  if (desc.spheres.empty() && desc.triangles.empty()) {
    throw std::invalid_argument("the arrays hold no primitive: give spheres, or vertices and triangles");
  }
  return desc;
}

PlyMesh ply_of_arrays(const FloatRows& vertices, const IndexRows& triangles, const std::optional<FloatRows>& normals,
                      const std::optional<FloatRows>& uvs, const std::string& where) {
  if (vertices.rows > kMaxObjVertices || triangles.rows > kMaxObjTriangles) {
    throw std::invalid_argument(where + ": at most " + std::to_string(kMaxObjVertices) + " vertices and " +
                                std::to_string(kMaxObjTriangles) + " triangles (a PLY mesh's bound), found " +
                                std::to_string(vertices.rows) + " and " + std::to_string(triangles.rows));
  }
  PlyMesh mesh;
  const auto columns = [&](const FloatRows& rows, const std::string& name, std::vector<float>& out) {
    if (rows.rows != vertices.rows) {
      throw std::invalid_argument(name + ": expected one row per vertex (" + std::to_string(vertices.rows) +
                                  "), found " + std::to_string(rows.rows));
    }
    out.reserve(rows.rows * rows.columns);
    for (std::size_t r = 0; r < rows.rows; ++r) {
      for (std::size_t c = 0; c < rows.columns; ++c) out.push_back(finite_float(rows, name, r, c));
    }
  };
  columns(vertices, where + ".vertices", mesh.positions);
  if (normals) columns(*normals, where + ".normals", mesh.normals);
  if (uvs) columns(*uvs, where + ".uvs", mesh.uvs);
  mesh.triangles.reserve(triangles.rows * 3);
  for (std::size_t f = 0; f < triangles.rows; ++f) {
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t index = vertex_index(triangles, where + ".triangles", f, c, vertices.rows);
      mesh.triangles.push_back(static_cast<std::uint32_t>(index));
    }
  }
  return mesh;
}

}  // namespace quiver
