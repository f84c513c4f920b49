"""Hostile input to the Python module: arrays of the wrong shape, dtype,
layout or values, bad arguments and bad scene files all raise a clear
exception (never a crash), scene-file errors carry the CLI's own
file:line:column text, and 1,000 calls leave the process no bigger."""
import os
import tempfile

import numpy as np
import pytest

import quiver
from support.python_support import TINY, cli_error

GOOD = np.array([[0.0, 0.0, 5.0], [1.0, 0.0, 5.0]], dtype=np.float32)
DOWN = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, -1.0]], dtype=np.float32)


@pytest.fixture(scope="module")
def scene():
    return quiver.from_arrays(spheres=np.array([[0.0, 0.0, 0.0, 1.0]]))


def bad_calls(scene):
    """(description, origins, directions, kwargs, expected words in the message)."""
    nan = GOOD.copy()
    nan[1, 2] = np.nan
    inf = DOWN.copy()
    inf[0, 0] = np.inf
    zero = DOWN.copy()
    zero[1] = 0.0
    huge = GOOD.astype(np.float64)
    huge[0, 1] = 1e300
    wide = np.zeros((2, 6), dtype=np.float32)
    return [
        ("wrong shape", GOOD[:, :2], DOWN, {}, "origins: expected shape (N, 3), found (2, 2)"),
        ("one dimension", GOOD.ravel(), DOWN, {}, "found (6,)"),
        ("wrong dtype", GOOD.astype(np.int32), DOWN, {}, "origins: expected dtype float32 or float64"),
        ("half floats", GOOD, DOWN.astype(np.float16), {}, "directions: expected dtype float32 or float64"),
        ("byte-swapped", GOOD.astype(">f4"), DOWN, {}, "native byte order"),
        ("NaN origin", nan, DOWN, {}, "origins[1] = (1, 0, nan) is not finite"),
        ("inf direction", GOOD, inf, {}, "directions[0] = (inf, 0, -1) is not finite"),
        ("zero direction", GOOD, zero, {}, "directions[1] is (0, 0, 0)"),
        ("float64 beyond float32", huge, DOWN.astype(np.float64), {}, "origins[0] = (0, inf, 5) is not finite in float32"),
        ("non-contiguous", wide[:, ::2], DOWN, {}, "origins: expected a C-contiguous array"),
        ("Fortran order", np.asfortranarray(GOOD), DOWN, {}, "C-contiguous"),
        ("empty", GOOD[:0], DOWN[:0], {}, "origins: expected at least one row, found shape (0, 3)"),
        ("counts differ", GOOD, DOWN[:1], {}, "the same number of rays"),
        ("dtypes differ", GOOD, DOWN.astype(np.float64), {}, "one dtype for both"),
        ("a list", GOOD.tolist(), DOWN, {}, "origins: expected a numpy.ndarray, found list"),
        ("negative tmin", GOOD, DOWN, {"tmin": -1.0}, "tmin: expected a finite number >= 0"),
        ("NaN tmin", GOOD, DOWN, {"tmin": float("nan")}, "tmin: expected a finite number >= 0"),
        ("tmax not above tmin", GOOD, DOWN, {"tmin": 2.0, "tmax": 2.0}, "tmax: expected a number greater than tmin"),
        ("NaN tmax", GOOD, DOWN, {"tmax": float("nan")}, "tmax: expected a number greater than tmin"),
        ("threads", GOOD, DOWN, {"threads": -1}, "--threads: expected an integer in [0, 1024], found -1"),
        ("simd", GOOD, DOWN, {"simd": "mmx"}, "--simd"),
    ]


@pytest.mark.parametrize("query", ["intersect", "occluded"])
def test_bad_rays_and_arguments_raise_value_errors_saying_what_is_wrong(scene, query):
    for description, origins, directions, kwargs, words in bad_calls(scene):
        with pytest.raises(ValueError) as error:
            getattr(scene, query)(origins, directions, **kwargs)
        assert words in str(error.value), description


def test_the_options_fail_as_the_cli_flags_do(scene):
    with pytest.raises(quiver.UsageError) as error:
        scene.intersect(GOOD, DOWN, simd="mmx")
    assert str(error.value) == cli_error("trace", TINY, "--simd", "mmx")
    with pytest.raises(quiver.UsageError) as error:
        quiver.render(scene, width=0)
    assert str(error.value) == cli_error("render", TINY, "--width", "0", "-o", "unused.png")


def write(folder, name, text):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def test_scene_file_errors_carry_the_cli_text():
    with tempfile.TemporaryDirectory() as folder:
        cases = [
            write(folder, "bad.nff", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\n"
                  "f 1 1 1 1 0 0 0 1\ns 0 0 x 1\n"),
            write(folder, "bad.toml", "[[spheres]]\ncenter = [0, 0]\nradius = 1\n"),
            write(folder, "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n"),
            write(folder, "bad.ply", "ply\nformat ascii 1.0\nelement vertex 99\nproperty float x\nend_header\n0\n"),
            os.path.join(folder, "absent.nff"),
            write(folder, "scene.xyz", "nothing"),
        ]
        for path in cases:
            with pytest.raises(quiver.ParseError) as error:
                quiver.load(path)
            assert isinstance(error.value, ValueError)
            assert str(error.value) == cli_error("info", path), path
            assert str(error.value).startswith(path)
        # PLY, glTF and STL go through the Assimp module from Python too.
        roof = os.path.join(os.environ["QUIVER_TEST_DATA_DIR"], "mesh", "roof.ply")
        assert "2 primitives" in repr(quiver.load(roof))
        # A file:line:column position where the error has one.
        with pytest.raises(quiver.ParseError) as error:
            quiver.load(cases[0])
        column = "s 0 0 x 1".index("x") + 1
        assert str(error.value).startswith("%s:9:%d: " % (cases[0], column))


def test_bad_scene_arrays_raise_value_errors():
    tri = np.array([[0, 1, 2]], dtype=np.int32)
    verts = np.eye(3)
    cases = [
        ({"spheres": np.array([[0.0, 0.0, np.nan, 1.0]])}, "spheres[0, 2] = nan is not finite in float32"),
        ({"spheres": np.array([[0.0, 0.0, 0.0, -1.0]])}, "spheres[0, 3] = -1.000000: expected a radius > 0"),
        # The bound itself: a radius of zero (of either sign) is no sphere.
        ({"spheres": np.array([[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0]])},
         "spheres[1, 3] = 0.000000: expected a radius > 0"),
        ({"spheres": np.array([[0.0, 0.0, 0.0, -0.0]])}, "spheres[0, 3] = -0.000000: expected a radius > 0"),
        ({"spheres": np.zeros((2, 3))}, "spheres: expected shape (N, 4), found (2, 3)"),
        ({"spheres": np.zeros((0, 4))}, "the arrays hold no primitive"),
        ({}, "the arrays hold no primitive"),
        ({"vertices": verts}, "give both"),
        ({"vertices": verts, "triangles": np.array([[0, 1, 3]], dtype=np.int32)},
         "triangles[0, 2] = 3: expected a vertex index in [0, 3)"),
        ({"vertices": verts, "triangles": np.array([[0, -1, 2]])}, "triangles[0, 1] = -1"),
        ({"vertices": verts, "triangles": tri.astype(np.float32)}, "triangles: expected dtype int32 or int64"),
        ({"vertices": verts, "triangles": np.zeros((1, 4), dtype=np.int32)}, "triangles: expected shape (F, 3)"),
        ({"vertices": np.array([[0, 0, 0], [1, np.inf, 0], [0, 1, 0]]), "triangles": tri}, "vertices[1, 1] = inf"),
    ]
    for kwargs, words in cases:
        with pytest.raises(ValueError) as error:
            quiver.from_arrays(**kwargs)
        assert words in str(error.value), kwargs


def resident_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    pytest.skip("no VmRSS in /proc/self/status")


def test_a_thousand_calls_leave_the_process_no_bigger():
    if "libasan" in os.environ.get("LD_PRELOAD", ""):
        pytest.skip("under ASan (the sanitize preset) freed memory stays resident in its quarantine by design")
    scene = quiver.load(TINY)
    rays = quiver.camera_rays(scene, width=100, height=100)
    o, d = rays["origins"], rays["directions"]
    bad = o.copy()
    bad[5000, 0] = np.nan

    def calls():
        result = scene.intersect(o, d)
        scene.occluded(o, d)
        with pytest.raises(ValueError):
            scene.intersect(bad, d)
        quiver.render(scene, width=8, height=6)
        return result

    for _ in range(50):  # warm up: thread pools, allocator caches
        calls()
    before = resident_kib()
    for _ in range(1000):
        calls()
    grown = resident_kib() - before
    # One call's outputs are 10,000 rays x 33 bytes (320 KiB); a leak of them
    # alone would grow the process by about 320 MiB over 1,000 calls.
    assert grown < 16 * 1024, "resident size grew by %d KiB over 1,000 calls" % grown
