"""Whole scenes from Python (quiver.from_dict, Scene.to_toml;
python/scene_dict.h): a dict holding every table of the TOML format renders
as the TOML file to_toml writes renders through the CLI, byte for byte;
what the TOML reader refuses is refused with its message at the dict's key;
values with no TOML form are TypeErrors naming their key; sizes are bounded
before anything is built; to_toml writes only where the scene's file names
resolve, and atomically."""
import os

import numpy as np
import pytest

import quiver
from support.python_support import TINY, run_cli

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "io", "examples")


def every_table():
    """A scene with every table and kind the TOML format has (files from io/examples)."""
    return {
        "background": [0.1, 0.1, 0.12],
        "ambient": (0.1, 0.1, 0.1),
        "camera": {"from": np.array([0.5, 3.0, 8.0]), "at": [0, 0.8, 0], "up": [0, 1, 0], "fov": np.float64(45),
                   "width": 48, "height": 36},
        "render": {"aa": "grid:2", "max_depth": 3, "min_weight": 0.01},
        "lights": [{"position": [4, 7, 5], "color": [0.5, 0.5, 0.5]},
                   {"type": "directional", "direction": [-1, -2, -1], "color": [0.2, 0.2, 0.2]},
                   {"type": "spot", "position": [0, 6, 0], "direction": [0, -1, 0], "outer_angle": 30},
                   {"type": "rectangle", "corner": [-2, 5, 2], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
                    "samples": 2},
                   {"type": "sphere", "center": [2, 5, 2], "radius": 0.5, "samples": 2}],
        "textures": [{"name": "checks", "type": "checker2d", "colors": [[0.9, 0.9, 0.9], [0.2, 0.3, 0.6]],
                      "scale": 8},
                     {"name": "solid", "type": "checker3d", "colors": [[0.95, 0.8, 0.2], [0.6, 0.1, 0.1]]},
                     {"name": "gradient", "type": "image", "file": "gradient.png", "wrap": "clamp"}],
        "materials": [{"name": "floor", "texture": "checks"},
                      {"name": "carved", "texture": "solid", "ks": 0.3, "shininess": 50},
                      {"name": "picture", "texture": "gradient"},
                      {"name": "glass", "color": [0.9, 0.95, 1.0], "kd": 0.05, "kt": 0.85, "ior": 1.5}],
        "planes": [{"point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"}],
        "spheres": [{"center": [1.5, 0.6, 0], "radius": np.float32(0.6), "material": "glass"}],
        "triangles": [{"vertices": [[-3, 0.01, -2], [-1, 0.01, -2], [-2, 1.5, -2]], "material": "picture"}],
        "polygons": [{"vertices": np.array([[-3, 0.02, 1], [-2, 0.02, 1], [-2, 0.02, 2], [-3, 0.02, 2]])}],
        "cylinders": [{"base": [0, 0, -1.5], "apex": [0, 1.2, -1.5], "radius": 0.3, "material": "carved"}],
        "cones": [{"base": [2, 0, -2], "apex": [2, 1, -2], "base_radius": 0.4, "apex_radius": 0.1}],
        "meshes": [{"file": "octahedron.obj", "scale": 0.3, "translate": [-1, 0.3, 0.5]}],
        "instances": [{"file": "octahedron.obj", "scale": 0.25, "rotate": [0, 15 * k, 0],
                       "translate": [k * 0.6 - 1.5, 0.25, 2.5]} for k in range(6)],
    }


def test_a_dict_scene_renders_as_its_toml_file_through_the_cli(tmp_path):
    scene = quiver.from_dict(every_table(), base_dir=EXAMPLES)
    assert scene.name == "<dict>"
    image = quiver.render(scene)
    assert (image.width, image.height) == (48, 36) and image.color.any()
    image.save(tmp_path / "python.png")
    toml = os.path.join(EXAMPLES, "python_dict_test_%d.toml" % os.getpid())
    try:
        scene.to_toml(toml)
        code, _, err = run_cli("render", toml, "-o", str(tmp_path / "cli.png"), "-q")
        assert code == 0, err
        assert quiver.load(toml).primitive_count == scene.primitive_count
    finally:
        if os.path.exists(toml):
            os.remove(toml)
    assert (tmp_path / "python.png").read_bytes() == (tmp_path / "cli.png").read_bytes()


def test_the_readers_refusals_name_the_dicts_key():
    scene = {"spheres": [{"center": [0, 0, 0], "radius": 1.0}, {"center": [0, 0, 0], "radius": -1.0}]}
    with pytest.raises(quiver.ParseError, match=r"^<dict>: spheres\[1\]\.radius: expected a number > 0"):
        quiver.from_dict(scene)
    with pytest.raises(quiver.ParseError, match=r"^<dict>: spheres\[0\]\.radios: expected"):
        quiver.from_dict({"spheres": [{"center": [0, 0, 0], "radios": 1.0}]})
    with pytest.raises(quiver.ParseError, match=r"^<dict>: camera\.fov: expected"):
        quiver.from_dict({"camera": {"from": [0, 0, 5], "at": [0, 0, 0], "fov": 180}, **scene})
    with pytest.raises(quiver.ParseError, match="no objects"):
        quiver.from_dict({})
    with pytest.raises(quiver.ParseError, match=r"^<dict>: meshes\[0\]\.file: .*inside the scene's folder"):
        quiver.from_dict({"meshes": [{"file": os.path.abspath(os.path.join(EXAMPLES, "octahedron.obj"))}]},
                         base_dir=os.path.dirname(TINY))
    allowed = quiver.from_dict({"meshes": [{"file": os.path.abspath(os.path.join(EXAMPLES, "octahedron.obj"))}]},
                               base_dir=os.path.dirname(TINY), allow_outside_paths=True)
    assert allowed.primitive_count == 8


def test_values_without_a_toml_form_are_type_errors_naming_their_key():
    for value, words in [(None, "NoneType"), (object(), "object"), ({1: 2}, "keys must be str"),
                         (np.array([1 + 2j]), "complex")]:
        with pytest.raises(TypeError, match=r"^spheres\[0\]\.radius"):
            quiver.from_dict({"spheres": [{"center": [0, 0, 0], "radius": value}]})
    with pytest.raises(TypeError, match="expected a dict"):
        quiver.from_dict([1, 2, 3])
    with pytest.raises(ValueError, match="64-bit"):
        quiver.from_dict({"spheres": [{"center": [0, 0, 0], "radius": 2**70}]})


def test_sizes_are_bounded_before_anything_is_built():
    deep = {"spheres": []}
    for _ in range(40):
        deep = {"x": deep}
    with pytest.raises(ValueError, match="nested deeper"):
        quiver.from_dict(deep)
    with pytest.raises(ValueError, match="at most"):
        quiver.from_dict({"polygons": [{"vertices": np.zeros((400000, 3))}]})


def test_the_depth_bound_itself_passes_and_one_level_more_does_not():
    # A sphere's centre coordinate lies L + 4 levels down under L wrapping
    # dicts (then the spheres list, the sphere, its centre list): 32 levels
    # pass the depth bound (and the scene is refused for its key 'x'), 33 do not.
    def wrapped(levels):
        scene = {"spheres": [{"center": [0, 0, 0], "radius": 1}]}
        for _ in range(levels):
            scene = {"x": scene}
        return scene

    with pytest.raises(ValueError) as at_bound:
        quiver.from_dict(wrapped(28))
    assert "nested deeper" not in str(at_bound.value)
    assert "found 'x'" in str(at_bound.value)
    with pytest.raises(ValueError, match=r"spheres\[0\]\.center\[0\]: nested deeper than 32 levels"):
        quiver.from_dict(wrapped(29))


def test_the_value_bound_is_the_toml_readers_and_the_bound_itself_passes():
    # Values counted as the TOML reader counts its nodes: the root table, the
    # key polygons, its one table, the key vertices, each vertex's list and
    # its three numbers: 4 + 4 n.
    bound = 1 << 19  # io/toml_reader.h's kMaxTomlNodes
    n = (bound - 4) // 4
    assert 4 + 4 * n == bound

    def error_of(rows):
        try:
            quiver.from_dict({"polygons": [{"vertices": np.zeros((rows, 3))}]})
        except ValueError as error:  # quiver.ParseError is one too
            return str(error)
        return ""

    assert error_of(n + 1).startswith("polygons[0].vertices[%d]: a scene holds at most %d values" % (n, bound))
    assert error_of(n) == ""  # the bound itself: converted, and read by the TOML reader


def test_an_error_in_a_row_of_a_long_array_names_the_arrays_key():
    vertices = np.random.default_rng(0).random((100, 3))  # toml++ writes it one row per line
    vertices[57, 1] = np.inf
    with pytest.raises(quiver.ParseError, match=r"^<dict>: polygons\[0\]\.vertices: expected a finite number"):
        quiver.from_dict({"polygons": [{"vertices": vertices}]})


def test_to_toml_writes_only_where_the_files_it_names_resolve(tmp_path):
    with pytest.raises(ValueError, match="from_dict"):
        quiver.load(TINY).to_toml(tmp_path / "tiny.toml")
    spheres = quiver.from_dict({"spheres": [{"center": [0, 0, 0], "radius": 1.0}]})
    with pytest.raises(ValueError, match=r"\.toml"):
        spheres.to_toml(tmp_path / "scene.txt")
    spheres.to_toml(tmp_path / "anywhere.toml")  # names no file: any folder
    assert quiver.load(tmp_path / "anywhere.toml").primitive_count == 1
    with_mesh = quiver.from_dict({"meshes": [{"file": "octahedron.obj"}]}, base_dir=EXAMPLES)
    with pytest.raises(ValueError, match="base_dir"):
        with_mesh.to_toml(tmp_path / "elsewhere.toml")
    assert not (tmp_path / "elsewhere.toml").exists()
    with pytest.raises(OSError):
        spheres.to_toml(tmp_path / "missing-folder" / "x.toml")


def wavy_grid(n=6):
    """A bumpy n x n grid of quads as vertices, triangles, normals and uvs (float64, int64)."""
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    vertices = np.stack([u.ravel() * 2 - 1, 0.15 * np.sin(6 * u.ravel()) * np.cos(5 * v.ravel()), v.ravel() - 1], 1)
    normals = np.tile([0.0, 1.0, 0.0], (n * n, 1))
    uvs = np.stack([u.ravel(), v.ravel()], 1)
    quads = [(r * n + c, r * n + c + 1, (r + 1) * n + c + 1, (r + 1) * n + c) for r in range(n - 1) for c in range(n - 1)]
    triangles = np.array([t for a, b, c, d in quads for t in ((a, d, b), (b, d, c))], dtype=np.int64)
    return vertices, triangles, normals, uvs


def array_mesh_scene():
    vertices, triangles, normals, uvs = wavy_grid()
    return {
        "camera": {"from": [0, 2.5, 2.5], "at": [0, 0, -0.5], "up": [0, 1, 0], "fov": 50, "width": 40, "height": 30},
        "lights": [{"position": [2, 4, 3], "color": [0.8, 0.8, 0.8]}],
        "textures": [{"name": "checks", "type": "checker2d", "colors": [[0.9, 0.9, 0.9], [0.2, 0.3, 0.6]],
                      "scale": 4}],
        "materials": [{"name": "checked", "texture": "checks"}, {"name": "red", "color": [0.9, 0.2, 0.1]}],
        "meshes": [{"vertices": vertices, "triangles": triangles, "uvs": uvs, "material": "checked"},
                   {"vertices": vertices.astype(np.float32), "triangles": triangles.astype(np.int32),
                    "normals": normals, "translate": [0, 0.5, 0], "scale": 0.3, "material": "red"}],
        "instances": [{"vertices": vertices, "triangles": triangles, "uvs": uvs, "scale": 0.2,
                       "translate": [0.5 * k - 0.5, 0.8, 0]} for k in range(3)],
    }


def test_meshes_from_arrays_render_as_the_files_to_toml_writes_beside_it(tmp_path):
    scene = quiver.from_dict(array_mesh_scene())
    vertices, triangles, _, _ = wavy_grid()
    assert scene.primitive_count == 2 * len(triangles) + len(triangles)  # two meshes, one instanced mesh
    image = quiver.render(scene)
    assert image.color.any()
    image.save(tmp_path / "python.png")
    scene.to_toml(tmp_path / "it's here.toml")
    written = sorted(p.name for p in tmp_path.iterdir())
    # The instances give the first mesh's array objects: two files for the five entries.
    assert written == ["it's here.toml", "it's here_array_mesh_0.ply", "it's here_array_mesh_1.ply", "python.png"]
    code, _, err = run_cli("render", tmp_path / "it's here.toml", "-o", tmp_path / "cli.png", "-q")
    assert code == 0, err
    assert (tmp_path / "python.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    # The file form reads back to the same arrays: float32 positions and the same indices.
    reread = quiver.from_dict({"meshes": [{"file": "it's here_array_mesh_0.ply"}]}, base_dir=tmp_path)
    hits = reread.intersect(np.array([[0.0, 5.0, -0.5]]), np.array([[0.0, -1.0, 0.0]]))
    direct = quiver.from_dict({"meshes": [{"vertices": vertices, "triangles": triangles}]})
    assert hits["t"][0] == direct.intersect(np.array([[0.0, 5.0, -0.5]]), np.array([[0.0, -1.0, 0.0]]))["t"][0]


def test_array_meshes_are_checked_and_their_errors_name_the_element():
    vertices, triangles, normals, _ = wavy_grid()
    bad = triangles.copy()
    bad[4, 2] = len(vertices)
    cases = [
        ({"vertices": vertices, "triangles": bad}, ValueError, r"meshes\[0\]\.triangles\[4, 2\] = 36: expected a vertex"),
        ({"vertices": np.where(np.arange(108).reshape(36, 3) == 7, 1e39, vertices), "triangles": triangles},
         ValueError, r"meshes\[0\]\.vertices\[2, 1\] = .* not finite in float32"),
        ({"vertices": vertices, "triangles": triangles, "normals": normals[:5]}, ValueError,
         r"meshes\[0\]\.normals: expected one row per vertex \(36\), found 5"),
        ({"vertices": vertices, "triangles": triangles, "uvs": vertices}, ValueError, r"meshes\[0\]\.uvs"),
        ({"vertices": vertices}, ValueError, r"meshes\[0\]: vertices need triangles"),
        ({"vertices": vertices, "triangles": triangles, "file": "x.ply"}, ValueError, "not both"),
        ({"vertices": vertices.tolist(), "triangles": triangles}, ValueError, r"meshes\[0\]\.vertices"),
        ({"vertices": vertices, "triangles": triangles.astype(np.float64)}, ValueError, r"meshes\[0\]\.triangles"),
        ({"vertices": vertices, "triangles": triangles, "colour": 1}, quiver.ParseError, r"meshes\[0\]\.colour"),
    ]
    for entry, error, message in cases:
        with pytest.raises(error, match=message):
            quiver.from_dict({"meshes": [entry]})
    with pytest.raises(quiver.ParseError, match=r"vertices"):  # arrays only where a mesh file could be named
        quiver.from_dict({"spheres": [{"center": [0, 0, 0], "radius": 1, "vertices": vertices}]})
