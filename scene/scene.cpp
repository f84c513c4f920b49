#include "scene/scene.h"

#include <algorithm>
#include <deque>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "geometry/bvh_store.h"
#include "geometry/parallel_indices.h"
#include "geometry/primitive_bounds.h"

namespace quiver {

namespace {

// Input primitives of one kind for one layer, with their origins.
template <class Desc>
struct LayerInput {
  DescRefs<Desc> descs;
  std::vector<PrimitiveOrigin> origins;
};

template <class K>
struct KindInput {
  LayerInput<typename K::Desc> opaque, transmissive;
  LayerInput<typename K::Desc>& layer(bool t) { return t ? transmissive : opaque; }
};

// origins[at[k]] for every k: the origins of the primitives a builder kept
// (at: the store's source), or a store's origins in leaf order (at: the
// positions before the reorder).
std::vector<PrimitiveOrigin> picked_origins(const std::vector<std::uint32_t>& at,
                                            const std::vector<PrimitiveOrigin>& origins) {
  std::vector<PrimitiveOrigin> picked(at.size());
  for_each_index(at.size(), [&](std::size_t k) { picked[k] = origins[at[k]]; });
  return picked;
}

// The triangles the triangle kernel renders a polygon as: every NFF `pp`
// patch (a triangle as it is, a larger polygon by ear clipping, each vertex
// taking the normal of the first input vertex at the same position), and a
// plain polygon of three vertices (with the polygon kernel's texture
// coordinates where textured). Empty: it stays a polygon.
std::vector<TriangleDesc> polygon_triangles(const ScenePolygon& polygon, bool textured) {
  std::vector<TriangleDesc> out;
  if (polygon.normals.empty()) {
    if (const std::optional<PolygonTriangle> t = polygon_as_triangle(polygon.polygon)) {
      out.push_back({t->p, {}, textured ? std::optional(t->uv) : std::nullopt});
    }
    return out;
  }
  const std::vector<Vec3<float>>& vs = polygon.polygon.vertices;
  auto normal_at = [&](const Vec3<float>& p) {
    for (std::size_t i = 0; i < vs.size(); ++i) {
      if (vs[i].x == p.x && vs[i].y == p.y && vs[i].z == p.z) return polygon.normals[i];
    }
    return Vec3<float>(0.f, 0.f, 0.f);  // the builder replaces a zero normal by the geometric one
  };
  if (vs.size() == 3) {
    out.push_back({{vs[0], vs[1], vs[2]}, std::array{polygon.normals[0], polygon.normals[1], polygon.normals[2]}, {}});
    return out;
  }
  for (const auto& tri : triangulate_polygon(polygon.polygon)) {
    out.push_back({tri, std::array{normal_at(tri[0]), normal_at(tri[1]), normal_at(tri[2])}, {}});
  }
  return out;
}

void layer_bounds(const GeometryLayer& g, Box& bounds) {
  g.kinds.for_each([&]<class K>(K, const KindStore<K>& k) {
    if constexpr (K::bounded) grow(bounds, store_box(k.store));
  });
}

// Builds one kind's store for one layer and the origins of what it kept.
template <class K>
void build_store(const LayerInput<typename K::Desc>& input, BuildReport& report, typename K::Store& store,
                 std::vector<PrimitiveOrigin>& origins) {
  store = K::build(input.descs, report);
  origins = picked_origins(store.source, input.origins);
}

// With options.acceleration == bvh and enough primitives in both layers
// together, builds the kind's BVH over both stores and puts each store and
// its origins in leaf order.
template <class K>
void index_stores(const KindInput<K>& input, const SceneBuildOptions& options, typename K::Store& opaque,
                  std::vector<PrimitiveOrigin>& opaque_origins, typename K::Store& transmissive,
                  std::vector<PrimitiveOrigin>& transmissive_origins, Bvh& bvh) {
  if (options.acceleration != Acceleration::bvh || opaque.count + transmissive.count < options.bvh_min_primitives) {
    return;
  }
  std::array<std::vector<std::uint32_t>, 2> positions;
  bvh = reorder_for_bvh(input.opaque.descs, opaque, input.transmissive.descs, transmissive, K::build, options.bvh,
                        &positions);
  opaque_origins = picked_origins(positions[0], opaque_origins);
  transmissive_origins = picked_origins(positions[1], transmissive_origins);
}

// The instanced meshes (each in its two stores, ids from 0, under one BVH
// whatever the acceleration option: the top level needs one), their
// origins, and the instances of those left with triangles, ids from
// first_id on.
template <class OriginOf, class IsTransmissive>
void build_instancing(const SceneDesc& desc, const SceneBuildOptions& options, OriginOf origin_of,
                      IsTransmissive is_transmissive, std::int32_t first_id, Scene& scene) {
  if (desc.instances.empty()) return;
  scene.meshes.resize(desc.meshes.size());
  scene.mesh_origins.resize(desc.meshes.size());
  for (std::size_t m = 0; m < desc.meshes.size(); ++m) {
    KindInput<TriangleKind> input;
    const std::vector<SceneTriangle>& triangles = desc.meshes[m].triangles;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      auto& in = input.layer(is_transmissive(triangles[i].material));
      in.origins.push_back(origin_of(triangles[i].material, kind_tag<TriangleKind>, i));
      in.descs.push_back(triangles[i].triangle);
    }
    InstancedMesh& mesh = scene.meshes[m];
    std::array<std::vector<PrimitiveOrigin>, 2>& origins = scene.mesh_origins[m].of_store;
    for (bool t : {false, true}) {
      build_store<TriangleKind>(input.layer(t), scene.counts.mesh_triangles, mesh.stores[t ? 1 : 0],
                                origins[t ? 1 : 0]);
    }
    SceneBuildOptions always = options;
    always.acceleration = Acceleration::bvh;
    always.bvh_min_primitives = 1;
    index_stores(input, always, mesh.stores[0], origins[0], mesh.stores[1], origins[1], mesh.bvh);
    mesh.stores[0].id_base = 0;
    mesh.stores[1].id_base = static_cast<std::int32_t>(mesh.stores[0].count);
    for (const TriangleSoA& store : mesh.stores) grow(mesh.bounds, store_box(store));
  }
  std::vector<Placement> placements;
  placements.reserve(desc.instances.size());
  for (const SceneInstance& instance : desc.instances) {
    if (instance.mesh >= desc.meshes.size()) {
      throw std::invalid_argument("an instance refers to mesh " + std::to_string(instance.mesh) + " of " +
                                  std::to_string(desc.meshes.size()));
    }
    if (scene.meshes[instance.mesh].triangle_count() == 0) continue;
    placements.push_back({static_cast<std::uint32_t>(instance.mesh), instance.object_to_world});
  }
  scene.counts.instances = placements.size();
  // Leaves of one instance: an instance costs a whole walk, not one test.
  BvhBuildOptions top = options.bvh;
  top.max_leaf_size = 1;
  scene.instance_bvh = build_instances(placements, scene.meshes, first_id, top, scene.instances);
}

}  // namespace

std::size_t GeometryLayer::primitive_count() const {
  std::size_t count = 0;
  kinds.for_each([&](auto, const auto& k) { count += k.store.count; });
  return count;
}

std::size_t GeometryLayer::memory_bytes() const {
  std::size_t bytes = 0;
  kinds.for_each([&](auto, const auto& k) { bytes += k.store.memory_bytes() + bytes_of(k.origins); });
  return bytes;
}

std::size_t Scene::acceleration_bytes() const {
  std::size_t bytes = instance_bvh.memory_bytes();
  for (const Bvh& bvh : kind_bvhs) bytes += bvh.memory_bytes();
  for (const InstancedMesh& m : meshes) bytes += m.bvh.memory_bytes();
  return bytes;
}

PrimitiveRef Scene::locate(std::int32_t id) const {
  const std::vector<std::int32_t>& bases = instances.id_base;
  if (!bases.empty() && id >= bases.front()) {
    const std::size_t row = std::size_t(std::upper_bound(bases.begin(), bases.end(), id) - bases.begin()) - 1;
    const TriangleSoA& first = meshes[instances.mesh[row]].stores[0];
    const std::uint32_t local = static_cast<std::uint32_t>(id - bases[row]);
    if (local < first.count) return {false, kind_tag<TriangleKind>, local, static_cast<std::int32_t>(row)};
    if (local - first.count < meshes[instances.mesh[row]].stores[1].count) {
      return {true, kind_tag<TriangleKind>, static_cast<std::uint32_t>(local - first.count),
              static_cast<std::int32_t>(row)};
    }
    throw std::out_of_range("no primitive with hit id " + std::to_string(id));
  }
  for (const IdRange& range : id_ranges) {
    const std::int32_t base = range.base;
    const std::size_t count = range.count;
    if (id >= base && std::size_t(id - base) < count) {
      return {range.transmissive, range.kind, static_cast<std::uint32_t>(id - base)};
    }
  }
  throw std::out_of_range("no primitive with hit id " + std::to_string(id));
}

const TriangleSoA& Scene::triangles_of(const PrimitiveRef& ref) const {
  if (ref.instance < 0) return layer(ref.transmissive).store<TriangleKind>();
  return meshes[instances.mesh[std::size_t(ref.instance)]].stores[ref.transmissive ? 1 : 0];
}

std::size_t Scene::primitive_count() const {
  std::size_t count = opaque.primitive_count() + transmissive.primitive_count();
  for (const InstancedMesh& m : meshes) count += m.triangle_count();
  return count;
}

bool Scene::has_transmissive() const {
  if (transmissive.primitive_count() > 0) return true;
  for (const InstancedMesh& m : meshes) {
    if (m.stores[1].count > 0) return true;
  }
  return false;
}

const PrimitiveOrigin& Scene::origin(const PrimitiveRef& ref) const {
  if (ref.instance >= 0) {
    return mesh_origins[instances.mesh[std::size_t(ref.instance)]].of_store[ref.transmissive ? 1 : 0][ref.local];
  }
  const GeometryLayer& g = layer(ref.transmissive);
  return visit_kind(ref.kind, [&](auto k) -> const PrimitiveOrigin& {
    return g.origins<decltype(k)>()[ref.local];
  });
}

std::uint64_t Scene::object_id(const PrimitiveRef& ref) const {
  const PrimitiveOrigin& o = origin(ref);
  if (ref.instance >= 0) return instance_object_id_base[std::size_t(ref.instance)] + o.index;
  return object_id_base[kind_index(o.kind)] + o.index;
}

std::size_t Scene::memory_bytes() const {
  std::size_t bytes = opaque.memory_bytes() + transmissive.memory_bytes() + bytes_of(material_of_id) +
                      bytes_of(plain_of_id) + instances.memory_bytes();
  for (const InstancedMesh& m : meshes) bytes += m.memory_bytes() - m.bvh.memory_bytes();
  for (const MeshOrigins& o : mesh_origins) bytes += bytes_of(o.of_store[0]) + bytes_of(o.of_store[1]);
  for (const Texture& t : textures) {
    bytes += bytes_of(t.image.rgb);
    for (const TextureImage& level : t.coarser) bytes += bytes_of(level.rgb);
  }
  return bytes;
}

namespace {

// The scene's primitives of every kind, split by layer (patches with
// normals become triangles), with their origins: references to the scene's
// own descriptions, and to the triangles made here for polygons.
struct SceneInputs {
  PerKind<KindInput> kinds;
  std::deque<TriangleDesc> polygon_triangles;  // a deque: references stay valid as it grows
};

// Appends each entry's description to its material's layer of input.
template <class K, class OriginOf, class IsTransmissive>
void split_by_layer(const SceneDesc& desc, OriginOf origin_of, IsTransmissive is_transmissive, SceneInputs& inputs) {
  const auto& entries = desc.*SceneEntries<K>::of;
  if constexpr (!std::is_same_v<K, PolygonKind>) {
    // Room for every entry up front: the reference and origin lists are not regrown.
    std::size_t transmissive = 0;
    for (const auto& entry : entries) transmissive += is_transmissive(entry.material) ? 1 : 0;
    for (bool t : {false, true}) {
      auto& in = inputs.kinds.of<K>().layer(t);
      const std::size_t count = in.descs.size() + (t ? transmissive : entries.size() - transmissive);
      in.descs.reserve(count);
      in.origins.reserve(count);
    }
  }
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& entry = entries[i];
    const PrimitiveOrigin o = origin_of(entry.material, kind_tag<K>, i);
    if constexpr (std::is_same_v<K, PolygonKind>) {
      // An NFF patch or a three-vertex polygon: triangles that keep kind polygon.
      std::vector<TriangleDesc> triangles = polygon_triangles(entry, desc.materials[entry.material].texture.has_value());
      if (!triangles.empty()) {
        auto& in = inputs.kinds.of<TriangleKind>().layer(is_transmissive(entry.material));
        for (TriangleDesc& t : triangles) {
          in.descs.push_back(inputs.polygon_triangles.emplace_back(std::move(t)));
          in.origins.push_back(o);
        }
        continue;
      }
    }
    auto& in = inputs.kinds.of<K>().layer(is_transmissive(entry.material));
    in.descs.push_back(entry.*SceneEntries<K>::desc);
    in.origins.push_back(o);
  }
}

template <class OriginOf, class IsTransmissive>
SceneInputs scene_inputs(const SceneDesc& desc, OriginOf origin_of, IsTransmissive is_transmissive) {
  SceneInputs inputs;
  for_each_kind([&]<class K>(K) { split_by_layer<K>(desc, origin_of, is_transmissive, inputs); });
  return inputs;
}

// Every kind's stores in both layers, their BVHs, ids from 0 in the list's
// order (opaque layer first), and the per-id material tables. Returns the
// next free id. The triangle stores' descriptions are let go once they are
// built (a BVH reorders them by their own columns), and with them
// `release_triangles` when given.
std::int32_t build_stores(SceneInputs& inputs, const SceneBuildOptions& options, Scene& scene,
                          std::vector<SceneTriangle>* release_triangles) {
  for_each_kind([&]<class K>(K) {
    KindInput<K>& input = inputs.kinds.of<K>();
    KindStore<K>& o = scene.opaque.kinds.of<K>();
    KindStore<K>& t = scene.transmissive.kinds.of<K>();
    BuildReport& report = scene.counts.kinds[kind_index(kind_tag<K>)];
    build_store<K>(input.opaque, report, o.store, o.origins);
    build_store<K>(input.transmissive, report, t.store, t.origins);
    // The stores' origins are picked: the inputs' are not read again.
    std::vector<PrimitiveOrigin>().swap(input.opaque.origins);
    std::vector<PrimitiveOrigin>().swap(input.transmissive.origins);
    if constexpr (std::is_same_v<K, TriangleKind>) {
      static_assert(ColumnsHoldEveryField<typename K::Store>, "the BVH reorder would read the released descriptions");
      input.opaque.descs = {};
      input.transmissive.descs = {};
      inputs.polygon_triangles = {};
      if (release_triangles != nullptr) std::vector<SceneTriangle>().swap(*release_triangles);
    }
    if constexpr (K::bounded) {
      Bvh& bvh = scene.kind_bvhs[kind_index(kind_tag<K>)];
      index_stores(input, options, o.store, o.origins, t.store, t.origins, bvh);
      if (bvh.empty()) {  // scanned: each store's box, the scans' cull
        for (KindStore<K>* k : {&o, &t}) k->bounds = store_box(k->store);
      }
    }
  });
  std::int32_t next_id = 0;
  for (bool transmissive : {false, true}) {
    GeometryLayer& g = transmissive ? scene.transmissive : scene.opaque;
    g.kinds.for_each([&]<class K>(K, KindStore<K>& k) {
      k.store.id_base = next_id;
      if (k.store.count > 0) scene.id_ranges.push_back({next_id, k.store.count, transmissive, kind_tag<K>});
      next_id += static_cast<std::int32_t>(k.store.count);
    });
  }
  scene.material_of_id.resize(scene.primitive_count());
  scene.plain_of_id.resize(scene.primitive_count());
  for (const GeometryLayer* g : {&scene.opaque, &scene.transmissive}) {
    g->kinds.for_each([&]<class K>(K, const KindStore<K>& k) {
      const auto& store = k.store;
      bool interpolated = false;
      if constexpr (std::is_same_v<K, TriangleKind>) interpolated = store.has_normals();
      const std::vector<PrimitiveOrigin>& origins = k.origins;
      for (std::size_t i = 0; i < origins.size(); ++i) {
        const std::size_t id = std::size_t(store.id_base) + i;
        scene.material_of_id[id] = origins[i].material;
        scene.plain_of_id[id] = !interpolated && !scene.materials[origins[i].material].texture ? 1 : 0;
      }
    });
  }
  return next_id;
}

// The box of every bounded primitive, placed instances included.
void set_bounds(Scene& scene) {
  Box bounds = empty_box();
  layer_bounds(scene.opaque, bounds);
  layer_bounds(scene.transmissive, bounds);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    grow(bounds, transformed_box(scene.meshes[scene.instances.mesh[i]].bounds, scene.instances.object_to_world[i]));
  }
  if (!is_empty(bounds)) {
    scene.bounds_min = bounds.lo;
    scene.bounds_max = bounds.hi;
  }
}

// Scene::object_id_base from the lists as read; returns the next object id.
std::uint64_t set_object_id_bases(const SceneDesc& desc, Scene& scene) {
  std::uint64_t next = 0;
  for_each_kind([&]<class K>(K) {
    scene.object_id_base[kind_index(kind_tag<K>)] = next;
    next += (desc.*SceneEntries<K>::of).size();
  });
  return next;
}

// Scene::instance_object_id_base, the placed instances' object ids from `next` on.
void set_instance_object_id_bases(const SceneDesc& desc, std::uint64_t next, Scene& scene) {
  std::vector<std::uint64_t> by_input(desc.instances.size());
  for (std::size_t j = 0; j < desc.instances.size(); ++j) {
    by_input[j] = next;
    next += desc.meshes[desc.instances[j].mesh].triangles.size();
  }
  scene.instance_object_id_base.resize(scene.instances.size());
  for (std::size_t row = 0; row < scene.instances.size(); ++row) {
    scene.instance_object_id_base[row] = by_input[scene.instances.source[row]];
  }
}

}  // namespace

void set_scene_view(Scene& scene, const SceneDesc& desc) {
  if (!desc.camera) throw std::invalid_argument("the scene has no camera");
  scene.camera = *desc.camera;
  scene.background = desc.background.value_or(Vec3<float>{0.f, 0.f, 0.f});
  scene.ambient = desc.ambient;
  scene.lights = desc.lights;
}

namespace {

// build_scene, releasing `release_triangles` (desc.triangles or null) as build_stores says.
Scene build_scene_from(const SceneDesc& desc, const SceneBuildOptions& options,
                       std::vector<SceneTriangle>* release_triangles) {
  Scene scene;
  set_scene_view(scene, desc);
  scene.materials = desc.materials;
  for (MaterialDesc& m : scene.materials) {
    if (m.texture && *m.texture >= desc.textures.size()) {
      throw std::invalid_argument("a material refers to texture " + std::to_string(*m.texture) + " of " +
                                  std::to_string(desc.textures.size()));
    }
    if (options.all_two_sided) m.two_sided = true;
  }
  scene.textures.reserve(desc.textures.size());
  for (const TextureDesc& t : desc.textures) scene.textures.push_back(build_texture(t));

  // A primitive's origin, its material index checked; its layer.
  auto origin_of = [&](std::size_t material, PrimitiveKind kind, std::size_t index) {
    if (material >= desc.materials.size()) {
      throw std::invalid_argument("a primitive refers to material " + std::to_string(material) + " of " +
                                  std::to_string(desc.materials.size()));
    }
    return PrimitiveOrigin{static_cast<std::uint32_t>(material), kind, static_cast<std::uint32_t>(index)};
  };
  // Bounded: the layer is asked before origin_of checks the index.
  auto is_transmissive = [&](std::size_t material) {
    return material < desc.materials.size() && desc.materials[material].kt > 0.f;
  };
  SceneInputs inputs = scene_inputs(desc, origin_of, is_transmissive);
  const std::uint64_t next_object_id = set_object_id_bases(desc, scene);
  const std::int32_t next_id = build_stores(inputs, options, scene, release_triangles);
  build_instancing(desc, options, origin_of, is_transmissive, next_id, scene);
  set_instance_object_id_bases(desc, next_object_id, scene);
  set_bounds(scene);
  return scene;
}

}  // namespace

Scene build_scene(const SceneDesc& desc, const SceneBuildOptions& options) {
  return build_scene_from(desc, options, nullptr);
}

Scene build_scene_releasing_triangles(SceneDesc& desc, const SceneBuildOptions& options) {
  return build_scene_from(desc, options, &desc.triangles);
}

}  // namespace quiver
