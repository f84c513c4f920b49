// The module's help texts, in NumPy's docstring style (a summary, then
// Parameters, Returns and Raises sections); pybind11 puts each function's
// signature above its text. docs/PYTHON.md says more of each.
#pragma once

namespace quiver::docstrings {

inline constexpr const char* kScene = R"(A scene built for queries and renders (quiver.load, quiver.from_arrays).

Attributes
----------
name : str
    The file it was read from, or "<arrays>".
primitive_count : int
    Primitives as built (degenerate ones dropped).
bounds : tuple
    ((xmin, ymin, zmin), (xmax, ymax, zmax)) of the bounded primitives.)";

inline constexpr const char* kIntersect = R"(Closest hits of rays in (tmin, tmax), as `quiver trace` finds them.

Parameters
----------
origins, directions : numpy.ndarray
    (N, 3) float32 or float64 arrays (one type for both), C-contiguous.
tmin, tmax : float
    The interval of the ray parameter; tmin finite and >= 0, tmax > tmin.
threads : int
    Worker threads, 0 for one per core (as --threads).
simd : str or None
    Lane width: auto, scalar, sse4, avx2 or avx512 (as --simd); every one gives the same hits.
points : bool
    Also return the hit points.

Returns
-------
dict
    t (N,) float32 (inf on a miss), primitive, kind and instance (N,) int32 (-1 on a miss),
    u, v (N,) float32, normal (N, 3) float32; with points, points (N, 3) float32:
    origin + t direction in double from the float32 ray (NaN on a miss).

Raises
------
ValueError
    Arrays of another shape, dtype or layout, a ray not finite in float32 or of zero direction, a bad interval.
quiver.UsageError
    threads or simd as the program would refuse them.)";

inline constexpr const char* kOccluded = R"(Whether anything lies in (tmin, tmax) along each ray.

Parameters
----------
origins, directions : numpy.ndarray
    (N, 3) float32 or float64 arrays, as for intersect.
tmin, tmax : float
    The interval of the ray parameter.
threads : int
    Worker threads, 0 for one per core.
simd : str or None
    Lane width, as for intersect.

Returns
-------
numpy.ndarray
    (N,) bool.

Raises
------
ValueError
    As for intersect.)";

inline constexpr const char* kToSrgb = R"(Linear values as the 8-bit sRGB codes quiver's PNG writer stores.

Parameters
----------
linear : array_like
    Linear values of any shape, such as quiver.render's image.

Returns
-------
numpy.ndarray
    uint8 codes of the same shape: the sRGB curve of each value clamped to [0, 1], to the nearest code; NaN is 0.)";

inline constexpr const char* kLoad = R"(Reads a scene file and builds it, as `quiver render` does.

Parameters
----------
path : str or os.PathLike
    A .nff, .toml, .obj, .ply, .gltf, .glb or .stl file.
crease_angle : float or None
    Smooth normals for meshes without them, 0 to 180 degrees (as --crease-angle).
allow_outside_paths : bool
    Let the scene name files outside its own folder (as --allow-outside-paths).

Returns
-------
quiver.Scene

Raises
------
quiver.ParseError
    A bad file: file:line:column: expected WHAT, found 'TOKEN'.)";

inline constexpr const char* kFromArrays = R"(A scene of spheres and triangles, each with one white material.

Parameters
----------
spheres : array_like or None
    (N, 4) rows of centre x, y, z and radius.
vertices : array_like or None
    (V, 3) vertex positions.
triangles : array_like or None
    (F, 3) int32 or int64 vertex indices into vertices.

Returns
-------
quiver.Scene

Raises
------
ValueError
    A value not finite in float32, a radius not above 0, an index outside [0, V).)";

inline constexpr const char* kRender = R"(Renders as `quiver render` does with the same options.

Parameters
----------
scene : quiver.Scene
width, height : int or None
    Image size in pixels; the scene camera's without them.
aa, max_depth, min_weight, threads, simd, seed, preset, two_sided, robust_methods, texture_filter
    As the flags of the same names (--aa, --max-depth, ...); None is the flag absent.
aov : str or None
    Extra outputs, any of "depth,normal,id".
look_from, look_at, up : str or sequence of 3 numbers or None
    The camera flags (--look-from, ...).
fov : float or None
    Field of view in degrees.

Returns
-------
quiver.Image
    The image, whatever the options: color (H, W, 3) float32 linear, row 0 at the top, and the AOVs
    asked for (depth, normal, kind, id; None otherwise); save(path) writes it as the program would.

Raises
------
quiver.UsageError
    An option the program would refuse, with its message.)";

inline constexpr const char* kFromDict = R"(A scene from a dict of the TOML scene format's keys (docs/PYTHON.md, io/README.md).

Parameters
----------
scene : dict
    Top-level keys (background, ambient), tables (camera, render) as dicts and arrays of tables
    (lights, textures, materials, spheres, planes, triangles, polygons, cylinders, cones, meshes,
    instances) as lists of dicts; values bool, int, float, str, os.PathLike, lists, tuples or NumPy
    arrays and scalars. A meshes or instances entry may give its mesh as NumPy arrays instead of a
    file: vertices (V, 3) and triangles (F, 3), with normals (V, 3) and uvs (V, 2) if wanted;
    entries giving the same array objects share one mesh.
base_dir : str or os.PathLike or None
    The folder relative file names (meshes, images) are resolved in; the current one without it.
    Unless allow_outside_paths, every file the scene names lies in it or below.
crease_angle : float or None
    As load's.
strict, allow_outside_paths : bool
    As --strict and --allow-outside-paths.

Returns
-------
quiver.Scene
    The scene as the TOML reader reads the dict's TOML form (Scene.to_toml writes that form).

Raises
------
TypeError
    A value with no TOML form (None, an object), named by its key ("spheres[2].radius").
ValueError
    A mesh's array of another shape or dtype, or an element not finite in float32 or not a vertex
    index, named ("meshes[0].triangles[4, 2]").
quiver.ParseError
    What the TOML reader refuses, with its message, at the dict's key ("<dict>: spheres[1].radius: expected ...").)";

inline constexpr const char* kToToml = R"(Writes a scene made by from_dict as the TOML file the CLI reads to the same scene.

Each mesh given as arrays is written beside it as <stem>_array_mesh_N.ply (binary PLY), which the
TOML text names.

Parameters
----------
path : str or os.PathLike
    A .toml file; in the scene's base_dir when the scene names files by relative paths.

Returns
-------
None

Raises
------
ValueError
    A scene not made by from_dict, another extension, or another folder than base_dir for a scene
    naming files.
OSError
    Writing failed (the files are written to temporary names and renamed over their targets).)";

inline constexpr const char* kImage = R"(An image quiver.render made: its colour and AOVs as NumPy views.

Attributes
----------
width, height : int
    The size in pixels.
color : numpy.ndarray
    (H, W, 3) float32 linear RGB, row 0 at the top.
depth : numpy.ndarray or None
    (H, W) float32 distance along the unit primary ray, inf on a miss (aov "depth").
normal : numpy.ndarray or None
    (H, W, 3) float32 unit shading normal facing the ray, 0 on a miss (aov "normal").
kind, id : numpy.ndarray or None
    (H, W) int32 primitive kind (an index into quiver.KINDS) and id in the whole scene, -1 on a
    miss (aov "id").

Notes
-----
The arrays are views of the image (writing to them changes what save writes); each keeps the
image alive.)";

inline constexpr const char* kImageSave = R"(Writes the image as `quiver render -o path` would with the same options.

Parameters
----------
path : str or os.PathLike
    .png, .jpg or .jpeg (8-bit sRGB) or .exr, .hdr, .tif or .tiff (32-bit float linear), any case;
    with AOVs, .exr (they become its Z, N.X N.Y N.Z, kind and id channels). Written to a temporary
    file and renamed over the target, so a failure leaves an existing file as it was.

Returns
-------
None

Raises
------
ValueError
    A path the program would refuse (its extension, AOVs in another format than EXR, a missing folder).
OSError
    Writing failed.)";

inline constexpr const char* kCameraRays = R"(The primary rays `quiver trace` casts, in its order.

Parameters
----------
scene : quiver.Scene
width, height : int or None
    Image size in pixels.
look_from, look_at, up : str or sequence of 3 numbers or None
    The camera flags.
fov : float or None
    Field of view in degrees.

Returns
-------
dict
    origins, directions (N, 3) float32, pixels (N, 2) int32, tile_starts (T + 1) int64, width, height.)";

}  // namespace quiver::docstrings
