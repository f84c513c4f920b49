// Instancing as a two-level BVH (the layout of Embree's and pbrt-v4's
// instances): a mesh is stored once, with its own BVH over its own
// coordinates (the bottom level), and placed many times by affine
// transforms; a top-level BVH over the instances' world boxes finds the
// instances a ray meets, and the ray is carried into each one's
// coordinates (o' = W o, d' = W d, unnormalised, so t is the same in both
// spaces) for the bottom-level walk (geometry/instance_leaves.h).
// Instance i's hits take ids id_base[i] + the mesh's own ids.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/affine_transform.h"
#include "geometry/box.h"
#include "geometry/bvh.h"
#include "geometry/kinds/triangle.h"

namespace quiver {

// One mesh as instances share it: its triangles in two stores (store 0 and
// 1, a scene's opaque and transmissive layers; ids 0.. over store 0 then
// store 1) and one BVH over both.
struct InstancedMesh {
  std::array<TriangleSoA, 2> stores;
  Bvh bvh;
  Box bounds = empty_box();

  std::size_t triangle_count() const { return stores[0].count + stores[1].count; }
  std::size_t memory_bytes() const;  // stores and BVH
};

// The placements, one row per instance, in the top-level BVH's leaf order.
struct InstanceTable {
  std::vector<AffineTransform> object_to_world, world_to_object;
  std::vector<std::uint32_t> mesh;      // index of its InstancedMesh
  std::vector<std::int32_t> id_base;    // ascending
  std::vector<std::uint32_t> source;    // its index in the input order

  std::size_t size() const { return mesh.size(); }
  std::size_t memory_bytes() const;
};

// One placement as given: the mesh and its object-to-world transform
// (invertible: build_instances checks).
struct Placement {
  std::uint32_t mesh;
  AffineTransform object_to_world;
};

// The world box of a mesh box under a transform: its corners mapped in
// double, widened by 2^-20 of the largest magnitude (a bound far above
// the rounding of carrying a ray into the instance, so the top level never
// culls what the bottom level would hit).
Box transformed_box(const Box& object_box, const AffineTransform& object_to_world);

// The table of `placements` (ids from first_id on, instance after
// instance, each taking its mesh's triangle count) and its top-level BVH
// (leaves of one instance), which orders the table. Throws
// std::invalid_argument for a singular transform or a mesh index out of
// range, std::length_error when the ids would pass 2^31 - 1.
Bvh build_instances(std::span<const Placement> placements, std::span<const InstancedMesh> meshes,
                    std::int32_t first_id, const BvhBuildOptions& options, InstanceTable& table);

}  // namespace quiver
