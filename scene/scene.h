// The renderable scene: SceneDesc's primitives built into SoA stores (only
// the kinds the scene has), split into two layers, opaque and transmissive
// (kt > 0), so shadow rays ask the opaque layer an any-hit question and only
// walk the transmissive one hit by hit. Each bounded kind has one BVH over
// both layers' stores (its leaves hold one layer each), so a closest-hit
// walk meets both layers front to back. Every store gets a consecutive range
// of hit ids (id_base), and each primitive remembers its material and where
// it came from in the SceneDesc.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/instances.h"
#include "geometry/kinds.h"
#include "scene/scene_desc.h"
#include "scene/texture.h"

namespace quiver {

// Where a built primitive came from: its material and its kind and index in
// the SceneDesc (an NFF `pp` patch becomes triangles that keep kind polygon).
struct PrimitiveOrigin {
  std::uint32_t material;
  PrimitiveKind kind;
  std::uint32_t index;
};

// One kind's store in a layer and the origin of each built primitive, in
// store order.
template <class K>
struct KindStore {
  typename K::Store store;
  std::vector<PrimitiveOrigin> origins;
  // A box of every primitive (primitive_box), set where the kind is bounded
  // and scanned without a BVH: the packets that pass it by skip the store.
  Box bounds = empty_box();
};

// A layer's store of every kind (geometry/kinds.h).
struct GeometryLayer {
  PerKind<KindStore> kinds;

  template <class K>
  typename K::Store& store() {
    return kinds.of<K>().store;
  }
  template <class K>
  const typename K::Store& store() const {
    return kinds.of<K>().store;
  }
  template <class K>
  const std::vector<PrimitiveOrigin>& origins() const {
    return kinds.of<K>().origins;
  }
  std::size_t primitive_count() const;
  std::size_t memory_bytes() const;  // stores and origins
};

// Which layers a query tests: bit 0 opaque, bit 1 transmissive (the BVHs'
// store numbers).
enum class Layers : unsigned { opaque = 1, transmissive = 2, both = 3 };

// A hit id resolved: which layer, which store, which primitive in it; for
// a hit on an instance, the instance (its row in Scene::instances) and the
// primitive in its mesh's store of that layer.
struct PrimitiveRef {
  bool transmissive;
  PrimitiveKind kind;
  std::uint32_t local;
  std::int32_t instance = -1;  // -1: not instanced
};

// A store's hit ids, [base, base + count), with its layer and kind.
struct IdRange {
  std::int32_t base;
  std::size_t count;
  bool transmissive;
  PrimitiveKind kind;
};

// Where an instanced mesh's triangles came from, per store (0 opaque, 1
// transmissive): material, and index in SceneDesc::meshes[m].triangles.
struct MeshOrigins {
  std::array<std::vector<PrimitiveOrigin>, 2> of_store;
};

enum class Acceleration { none, bvh };

struct SceneBuildOptions {
  bool all_two_sided = false;  // SPD rule: every surface two-sided
  // bvh: a BVH per bounded kind of at least bvh_min_primitives in both layers
  // together (the order of the stores follows its leaves); none: every ray
  // scans every store.
  Acceleration acceleration = Acceleration::bvh;
  std::size_t bvh_min_primitives = 16;
  BvhBuildOptions bvh;
};

struct SceneCounts {
  std::array<BuildReport, kKindCount> kinds;  // by kind_index
  BuildReport mesh_triangles;  // of the instanced meshes, each counted once
  std::size_t instances = 0;   // placed (instances of meshes left empty are dropped)
};

struct Scene {
  CameraDesc camera;
  Vec3<float> background{0.f, 0.f, 0.f};
  Vec3<float> ambient{0.f, 0.f, 0.f};
  std::vector<LightDesc> lights;
  std::vector<MaterialDesc> materials;
  std::vector<Texture> textures;
  GeometryLayer opaque, transmissive;
  // Per kind (by kind_index), over both layers' stores (store 0 opaque,
  // store 1 transmissive); empty when the kind is scanned (unbounded kinds
  // always are; see SceneBuildOptions).
  std::array<Bvh, kKindCount> kind_bvhs;
  SceneCounts counts;
  // Instancing (geometry/instances.h): the meshes stored once, the
  // placements and the top-level BVH over them; their hit ids follow every
  // other store's.
  std::vector<InstancedMesh> meshes;
  std::vector<MeshOrigins> mesh_origins;
  InstanceTable instances;
  Bvh instance_bvh;
  // Per hit id of the stores above (a store's id_base + index): the
  // primitive's material, and 1 where its surface is plain (no interpolated
  // normals, no texture), so the material alone says how it looks. Instance
  // hits are never plain (shading needs their transform).
  std::vector<IdRange> id_ranges;  // of the non-empty stores above, ascending
  // Object ids, one per primitive as read, unique over the whole scene:
  // each kind's SceneDesc list in kind order, then each instance's mesh
  // triangles in the order the instances were read (object_id).
  std::array<std::uint64_t, kKindCount> object_id_base{};
  std::vector<std::uint64_t> instance_object_id_base;  // per InstanceTable row
  std::vector<std::uint32_t> material_of_id;
  std::vector<std::uint8_t> plain_of_id;
  Vec3<float> bounds_min{0.f, 0.f, 0.f}, bounds_max{0.f, 0.f, 0.f};  // of the built primitives (planes excluded)

  template <class K>
  const Bvh& bvh() const {
    return kind_bvhs[kind_index(kind_tag<K>)];
  }
  PrimitiveRef locate(std::int32_t id) const;
  bool is_plain(std::int32_t id) const {
    return std::size_t(id) < plain_of_id.size() && plain_of_id[std::size_t(id)] != 0;
  }
  // The triangles a triangle ref's primitive is in (its instance's mesh's, if any).
  const TriangleSoA& triangles_of(const PrimitiveRef& ref) const;
  // The store a ref's primitive is in (for triangles, triangles_of).
  template <class K>
  const typename K::Store& store_of(const PrimitiveRef& ref) const {
    if constexpr (std::is_same_v<K, TriangleKind>) {
      return triangles_of(ref);
    } else {
      return layer(ref.transmissive).store<K>();
    }
  }
  const GeometryLayer& layer(bool transmissive_layer) const { return transmissive_layer ? transmissive : opaque; }
  const PrimitiveOrigin& origin(const PrimitiveRef& ref) const;
  std::uint64_t object_id(const PrimitiveRef& ref) const;
  // Stored primitives: each instanced mesh counted once.
  std::size_t primitive_count() const;
  // Some primitive, instanced or not, lets light through (kt > 0).
  bool has_transmissive() const;
  std::size_t memory_bytes() const;  // geometry stores, per-id tables and textures
  std::size_t acceleration_bytes() const;  // BVH nodes (top level and instanced meshes' included)
};

// The parts of a built scene that a view changes: desc's camera (which it
// must have; else std::invalid_argument), background (black when it has
// none), ambient and lights. build_scene sets them so; quiver view sets
// them again for each view, the primitives built once.
void set_scene_view(Scene& scene, const SceneDesc& desc);

// Builds the scene; the SceneDesc must have a camera (scene/auto_view.h adds
// one). Throws std::invalid_argument for a material or texture index out of
// range, and what build_texture throws for a bad texture.
Scene build_scene(const SceneDesc& desc, const SceneBuildOptions& options);

// build_scene for a program that keeps only what was built: desc.triangles
// (what mesh readers make, a large mesh's largest part) is released as soon
// as the triangle stores hold its triangles, before their BVH is built, and
// is empty afterwards; the rest of desc is unchanged. The same scene as
// build_scene(desc) before the call.
Scene build_scene_releasing_triangles(SceneDesc& desc, const SceneBuildOptions& options);

}  // namespace quiver
