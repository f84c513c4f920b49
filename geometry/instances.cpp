#include "geometry/instances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace quiver {

std::size_t InstancedMesh::memory_bytes() const {
  std::size_t bytes = bvh.memory_bytes();
  for (const TriangleSoA& s : stores) bytes += s.memory_bytes();
  return bytes;
}

std::size_t InstanceTable::memory_bytes() const {
  return bytes_of(object_to_world) + bytes_of(world_to_object) + bytes_of(mesh) + bytes_of(id_base) +
         bytes_of(source);
}

Box transformed_box(const Box& object_box, const AffineTransform& object_to_world) {
  if (is_empty(object_box)) return empty_box();
  double lo[3], hi[3];
  for (int r = 0; r < 3; ++r) {
    // Per row: the smallest and largest of sum_c m[r][c] x_c over the box.
    lo[r] = hi[r] = object_to_world.at(r, 3);
    for (int c = 0; c < 3; ++c) {
      const double a = double(object_to_world.at(r, c)) * object_box.lo[c];
      const double b = double(object_to_world.at(r, c)) * object_box.hi[c];
      lo[r] += std::min(a, b);
      hi[r] += std::max(a, b);
    }
  }
  double largest = 0.0;
  for (int r = 0; r < 3; ++r) largest = std::max({largest, std::fabs(lo[r]), std::fabs(hi[r])});
  const double pad = std::ldexp(largest, -20);
  Box box;
  for (int r = 0; r < 3; ++r) {
    box.lo[r] = std::nextafter(static_cast<float>(lo[r] - pad), -std::numeric_limits<float>::infinity());
    box.hi[r] = std::nextafter(static_cast<float>(hi[r] + pad), std::numeric_limits<float>::infinity());
  }
  return box;
}

Bvh build_instances(std::span<const Placement> placements, std::span<const InstancedMesh> meshes,
                    std::int32_t first_id, const BvhBuildOptions& options, InstanceTable& table) {
  std::vector<Box> boxes;
  std::vector<AffineTransform> inverses;
  boxes.reserve(placements.size());
  inverses.reserve(placements.size());
  for (std::size_t i = 0; i < placements.size(); ++i) {
    const Placement& p = placements[i];
    if (p.mesh >= meshes.size()) {
      throw std::invalid_argument("instance " + std::to_string(i) + " refers to mesh " + std::to_string(p.mesh) +
                                  " of " + std::to_string(meshes.size()));
    }
    const std::optional<AffineTransform> to_object = inverse(p.object_to_world);
    if (!to_object) throw std::invalid_argument("instance " + std::to_string(i) + " has a singular transform");
    inverses.push_back(*to_object);
    boxes.push_back(transformed_box(meshes[p.mesh].bounds, p.object_to_world));
  }
  std::vector<std::uint32_t> order;
  Bvh bvh = build_bvh(boxes, options, order);
  table = InstanceTable{};
  table.object_to_world.reserve(order.size());
  table.world_to_object.reserve(order.size());
  table.mesh.reserve(order.size());
  table.id_base.reserve(order.size());
  table.source = order;
  std::int64_t next_id = first_id;
  for (std::uint32_t k : order) {
    const Placement& p = placements[k];
    table.object_to_world.push_back(p.object_to_world);
    table.world_to_object.push_back(inverses[k]);
    table.mesh.push_back(p.mesh);
    table.id_base.push_back(static_cast<std::int32_t>(std::min<std::int64_t>(next_id, 0x7fffffff)));
    next_id += static_cast<std::int64_t>(meshes[p.mesh].triangle_count());
    if (next_id > std::int64_t{0x7fffffff}) {
      throw std::length_error("the instances' triangles would take more than 2^31 - 1 hit ids (" +
                              std::to_string(placements.size()) + " instances)");
    }
  }
  return bvh;
}

}  // namespace quiver
