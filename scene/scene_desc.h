// A scene as a reader found it: plain arrays of structs, already checked for
// syntax, finite numbers and sane bounds. Every format maps onto these native
// materials and lights (NFF's mapping is in io/README.md). Geometric
// degeneracy (zero radius, collinear vertices, ...) is left to the geometry
// builders, which drop and count it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/affine_transform.h"
#include "geometry/kinds.h"
#include "scene/anti_aliasing.h"
#include "simd/vec3.h"

namespace quiver {

// Largest image side and pixel count any scene or command line may ask for.
inline constexpr int kMaxImageSide = 65'536;
// The side of a scene's image when nothing gives one (no camera, or a glTF
// camera's longer side).
inline constexpr int kDefaultImageSide = 512;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 28;

// Pinhole camera: eye, look-at point, up hint (any length, not parallel to
// at - from), and the full field of view between the centres of the
// outermost pixel columns (rows when the image is taller than wide).
struct CameraDesc {
  Vec3<float> from, at, up;
  float angle_degrees;
  float hither;  // near-plane distance as written; the ray tracer ignores it
  int width, height;
};

// Lights. Intensity is an RGB colour (linear). Area lights are sampled with
// samples x samples stratified shadow rays.
struct LightDesc {
  enum class Kind { point, directional, rectangle, sphere, spot };
  Kind kind = Kind::point;
  Vec3<float> position{0.f, 0.f, 0.f};    // point, spot; rectangle corner; sphere centre
  Vec3<float> direction{0.f, -1.f, 0.f};  // directional, spot: the way the light travels
  // spot: cosines of the half-angles of the cone of full light and of the
  // cone beyond which none falls (inner > outer; integrator/light_cone.h).
  float cone_inner_cos = 1.f, cone_outer_cos = 0.70710678f;
  Vec3<float> edge_u{1.f, 0.f, 0.f};      // rectangle: corner + s*edge_u + t*edge_v
  Vec3<float> edge_v{0.f, 0.f, 1.f};
  float radius = 1.f;                      // sphere
  Vec3<float> color{1.f, 1.f, 1.f};
  int samples = 4;                         // area lights: per side

  // A rectangle or a sphere: sampled over its area, and seen by rays.
  bool is_area() const { return kind == Kind::rectangle || kind == Kind::sphere; }
};

enum class WrapMode { repeat, clamp, mirror };

// Where a scene file names a file that is read later (an image texture's),
// so that an error found then points there; line 0 when no file named it.
struct FilePosition {
  std::string file;
  std::size_t line = 0, column = 0;
};

// A texture: a 2D checkerboard over (u, v), a 3D solid checkerboard over the
// world position, or an image (a file, or pixels in memory for built-in scenes).
struct TextureDesc {
  enum class Kind { checker2d, checker3d, image };
  Kind kind = Kind::checker2d;
  Vec3<float> color_a{1.f, 1.f, 1.f}, color_b{0.f, 0.f, 0.f};  // checkers
  float scale = 1.f;  // checks per unit of (u, v) or of world space
  std::string path;   // image file; absolute or relative to the working directory
  FilePosition named_at;  // the text that names path
  WrapMode wrap = WrapMode::repeat;
  // In-memory image (used when path is empty): linear RGB, row 0 at v = 1.
  int width = 0, height = 0;
  std::vector<float> rgb;
  // An image file's bytes held in memory (a glTF's embedded image), decoded
  // into width, height and rgb like a file when the scene is loaded.
  std::vector<std::uint8_t> encoded;
};

// Whitted material: I = ka*Ia + sum f_i*I_i*(kd*(N.L) + ks*(N.H)^shininess)
// times the surface colour (texture when set) for ka and kd, plus kr times
// the reflected and kt times the refracted light. two_sided: the normal
// faces the ray on either side; a one-sided surface seen from behind gets
// the ambient term only.
struct MaterialDesc {
  Vec3<float> color{1.f, 1.f, 1.f};
  std::optional<std::size_t> texture{};  // index into SceneDesc::textures
  float ka = 0.1f, kd = 0.9f, ks = 0.f, shininess = 32.f, kr = 0.f, kt = 0.f, ior = 1.f;
  bool two_sided = true;
  // A dielectric's exact Fresnel reflectance F (unpolarised) splits kt:
  // F kt is reflected, (1 - F) kt refracted; off, kr and kt stay fixed (the
  // SPD procedure's Whitted model).
  bool fresnel = false;
};

// Render settings a scene file may carry; the command line overrides them.
// One bound and one default per setting, for the readers, the command line,
// quiver-mpi and Python alike.
struct RenderDesc {
  std::optional<AntiAliasing> aa;  // as --aa
  std::optional<int> max_depth;    // bounces after the primary ray, [0, kMaxMaxDepth]
  std::optional<float> min_weight;  // a reflection or refraction ray's largest RGB weight below this is not cast
};
inline constexpr int kDefaultMaxDepth = 5;
inline constexpr int kMaxMaxDepth = 64;
inline constexpr float kDefaultMinWeight = 1e-3f;
constexpr bool valid_max_depth(long long depth) { return depth >= 0 && depth <= kMaxMaxDepth; }
// A weight is a fraction of a ray's colour: 0 (every ray cast) to 1.
constexpr bool valid_min_weight(double weight) { return weight >= 0.0 && weight <= 1.0; }

// Primitives refer to materials by index into SceneDesc::materials.
struct SceneSphere {
  SphereDesc sphere;
  std::size_t material;
};

struct ScenePlane {
  PlaneDesc plane;
  std::size_t material;
};

struct SceneTriangle {
  TriangleDesc triangle;
  std::size_t material;
};

// A polygon; normals holds one shading normal per vertex for an NFF `pp`
// patch and is empty for a plain polygon.
struct ScenePolygon {
  PolygonDesc polygon;
  std::vector<Vec3<float>> normals;
  std::size_t material;
};

struct SceneCone {
  ConeDesc cone;
  std::size_t material;
};

// A mesh stored once and placed by instances: its triangles in its own
// coordinates; `name` says where it came from (for messages).
struct SceneMesh {
  std::string name;
  std::vector<SceneTriangle> triangles;
};

// One placement of SceneDesc::meshes[mesh]: world = object_to_world(p).
struct SceneInstance {
  std::size_t mesh;
  AffineTransform object_to_world;
};

// A mesh file's faces as it declares them and how many of them became
// triangles (`quiver info` prints both): OBJ's f, l and p statements; PLY's
// faces, strip triangles and edges; for STL and glTF, the triangles their
// facets or primitives declare and the points and lines Assimp returns.
struct FaceTally {
  std::string file;
  std::uint64_t declared = 0, kept = 0;
};

struct SceneDesc {
  std::optional<CameraDesc> camera;
  std::optional<Vec3<float>> background;  // none: black, or the default rig's grey
  Vec3<float> ambient{0.1f, 0.1f, 0.1f};  // Ia
  std::vector<LightDesc> lights;
  std::vector<MaterialDesc> materials;
  std::vector<TextureDesc> textures;
  std::vector<SceneSphere> spheres;
  std::vector<ScenePlane> planes;
  std::vector<SceneTriangle> triangles;
  std::vector<ScenePolygon> polygons;
  std::vector<SceneCone> cones;
  std::vector<SceneMesh> meshes;
  std::vector<SceneInstance> instances;
  RenderDesc render;
  // The model's up axis where its format states one (STL: +z), and which
  // convention that is, for the default view (scene/auto_view.h).
  struct StatedUp {
    Vec3<float> axis;
    std::string convention;
  };
  std::optional<StatedUp> model_up;
  std::vector<FaceTally> face_tallies;  // one per mesh file read, in reading order
  // The files the scene was read from, each once, in reading order: the
  // scene file, meshes, MTL libraries, and a glTF's buffer and image files
  // (texture images are also in textures[].path).
  std::vector<std::string> source_files;
  // What a forgiving reader let pass, one line each ("file:line:column:
  // warning: ..."; io/reader_warnings.h), for the program to show.
  std::vector<std::string> warnings;
};

// Each kind's entries in a SceneDesc and the description in an entry, for
// code that iterates the list of kinds (geometry/kinds.h).
template <class K>
struct SceneEntries;
template <>
struct SceneEntries<SphereKind> {
  static constexpr auto of = &SceneDesc::spheres;
  static constexpr auto desc = &SceneSphere::sphere;
};
template <>
struct SceneEntries<PlaneKind> {
  static constexpr auto of = &SceneDesc::planes;
  static constexpr auto desc = &ScenePlane::plane;
};
template <>
struct SceneEntries<TriangleKind> {
  static constexpr auto of = &SceneDesc::triangles;
  static constexpr auto desc = &SceneTriangle::triangle;
};
template <>
struct SceneEntries<PolygonKind> {
  static constexpr auto of = &SceneDesc::polygons;
  static constexpr auto desc = &ScenePolygon::polygon;
};
template <>
struct SceneEntries<ConeKind> {
  static constexpr auto of = &SceneDesc::cones;
  static constexpr auto desc = &SceneCone::cone;
};

}  // namespace quiver
