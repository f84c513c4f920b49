"""How the Python module reads its arguments (python/arguments.h): camera
vectors as text, sequences or NumPy arrays of any real dtype, layout and
byte order give the same render as the text of their values; arrays of
every other dtype or layout, 0-d, empty, misaligned or of huge length, and
arguments of the wrong type raise a ValueError or TypeError naming the
argument, never a crash or another value. The NumPy-camera case also runs in
a child interpreter under PYTHONMALLOC=debug, where reading a freed object
(a NumPy array's items are temporaries) crashes at once."""
import array
import fractions
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import quiver
from support.python_support import TINY

REAL_DTYPES = ["int8", "int16", "int32", "int64", "uint8", "uint16", "uint32", "uint64",
               "float16", "float32", "float64", "longdouble", ">f8", ">i4", "<u2"]
OTHER_DTYPES = ["bool", "complex64", "complex128", "object", "U3", "S3", "datetime64[s]", "timedelta64[s]",
                "f4,f4,f4"]
GOOD = np.array([[0.0, 0.0, 5.0], [1.0, 0.0, 5.0]], dtype=np.float32)
DOWN = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, -1.0]], dtype=np.float32)


@pytest.fixture(scope="module")
def scene():
    return quiver.load(TINY)


@pytest.fixture(scope="module")
def spheres():
    return quiver.from_arrays(spheres=np.array([[0.0, 0.0, 0.0, 1.0]]))


def text(values):
    """The "x,y,z" flag text of three numbers (repr reads back to the same double)."""
    return ",".join(repr(float(v)) for v in values)


def render(scene, **camera):
    return quiver.render(scene, width=16, height=12, threads=1, **camera).color


def misaligned(values, dtype):
    """values as a C-contiguous array of dtype whose data starts one byte past an aligned address."""
    values = np.asarray(values, dtype=dtype)
    raw = np.zeros(values.nbytes + values.itemsize, dtype=np.uint8)
    start = 1 if raw.ctypes.data % values.itemsize == 0 else 0
    view = raw[start:start + values.nbytes].view(dtype).reshape(values.shape)
    view[...] = values
    assert not view.flags["ALIGNED"] and view.flags["C_CONTIGUOUS"]
    return view


def test_the_numpy_camera_renders_as_its_text(scene):
    image = quiver.render(scene, width=32, height=32, look_from=np.array([0, 0.1, 3.0]), look_at=(0, 0.1, 0)).color
    expected = quiver.render(scene, width=32, height=32, look_from="0,0.1,3", look_at="0,0.1,0").color
    np.testing.assert_array_equal(image, expected)
    # A later, unrelated allocation-heavy call: a heap written through a freed object fails here.
    assert [str(i) for i in range(10000)][-1] == "9999"
    np.testing.assert_array_equal(render(scene, look_from=np.array([1.0, 2.0, 8.0])), render(scene, look_from="1,2,8"))


def test_the_numpy_camera_survives_the_debug_allocator():
    child = ("import numpy as np, quiver\n"
             "scene = quiver.load(%r)\n"
             "for _ in range(20):\n"
             "    quiver.render(scene, width=32, height=32, look_from=np.array([0, 0.1, 3.0]), look_at=(0, 0.1, 0))\n"
             "    quiver.camera_rays(scene, width=8, height=8, up=np.array([0.0, 1.0, 0.0]))\n"
             "print('clean')\n" % TINY)
    # Under ASan (PYTHONMALLOC=malloc) the hooks go on malloc, which ASan watches.
    hooks = "malloc_debug" if os.environ.get("PYTHONMALLOC", "").startswith("malloc") else "debug"
    env = dict(os.environ, PYTHONMALLOC=hooks, PYTHONFAULTHANDLER="1")
    done = subprocess.run([sys.executable, "-c", child], env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and done.stdout.strip() == "clean", "exit %d\n%s" % (done.returncode, done.stderr)


@pytest.mark.parametrize("dtype", REAL_DTYPES)
def test_camera_arrays_of_every_real_dtype_render_as_their_values(scene, dtype):
    look_from = np.array([1, 2, 8], dtype=dtype)
    up = np.array([0, 1, 0], dtype=dtype)
    expected = render(scene, look_from=text(look_from), up=text(up))
    np.testing.assert_array_equal(render(scene, look_from=look_from, up=up), expected)
    if np.dtype(dtype).kind == "f":  # fractions, as the dtype rounds them
        values = np.array([0.1, 2.5, 7.75]).astype(dtype)
        np.testing.assert_array_equal(render(scene, look_from=values), render(scene, look_from=text(values)))


def test_camera_arrays_of_any_layout_render_as_their_values(scene):
    expected = render(scene, look_from="1,2,8", look_at="0,0.5,0")
    backing = np.array([1.0, -1, 2, -1, 8, -1])
    read_only = np.array([1.0, 2.0, 8.0])
    read_only.setflags(write=False)
    layouts = {
        "strided": backing[::2],
        "reversed": np.array([8.0, 2.0, 1.0])[::-1],
        "read-only": read_only,
        "misaligned": misaligned([1.0, 2.0, 8.0], np.float64),
        "Fortran": np.asfortranarray([1.0, 2.0, 8.0]),
        "a row of a Fortran matrix": np.asfortranarray([[1.0, 2.0, 8.0], [0, 0, 0]])[0],
    }
    for name, look_from in layouts.items():
        image = render(scene, look_from=look_from, look_at=np.array([0, 0.5, 0], dtype=np.float32))
        np.testing.assert_array_equal(image, expected, err_msg=name)


def test_camera_sequences_of_numbers_render_as_their_values(scene):
    expected = render(scene, look_from="1,2,8", up="0,1,0")
    sequences = [(1, 2, 8), [1.0, 2.0, 8.0], (1, 2, 8.0), array.array("d", [1, 2, 8]),
                 memoryview(array.array("i", [1, 2, 8])), [np.float32(1), np.int64(2), np.uint8(8)],
                 (fractions.Fraction(2, 2), 2, 8.0), [np.array(1.0), 2, 8]]
    for look_from in sequences:
        np.testing.assert_array_equal(render(scene, look_from=look_from, up=(0, 1, 0)), expected,
                                      err_msg=repr(look_from))


def refused_camera_vectors():
    """(value, words in the message) for values that are not three real numbers."""
    return [
        (5, "found an int"),
        (5.0, "found a float"),
        (b"1,2,8", "found a bytes"),
        (bytearray(b"128"), "found a bytearray"),
        ((1, 2), "found a tuple of 2 items"),
        ([1, 2, 8, 9], "found a list of 4 items"),
        ([], "found a list of 0 items"),
        (["1", "2", "8"], "found a list of 3 items, not all real numbers"),
        ([1, 2, 8j], "not all real numbers"),
        ([1, 2, None], "not all real numbers"),
        ([[1], [2], [8]], "not all real numbers"),
        ([1, 2, np.array([8.0, 9.0])], "not all real numbers"),
        ({"x": 1, "y": 2, "z": 8}, "found a dict"),
        ({1, 2, 8}, "found a set"),
        ((v for v in (1, 2, 8)), "found a generator"),
        (range(10**12), "found a range of 1000000000000 items"),
        (range(10**20), "found a range"),
        (np.float64(1.0), "found a float64"),
        (np.array(1.0), "found an array of shape () and dtype float64"),
        (np.zeros(0), "found an array of shape (0,) and dtype float64"),
        (np.zeros(4), "shape (4,)"),
        (np.zeros((3, 1)), "shape (3, 1)"),
        (np.zeros((1, 3)), "shape (1, 3)"),
        (np.broadcast_to(np.zeros(1), (2**40,)), "shape (1099511627776,)"),
    ] + [(np.zeros(3, dtype=dtype), "and dtype " + str(np.dtype(dtype))) for dtype in OTHER_DTYPES]


@pytest.mark.parametrize("name", ["look_from", "look_at", "up"])
def test_camera_values_that_are_not_three_real_numbers_raise_value_errors(scene, name):
    for value, words in refused_camera_vectors():
        for call in (render, quiver.camera_rays):
            with pytest.raises(ValueError) as error:
                call(scene, **{name: value})
            assert str(error.value).startswith(name + ': expected "x,y,z" or three real numbers, found '), repr(value)
            assert words in str(error.value), repr(value)


def test_camera_numbers_not_finite_in_float32_fail_as_the_cli_flag(scene):
    for value in [(0, float("nan"), 3), np.array([0, 0, np.inf]), [1e300, 0, 0]]:
        with pytest.raises(quiver.UsageError, match="--look-from: expected"):
            render(scene, look_from=value)


def test_camera_rays_read_numpy_vectors_as_their_text(scene):
    given = quiver.camera_rays(scene, width=8, height=8, look_from=np.array([1, 2, 8], dtype=np.int16),
                               up=np.array([0.0, 1.0, 0.0], dtype=np.float32))
    expected = quiver.camera_rays(scene, width=8, height=8, look_from="1,2,8", up="0,1,0")
    for key in ("origins", "directions", "pixels", "tile_starts"):
        np.testing.assert_array_equal(given[key], expected[key], err_msg=key)


@pytest.mark.parametrize("dtype", REAL_DTYPES[:8] + ["float16", "longdouble", ">f4", ">f8"] + OTHER_DTYPES)
def test_rays_of_other_dtypes_raise_value_errors(spheres, dtype):
    other = np.zeros(GOOD.shape, dtype=dtype)
    for origins, directions, which in [(other, DOWN, "origins"), (GOOD, other, "directions")]:
        for query in (spheres.intersect, spheres.occluded):
            with pytest.raises(ValueError, match=which + ": expected dtype float32 or float64"):
                query(origins, directions)


def refused_ray_layouts():
    """(origins, words in the message) for float32 arrays the queries cannot read in place."""
    return [
        (GOOD[::-1], "origins: expected a C-contiguous array"),
        (np.asfortranarray(GOOD), "origins: expected a C-contiguous array"),
        (np.zeros((2, 6), dtype=np.float32)[:, ::2], "found strides (24, 8)"),
        (misaligned(GOOD, np.float32), "origins: expected an aligned array"),
        (np.float32(1), "origins: expected a numpy.ndarray, found float32"),
        (np.array(1, dtype=np.float32), "origins: expected shape (N, 3), found ()"),
        (np.zeros((2, 3, 1), dtype=np.float32), "found (2, 3, 1)"),
        (np.zeros((0, 3), dtype=np.float32), "origins: expected at least one row"),
        (np.broadcast_to(GOOD[:1], (2**40, 3)), "origins: expected a C-contiguous array"),
        (None, "origins: expected a numpy.ndarray, found NoneType"),
        (tuple(map(tuple, GOOD)), "found tuple"),
    ]


def test_ray_layouts_not_read_in_place_raise_value_errors(spheres):
    for origins, words in refused_ray_layouts():  # origins are checked before directions
        for query in (spheres.intersect, spheres.occluded):
            with pytest.raises(ValueError) as error:
                query(origins, DOWN)
            assert words in str(error.value), words


def test_read_only_and_float64_rays_give_the_same_hits(spheres):
    reference = spheres.intersect(GOOD, DOWN)
    o, d = GOOD.copy(), DOWN.astype(np.float64)
    o.setflags(write=False)
    d.setflags(write=False)
    result = spheres.intersect(o.astype(np.float64), d)
    for key in reference:
        np.testing.assert_array_equal(result[key], reference[key], err_msg=key)
    np.testing.assert_array_equal(spheres.occluded(o, DOWN), spheres.occluded(GOOD, DOWN))
    assert reference["t"][0] == 4.0  # the first ray hits the sphere


def test_scene_arrays_of_other_dtypes_or_layouts_raise_value_errors():
    sphere = np.array([[0.0, 0.0, 0.0, 1.0]])
    vertices = np.eye(3)
    faces = np.array([[0, 1, 2]], dtype=np.int32)
    cases = [({"spheres": sphere.astype(d)}, "spheres: expected dtype float32 or float64") for d in
             ["int64", "float16", "longdouble", ">f8", "complex128", "object", "bool"]]
    cases += [({"vertices": vertices, "triangles": faces.astype(d)}, "triangles: expected dtype int32 or int64") for d in
              ["uint32", "int16", "uint64", ">i8", "float64", "object", "bool"]]
    cases += [
        ({"spheres": misaligned(sphere, np.float64)}, "spheres: expected an aligned array"),
        ({"vertices": misaligned(vertices, np.float32), "triangles": faces}, "vertices: expected an aligned array"),
        ({"vertices": vertices, "triangles": misaligned(faces, np.int32)}, "triangles: expected an aligned array"),
        ({"spheres": np.asfortranarray(np.ones((2, 4)))}, "spheres: expected a C-contiguous array"),
        ({"vertices": np.ones((3, 6))[:, ::2], "triangles": faces}, "vertices: expected a C-contiguous array"),
        ({"vertices": vertices, "triangles": np.asfortranarray(np.zeros((2, 3), np.int32))},
         "triangles: expected a C-contiguous array"),
        ({"vertices": vertices, "triangles": np.broadcast_to(faces, (2**40, 3))}, "triangles: expected a C-contiguous"),
        ({"spheres": np.array(1.0)}, "spheres: expected shape (N, 4), found ()"),
        ({"spheres": sphere.tolist()}, "spheres: expected a numpy.ndarray, found list"),
        ({"vertices": vertices, "triangles": [[0, 1, 2]]}, "triangles: expected a numpy.ndarray, found list"),
        ({"vertices": vertices, "triangles": np.zeros((0, 3), np.int32)}, "the arrays hold no primitive"),
    ]
    for kwargs, words in cases:
        with pytest.raises(ValueError) as error:
            quiver.from_arrays(**kwargs)
        assert words in str(error.value), words


def test_read_only_scene_arrays_build_the_same_scene():
    vertices = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    faces = np.array([[0, 1, 2]], dtype=np.int64)
    for given in (vertices, faces):
        given.setflags(write=False)
    scene = quiver.from_arrays(spheres=np.array([[5.0, 0.0, 0.0, 1.0]], dtype=np.float32), vertices=vertices,
                               triangles=faces)
    assert scene.primitive_count == 2
    hits = scene.intersect(np.array([[0.25, 0.25, 1.0], [5.0, 0.0, 3.0]]), np.array([[0.0, 0.0, -1.0]] * 2))
    np.testing.assert_array_equal(hits["kind"], [quiver.KINDS.index("triangle"), quiver.KINDS.index("sphere")])


def test_numpy_scalars_are_read_as_their_values(scene, spheres):
    np.testing.assert_array_equal(
        quiver.render(scene, width=np.int64(16), height=np.uint16(12), threads=np.int8(1), seed=np.uint64(7),
                      aa="jitter:2", min_weight=np.float32(0.25), fov=np.float16(50)).color,
        quiver.render(scene, width=16, height=12, threads=1, seed=7, aa="jitter:2", min_weight=0.25, fov=50.0).color)
    hits = spheres.intersect(GOOD, DOWN, tmin=np.float32(0.5), tmax=np.float64(4.5), threads=np.int32(1))
    np.testing.assert_array_equal(hits["t"], [4.0, np.inf])
    assert quiver.load(TINY, crease_angle=np.float32(30)).primitive_count == scene.primitive_count


def test_load_takes_str_and_path_like_paths(tmp_path):
    from_str = quiver.load(TINY)
    from_path = quiver.load(pathlib.Path(TINY))

    class PathLike:
        def __fspath__(self):
            return TINY

    from_path_like = quiver.load(PathLike())
    for scene in (from_path, from_path_like):
        assert scene.primitive_count == from_str.primitive_count and scene.bounds == from_str.bounds
    with pytest.raises(TypeError):
        quiver.load(3)
    with pytest.raises(quiver.ParseError):
        quiver.load(tmp_path / "missing.nff")


def test_arguments_of_the_wrong_type_raise_type_errors(scene, spheres):
    # Integers only through __index__: pybind11's int caster would truncate a
    # NumPy float or a size-1 array through int().
    wrong = [{"width": 16.0}, {"width": np.float32(16.5)}, {"height": np.float64(12)}, {"width": "16"},
             {"width": np.array([16])}, {"height": [12]}, {"threads": np.float32(1.5)}, {"max_depth": 2.5},
             {"seed": 7.0}, {"seed": "7"}, {"seed": np.float64(7)}, {"seed": np.array([7])}, {"aa": 2},
             {"min_weight": "0.5"}, {"fov": 1j}, {"two_sided": "no"}]
    for kwargs in wrong:
        with pytest.raises(TypeError):
            quiver.render(scene, **kwargs)
    for kwargs in [{"width": np.float32(8)}, {"height": 8.0}]:
        with pytest.raises(TypeError, match=next(iter(kwargs)) + ": expected an integer"):
            quiver.camera_rays(scene, **kwargs)
    for kwargs in [{"tmin": "0"}, {"tmax": None}, {"threads": np.float64(1)}, {"simd": 4}]:
        with pytest.raises(TypeError):
            spheres.intersect(GOOD, DOWN, **kwargs)
    with pytest.raises(OverflowError, match="width: expected an integer in the range of int32, found 1099511627776"):
        quiver.render(scene, width=2**40)
    with pytest.raises(OverflowError, match="threads: expected an integer in the range of int32"):
        spheres.occluded(GOOD, DOWN, threads=-2**70)
    with pytest.raises(quiver.UsageError, match="--seed: expected an integer in .0, 18446744073709551615., found '-1'"):
        quiver.render(scene, seed=np.int8(-1))
    for args in [(5,), (None,), (TINY, "30")]:
        with pytest.raises(TypeError):
            quiver.load(*args)
