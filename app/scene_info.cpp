#include "app/scene_info.h"

#include <sys/resource.h>

#include <cmath>
#include <numbers>
#include <charconv>
#include <initializer_list>
#include <cstdio>
#include <fstream>
#include <string_view>

namespace quiver {

namespace {

ByKind<std::string_view> kind_plurals() {
  ByKind<std::string_view> names;
  for_each_kind([&]<class K>(K) { names[kind_index(kind_tag<K>)] = K::plural; });
  return names;
}

// Shortest decimal text that reads back as the same float.
std::string number(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

// An angle in degrees from its cosine, to 4 significant digits (the
// cosine's rounding moves the angle in its sixth).
std::string degrees_of_cosine(float cosine) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", std::acos(double(cosine)) * 180.0 / std::numbers::pi);
  return text;
}

std::string vec(const Vec3<float>& v) {
  std::string text(1, '(');
  text += number(v.x);
  text += ' ';
  text += number(v.y);
  text += ' ';
  text += number(v.z);
  text += ')';
  return text;
}

// A right-aligned cell wider than its column still gets one space before it,
// so numbers of large scenes do not run together.
std::string padded(std::string_view text, std::size_t width, bool right = true) {
  std::string out;
  if (right) out.append(text.size() < width ? width - text.size() : 1, ' ');
  out += text;
  if (!right && text.size() < width) out.append(width - text.size(), ' ');
  return out;
}

std::string milliseconds(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f ms", ms);
  return text;
}

std::string_view light_kind(LightDesc::Kind kind) {
  switch (kind) {
    case LightDesc::Kind::point: return "point";
    case LightDesc::Kind::directional: return "directional";
    case LightDesc::Kind::rectangle: return "rectangle";
    case LightDesc::Kind::sphere: return "sphere";
    case LightDesc::Kind::spot: return "spot";
  }
  return "?";
}

std::string_view wrap_name(WrapMode wrap) {
  switch (wrap) {
    case WrapMode::repeat: return "repeat";
    case WrapMode::clamp: return "clamp";
    case WrapMode::mirror: return "mirror";
  }
  return "?";
}

ByKind<std::size_t> layer_counts(const GeometryLayer& g) {
  ByKind<std::size_t> counts;
  g.kinds.for_each([&]<class K>(K, const KindStore<K>& k) { counts[kind_index(kind_tag<K>)] = k.store.count; });
  return counts;
}

// One table row: a left-aligned name, then right-aligned columns.
void write_row(std::ostream& out, std::string_view name, std::initializer_list<std::string> cells,
               std::initializer_list<std::size_t> widths) {
  out << "  " << padded(name, 12, false);
  auto width = widths.begin();
  for (const std::string& cell : cells) out << padded(cell, *width++);
  out << "\n";
}

void write_primitives(std::ostream& out, const SceneDesc& desc, const Scene& scene, const ByKind<std::size_t>& read) {
  const auto& reports = scene.counts.kinds;
  const auto names = kind_plurals();
  const auto opaque = layer_counts(scene.opaque);
  const auto transmissive = layer_counts(scene.transmissive);
  const std::initializer_list<std::size_t> widths{8, 8, 12, 12, 8, 14};
  out << "primitives: as read; kept by the builders or dropped (non-finite, degenerate); kept = opaque + "
         "transmissive\n";
  write_row(out, "", {"read", "kept", "non-finite", "degenerate", "opaque", "transmissive"}, widths);
  std::array<std::size_t, 6> totals{};
  for (std::size_t k = 0; k < kKindCount; ++k) {
    const std::array<std::size_t, 6> row{read[k],     reports[k].kept, reports[k].dropped_non_finite,
                                         reports[k].dropped_degenerate, opaque[k], transmissive[k]};
    for (std::size_t c = 0; c < row.size(); ++c) totals[c] += row[c];
    write_row(out, names[k],
              {std::to_string(row[0]), std::to_string(row[1]), std::to_string(row[2]), std::to_string(row[3]),
               std::to_string(row[4]), std::to_string(row[5])},
              widths);
  }
  write_row(out, "total",
            {std::to_string(totals[0]), std::to_string(totals[1]), std::to_string(totals[2]),
             std::to_string(totals[3]), std::to_string(totals[4]), std::to_string(totals[5])},
            widths);

  // Polygons built as triangles (patches and three-vertex polygons) keep kind polygon.
  std::size_t patches = 0, cut_triangles = 0;
  for (const ScenePolygon& p : desc.polygons) patches += p.normals.empty() ? 0 : 1;
  std::vector<bool> cut(desc.polygons.size(), false);
  for (const GeometryLayer* g : {&scene.opaque, &scene.transmissive}) {
    for (const PrimitiveOrigin& o : g->origins<TriangleKind>()) {
      if (o.kind != kind_tag<PolygonKind>) continue;
      ++cut_triangles;
      cut[o.index] = true;
    }
  }
  const auto cut_polygons = std::size_t(std::count(cut.begin(), cut.end(), true));
  if (cut_polygons > 0) {
    out << "  polygons built as triangles: " << cut_polygons << " (" << patches << " read with vertex normals), as "
        << cut_triangles << " of the triangles kept\n";
  }
  if (!desc.instances.empty()) {
    std::size_t placed = 0;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) placed += scene.meshes[scene.instances.mesh[i]].triangle_count();
    const BuildReport& m = scene.counts.mesh_triangles;
    out << "instances       " << scene.counts.instances << " placed (of " << desc.instances.size() << " read) of "
        << desc.meshes.size() << " mesh" << (desc.meshes.size() == 1 ? "" : "es") << ", stored once: " << m.kept
        << " triangles kept (" << m.dropped_non_finite << " non-finite, " << m.dropped_degenerate
        << " degenerate dropped), " << placed << " placed\n";
    for (std::size_t k = 0; k < desc.meshes.size(); ++k) {
      out << "  mesh " << k << ": " << desc.meshes[k].name << ", " << scene.meshes[k].triangle_count() << " triangles\n";
    }
  }
  out << "bounds          " << vec(scene.bounds_min) << " to " << vec(scene.bounds_max) << " (planes excluded)\n";
}

void write_camera(std::ostream& out, const Scene& scene, const std::optional<DefaultView>& default_view) {
  const CameraDesc& c = scene.camera;
  out << "camera          from " << vec(c.from) << " at " << vec(c.at) << " up " << vec(c.up) << "\n"
      << "                angle " << number(c.angle_degrees) << " degrees, hither " << number(c.hither)
      << ", resolution " << c.width << "x" << c.height << "\n";
  if (default_view) {
    out << "                (none in the file: a default view of the whole scene,\n"
        << "                up " << default_view->up_reason << ";\n"
        << "                front " << default_view->front_reason << ";\n"
        << "                seen 35 degrees round from the front and 25 above, filling "
        << int(kDefaultViewFill * 100.0 + 0.5) << "% of the image;\n"
        << "                then the camera flags given)\n";
  }
  out << "background      " << vec(scene.background) << "\n"
      << "ambient         " << vec(scene.ambient) << "\n";
}

void write_render_settings(std::ostream& out, const RenderDesc& render) {
  if (!render.aa && !render.max_depth && !render.min_weight) return;
  out << "render settings";
  if (render.aa) out << " aa " << to_string(*render.aa);
  if (render.max_depth) out << " max_depth " << *render.max_depth;
  if (render.min_weight) out << " min_weight " << number(*render.min_weight);
  out << "\n";
}

void write_lights(std::ostream& out, const SceneDesc& desc, const Scene& scene) {
  out << "lights          " << scene.lights.size();
  if (desc.lights.empty() && !scene.lights.empty()) out << " (none in the file: the default rig, a key light above and right of the eye and a fill at the eye)";
  out << "\n";
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const LightDesc& l = scene.lights[i];
    out << "  " << i << ": " << light_kind(l.kind);
    switch (l.kind) {
      case LightDesc::Kind::point: out << " position " << vec(l.position); break;
      case LightDesc::Kind::directional: out << " direction " << vec(l.direction); break;
      case LightDesc::Kind::spot:
        out << " position " << vec(l.position) << " direction " << vec(l.direction) << " cone "
            << degrees_of_cosine(l.cone_inner_cos) << " to " << degrees_of_cosine(l.cone_outer_cos) << " degrees";
        break;
      case LightDesc::Kind::rectangle:
        out << " corner " << vec(l.position) << " edges " << vec(l.edge_u) << " " << vec(l.edge_v);
        break;
      case LightDesc::Kind::sphere: out << " centre " << vec(l.position) << " radius " << number(l.radius); break;
    }
    out << " colour " << vec(l.color);
    if (l.is_area()) {
      out << " samples " << l.samples << "x" << l.samples;
    }
    out << "\n";
  }
}

void write_materials(std::ostream& out, const Scene& scene) {
  out << "materials       " << scene.materials.size() << "\n";
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    out << "  " << i << ": colour " << vec(m.color) << " texture "
        << (m.texture ? std::to_string(*m.texture) : std::string("none")) << " ka " << number(m.ka) << " kd "
        << number(m.kd) << " ks " << number(m.ks) << " shininess " << number(m.shininess) << " kr " << number(m.kr)
        << " kt " << number(m.kt) << " ior " << number(m.ior) << (m.two_sided ? " two-sided" : " one-sided") << "\n";
  }
}

void write_textures(std::ostream& out, const SceneDesc& desc, const Scene& scene) {
  out << "textures        " << desc.textures.size() << "\n";
  for (std::size_t i = 0; i < desc.textures.size(); ++i) {
    const TextureDesc& t = desc.textures[i];
    out << "  " << i << ": ";
    switch (t.kind) {
      case TextureDesc::Kind::checker2d:
      case TextureDesc::Kind::checker3d:
        out << (t.kind == TextureDesc::Kind::checker2d ? "checker2d" : "checker3d") << " colours " << vec(t.color_a)
            << " " << vec(t.color_b) << " scale " << number(t.scale);
        break;
      case TextureDesc::Kind::image: {
        out << "image " << (t.path.empty() ? std::string("(in memory)") : t.path);
        if (i < scene.textures.size()) {
          out << " " << scene.textures[i].image.width << "x" << scene.textures[i].image.height;
        }
        out << " wrap " << wrap_name(t.wrap);
        break;
      }
    }
    out << "\n";
  }
}

void write_memory(std::ostream& out, const Scene& scene) {
  const std::initializer_list<std::size_t> widths{10, 14};
  out << "memory (bytes: SoA columns by capacity, with their source and origin arrays)\n";
  write_row(out, "", {"opaque", "transmissive"}, widths);
  const auto opaque = memory_by_kind(scene.opaque);
  const auto transmissive = memory_by_kind(scene.transmissive);
  const auto names = kind_plurals();
  for (std::size_t k = 0; k < kKindCount; ++k) {
    write_row(out, names[k], {std::to_string(opaque[k]), std::to_string(transmissive[k])}, widths);
  }
  std::size_t texture_bytes = 0;
  for (const Texture& t : scene.textures) texture_bytes += bytes_of(t.image.rgb);
  out << "  " << padded("textures", 12, false) << texture_bytes << "\n";
  if (!scene.meshes.empty()) {
    std::size_t mesh_bytes = 0;
    for (const InstancedMesh& m : scene.meshes) mesh_bytes += m.memory_bytes() - m.bvh.memory_bytes();
    out << "  " << padded("instanced meshes (stores, once each)", 38, false) << mesh_bytes << "\n"
        << "  " << padded("instance table", 38, false) << scene.instances.memory_bytes() << "\n";
  }
  out << "  " << padded("total", 12, false) << scene.memory_bytes() << "\n";
}

// Per bounded kind: the BVH's width, nodes, depth and bytes.
void write_acceleration(std::ostream& out, const Scene& scene) {
  out << "acceleration (a BVH per bounded kind of " << SceneBuildOptions{}.bvh_min_primitives
      << " or more primitives, over both layers; planes and smaller kinds are scanned)\n";
  bool any = false;
  const auto write_tree = [&](const std::string& name, const Bvh& bvh) {
    if (bvh.empty()) return;
    any = true;
    out << "  " << padded(name, 22, false) << bvh.width << "-wide, " << bvh.node_count << " nodes, depth "
        << bvh.depth << ", " << bvh.memory_bytes() << " bytes\n";
  };
  for_each_kind([&]<class K>(K) { write_tree(std::string(K::name), scene.bvh<K>()); });
  for (std::size_t k = 0; k < scene.meshes.size(); ++k) write_tree("instanced mesh " + std::to_string(k), scene.meshes[k].bvh);
  write_tree("instances (top level)", scene.instance_bvh);
  if (!any) out << "  none\n";
  out << "  " << padded("total", 12, false) << scene.acceleration_bytes() << "\n";
}

}  // namespace

ByKind<std::size_t> read_counts(const SceneDesc& desc) {
  ByKind<std::size_t> counts{};
  for_each_kind([&]<class K>(K) { counts[kind_index(kind_tag<K>)] = (desc.*SceneEntries<K>::of).size(); });
  return counts;
}

ByKind<std::size_t> memory_by_kind(const GeometryLayer& g) {
  ByKind<std::size_t> bytes{};
  g.kinds.for_each([&]<class K>(K, const KindStore<K>& k) {
    bytes[kind_index(kind_tag<K>)] = k.store.memory_bytes() + bytes_of(k.origins);
  });
  return bytes;
}

// Each mesh file's faces as declared and as kept (SceneDesc::face_tallies).
void write_face_tallies(std::ostream& out, const SceneDesc& desc) {
  if (desc.face_tallies.empty()) return;
  out << "mesh faces      declared, kept\n";
  for (const FaceTally& t : desc.face_tallies) {
    out << "  " << t.file << ": " << t.declared << ", " << t.kept;
    if (t.declared > t.kept) out << " (" << t.declared - t.kept << " not drawn: see the warnings)";
    out << "\n";
  }
}

std::size_t peak_resident_bytes() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return std::size_t(usage.ru_maxrss) * 1024;
}

bool restart_resident_high_water() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5";  // 5: reset the peak resident set size
  clear_refs.flush();
  return clear_refs.good();
}

std::optional<std::size_t> process_status_bytes(std::string_view key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    const std::string_view text = line;
    if (!text.starts_with(key) || text.size() <= key.size() || text[key.size()] != ':') continue;
    const std::size_t digits = text.find_first_not_of(" \t", key.size() + 1);
    if (digits == std::string_view::npos) return std::nullopt;
    std::size_t kib = 0;
    const auto [end, error] = std::from_chars(text.data() + digits, text.data() + text.size(), kib);
    if (error != std::errc() || std::string_view(end, std::size_t(text.data() + text.size() - end)) != " kB") {
      return std::nullopt;
    }
    return kib * 1024;
  }
  return std::nullopt;
}

void write_scene_info(std::ostream& out, const SceneDesc& desc, const Scene& scene, const SceneInfoContext& context) {
  out << "scene           " << context.scene << "\n"
      << "load            " << milliseconds(context.load_ms) << "\n"
      << "build           " << milliseconds(context.build_ms) << "\n";
  write_primitives(out, desc, scene, context.read);
  write_face_tallies(out, desc);
  write_camera(out, scene, context.default_view);
  write_render_settings(out, desc.render);
  write_lights(out, desc, scene);
  write_materials(out, scene);
  write_textures(out, desc, scene);
  write_memory(out, scene);
  write_acceleration(out, scene);
  if (context.peak_resident_bytes) {
    out << "peak memory     " << *context.peak_resident_bytes << " bytes resident at most (loading and building), for "
        << scene.memory_bytes() + scene.acceleration_bytes() << " kept (memory and acceleration totals)\n";
  }
  if (context.build_peak_resident_bytes && context.build_start_resident_bytes) {
    out << "build peak      " << *context.build_peak_resident_bytes
        << " bytes resident at most while the scene was built, from " << *context.build_start_resident_bytes
        << " when it began (the scene as read)\n";
  }
}

}  // namespace quiver
