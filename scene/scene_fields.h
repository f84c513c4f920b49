// The fields of a built Scene, listed once for every archive that copies a
// scene member by member in one fixed order: quiver-mpi's broadcast of rank
// 0's scene to the other ranks (app/scene_broadcast.h) and the tests' byte
// round trip. Not a file format: both ends are the same build.
//
// An archive A provides
//   static constexpr bool kReading;            true: fills the scene; false: reads it
//   void bytes(void* data, std::size_t size);  copies raw bytes out of or into data
//   void count(std::size_t& n, std::size_t element_bytes);  a list's length (a
//       reading archive of bytes it cannot trust checks it before anything is
//       allocated for it)
// transfer(archive, x) copies x: a trivially copyable value as its bytes, a
// vector as its length then its elements (trivially copyable ones as one
// block), an array or optional element by element, a PerKind kind by kind,
// and any other struct member by member as members(x) lists them, which must
// be every member (checked at compile time against the aggregate's count).
// A writing archive never modifies what it is given (the const_cast in
// transfer_scene is safe for it).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <tuple>
#include <type_traits>
#include <vector>

#include "scene/scene.h"

namespace quiver {

namespace scene_fields_detail {

template <class T>
struct IsVector : std::false_type {};
template <class T, class Allocator>
struct IsVector<std::vector<T, Allocator>> : std::true_type {};
template <class T>
struct IsArray : std::false_type {};
template <class T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

// The number of members of an aggregate: the most initializers T{...}
// accepts, each convertible to anything.
struct AnyMember {
  template <class T>
  operator T() const;
};
template <class T, class... Initializers>
constexpr std::size_t member_count() {
  if constexpr (requires { T{Initializers{}..., AnyMember{}}; }) {
    return member_count<T, Initializers..., AnyMember>();
  } else {
    return sizeof...(Initializers);
  }
}

}  // namespace scene_fields_detail

// Each struct's members in transfer order (transfer checks that none is
// left out: a member added to one of these structs must be listed here).
inline auto members(Bvh& b) { return std::tie(b.width, b.nodes, b.node_count, b.depth, b.bounds); }
inline auto members(SphereSoA& s) {
  return std::tie(s.cx, s.cy, s.cz, s.r2, s.inv_r, s.count, s.source, s.id_base);
}
inline auto members(PlaneSoA& s) {
  return std::tie(s.nx, s.ny, s.nz, s.d, s.px, s.py, s.pz, s.count, s.source, s.id_base);
}
inline auto members(TriangleSoA& s) {
  return std::tie(s.v0x, s.v0y, s.v0z, s.v1x, s.v1y, s.v1z, s.v2x, s.v2y, s.v2z, s.n0x, s.n0y, s.n0z, s.n1x, s.n1y,
                  s.n1z, s.n2x, s.n2y, s.n2z, s.uv0u, s.uv0v, s.uv1u, s.uv1v, s.uv2u, s.uv2v, s.count, s.source,
                  s.id_base);
}
inline auto members(PolygonSoA& s) {
  return std::tie(s.nx, s.ny, s.nz, s.origin_u, s.origin_v, s.umin, s.umax, s.vmin, s.vmax, s.reach, s.plane_slack,
                  s.axis_u, s.axis_v, s.vertex_count, s.first_vertex, s.pu, s.pv, s.px, s.py, s.pz, s.band_count,
                  s.band_scale, s.band_start, s.band_first, s.band_edges, s.band_spans, s.count, s.source, s.id_base);
}
inline auto members(ConeSoA& s) {
  return std::tie(s.bx, s.by, s.bz, s.ax, s.ay, s.az, s.height, s.radius0, s.slope, s.facing, s.count, s.source,
                  s.id_base);
}
template <class K>
auto members(KindStore<K>& k) {
  return std::tie(k.store, k.origins, k.bounds);
}
inline auto members(GeometryLayer& g) { return std::tie(g.kinds); }
inline auto members(TextureImage& t) { return std::tie(t.width, t.height, t.rgb); }
inline auto members(Texture& t) { return std::tie(t.kind, t.color_a, t.color_b, t.scale, t.wrap, t.image, t.coarser); }
inline auto members(InstancedMesh& m) { return std::tie(m.stores, m.bvh, m.bounds); }
inline auto members(MeshOrigins& m) { return std::tie(m.of_store); }
inline auto members(InstanceTable& t) {
  return std::tie(t.object_to_world, t.world_to_object, t.mesh, t.id_base, t.source);
}
inline auto members(Scene& s) {
  return std::tie(s.camera, s.background, s.ambient, s.lights, s.materials, s.textures, s.opaque, s.transmissive,
                  s.kind_bvhs, s.counts, s.meshes, s.mesh_origins, s.instances, s.instance_bvh, s.id_ranges,
                  s.object_id_base, s.instance_object_id_base, s.material_of_id, s.plain_of_id, s.bounds_min,
                  s.bounds_max);
}

template <class A, class T>
void transfer(A& archive, T& x) {
  using namespace scene_fields_detail;
  if constexpr (IsVector<T>::value) {
    using Element = typename T::value_type;
    std::size_t n = x.size();
    archive.count(n, sizeof(Element));
    if constexpr (A::kReading) x.resize(n);
    if constexpr (std::is_trivially_copyable_v<Element>) {
      if (n > 0) archive.bytes(x.data(), n * sizeof(Element));
    } else {
      for (Element& e : x) transfer(archive, e);
    }
  } else if constexpr (std::is_trivially_copyable_v<T>) {
    static_assert(!std::is_pointer_v<T>, "an address means nothing in another process");
    archive.bytes(&x, sizeof x);
  } else if constexpr (IsArray<T>::value) {
    for (auto& e : x) transfer(archive, e);
  } else if constexpr (IsOptional<T>::value) {
    bool present = x.has_value();
    archive.bytes(&present, sizeof present);
    if constexpr (A::kReading) {
      if (present) x.emplace();
    }
    if (present) transfer(archive, *x);
  } else if constexpr (std::is_same_v<T, PerKind<KindStore>>) {
    x.for_each([&](auto, auto& kind_store) { transfer(archive, kind_store); });
  } else {
    auto listed = members(x);
    static_assert(std::is_aggregate_v<T> && std::tuple_size_v<decltype(listed)> == member_count<T>(),
                  "members() must list every member of the struct");
    std::apply([&](auto&... member) { (transfer(archive, member), ...); }, listed);
  }
}

// Every field of the scene through the archive: filled by a reading one,
// read by a writing one.
template <class A>
void transfer_scene(A& archive, const Scene& scene) requires(!A::kReading) {
  transfer(archive, const_cast<Scene&>(scene));
}
template <class A>
void transfer_scene(A& archive, Scene& scene) requires(A::kReading) {
  transfer(archive, scene);
}

}  // namespace quiver
