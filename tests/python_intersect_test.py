"""scene.intersect and scene.occluded (python/ray_queries.h): the same hits
as `quiver trace` on its own rays (quiver.camera_rays), bit for bit, for
every SIMD width and thread count; hits that agree with the geometry of
scenes built from arrays; misses as inf and -1; occluded agreeing with
intersect."""
import os
import shutil
import sys

import numpy as np
import pytest

import quiver
from support.python_support import DATA, TINY, shared_file, trace_json

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
from trace_totals import trace_totals  # noqa: E402

SIMD = ["scalar", "sse4", "auto"]


@pytest.mark.parametrize("simd", SIMD)
@pytest.mark.parametrize("size", [(48, 32), (37, 21)])
def test_camera_rays_hit_as_quiver_trace(simd, size):
    width, height = size
    scene = quiver.load(TINY)
    rays = quiver.camera_rays(scene, width=width, height=height)
    assert rays["origins"].shape == (width * height, 3)
    result = scene.intersect(rays["origins"], rays["directions"], simd=simd)
    hits, t_sum = trace_totals(result, rays["tile_starts"])
    expected = trace_json(TINY, "--width", width, "--height", height, "--repeat", 1, "--simd", simd)
    assert expected["rays"] == width * height
    assert hits == expected["hits"]
    assert t_sum == expected["t_sum"]
    assert 0 < hits < width * height  # the view shows the scene and the background


def test_bunny_camera_rays_hit_as_quiver_trace():
    bunny = shared_file("meshes", "stanford-bunny.obj")
    scene = quiver.load(bunny)
    rays = quiver.camera_rays(scene, width=160, height=128)
    result = scene.intersect(rays["origins"], rays["directions"])
    assert (result["kind"][result["kind"] >= 0] == quiver.KINDS.index("triangle")).all()
    hits, t_sum = trace_totals(result, rays["tile_starts"])
    expected = trace_json(bunny, "--width", 160, "--height", 128, "--repeat", 1)
    assert (hits, t_sum) == (expected["hits"], expected["t_sum"])


def test_every_width_thread_count_and_float64_input_give_the_same_hits():
    scene = quiver.load(TINY)
    rays = quiver.camera_rays(scene, width=40, height=30)
    o, d = rays["origins"], rays["directions"]
    reference = scene.intersect(o, d, simd="scalar", threads=1)
    for simd, threads in [("sse4", 2), ("auto", 0), ("auto", 1)]:
        result = scene.intersect(o, d, simd=simd, threads=threads)
        for key in reference:
            np.testing.assert_array_equal(result[key], reference[key], err_msg=key)
    as_float64 = scene.intersect(o.astype(np.float64), d.astype(np.float64))
    for key in reference:
        np.testing.assert_array_equal(as_float64[key], reference[key], err_msg=key)


def test_spheres_from_arrays_are_hit_where_the_geometry_says():
    rng = np.random.default_rng(3)
    gx, gy = np.meshgrid(np.arange(8) * 3.0, np.arange(6) * 3.0)
    n = gx.size
    centres = np.column_stack([gx.ravel(), gy.ravel(), rng.uniform(-1, 1, n)])
    radii = rng.uniform(0.2, 1.0, n)
    scene = quiver.from_arrays(spheres=np.column_stack([centres, radii]))
    # Straight down -z from z = 100, off each centre by a fraction of its radius in y.
    offset = rng.uniform(-0.9, 0.9, n) * radii
    origins = centres + np.column_stack([np.zeros(n), offset, 100.0 - centres[:, 2]])
    directions = np.tile([0.0, 0.0, -1.0], (n, 1))
    result = scene.intersect(origins, directions)
    height = np.sqrt(radii ** 2 - offset ** 2)
    np.testing.assert_array_equal(result["primitive"], np.arange(n))
    np.testing.assert_array_equal(result["kind"], quiver.KINDS.index("sphere"))
    np.testing.assert_allclose(result["t"], 100.0 - centres[:, 2] - height, rtol=1e-5)
    expected_normal = np.column_stack([np.zeros(n), offset, height]) / radii[:, None]
    np.testing.assert_allclose(result["normal"], expected_normal, atol=1e-4)


def test_triangles_from_arrays_report_barycentrics_and_face_index():
    vertices = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [5, 0, 1], [7, 0, 1], [5, 2, 1]], dtype=np.float32)
    faces = np.array([[0, 1, 2], [3, 4, 5]], dtype=np.int64)
    scene = quiver.from_arrays(vertices=vertices, triangles=faces)
    rng = np.random.default_rng(5)
    weights = rng.dirichlet([1, 1, 1], size=200)
    face = rng.integers(0, 2, size=200)
    targets = np.einsum("nk,nkc->nc", weights, vertices[faces[face]].astype(np.float64))
    origins = targets.copy()
    origins[:, 2] = 10.0
    directions = np.tile([0.0, 0.0, -1.0], (200, 1))
    result = scene.intersect(origins, directions)
    np.testing.assert_array_equal(result["primitive"], face)
    np.testing.assert_array_equal(result["kind"], quiver.KINDS.index("triangle"))
    np.testing.assert_allclose(result["t"], 10.0 - targets[:, 2], rtol=1e-6)
    u, v = result["u"].astype(np.float64), result["v"].astype(np.float64)
    p = vertices[faces[face]].astype(np.float64)
    rebuilt = (1 - u - v)[:, None] * p[:, 0] + u[:, None] * p[:, 1] + v[:, None] * p[:, 2]
    np.testing.assert_allclose(rebuilt, targets, atol=1e-5)
    np.testing.assert_allclose(np.abs(result["normal"][:, 2]), 1.0, rtol=1e-6)


def test_a_scene_naming_a_file_outside_its_folder_needs_allow_outside_paths(tmp_path):
    (tmp_path / "scene").mkdir()
    mesh = os.path.abspath(os.path.join(DATA, "obj", "roof.obj"))
    scene_file = tmp_path / "scene" / "outside.toml"
    scene_file.write_text('[[meshes]]\nfile = "%s"\n' % mesh)
    with pytest.raises(quiver.ParseError, match="inside the scene's folder"):
        quiver.load(str(scene_file))
    assert quiver.load(str(scene_file), allow_outside_paths=True).primitive_count == 2


def test_instance_hits_name_the_instance_and_the_mesh_triangle(tmp_path):
    shutil.copy(os.path.join(DATA, "obj", "roof.obj"), tmp_path / "roof.obj")  # a scene names files in its folder
    scene_file = tmp_path / "instances.toml"
    scene_file.write_text('[[instances]]\nfile = "roof.obj"\n[[instances]]\nfile = "roof.obj"\ntranslate = [5, 0, 0]\n')
    scene = quiver.load(str(scene_file))
    assert scene.primitive_count == 2  # the roof's two faces, stored once
    origins = np.array([[0.25, 0.25, 5.0], [5.25, 0.25, 5.0], [-4.75, 0.25, 5.0], [20.0, 0.0, 5.0]])
    directions = np.tile([0.0, 0.0, -1.0], (4, 1))
    result = scene.intersect(origins, directions)
    assert list(result["instance"]) == [0, 1, -1, -1]
    assert list(result["primitive"]) == [0, 0, -1, -1]  # face 1 of roof.obj (x > 0)
    assert list(result["kind"][:2]) == [quiver.KINDS.index("triangle")] * 2
    assert result["t"][0] == result["t"][1]
    assert list(scene.occluded(origins, directions)) == [True, True, False, False]
    # Off instances the column is -1 too.
    spheres = quiver.from_arrays(spheres=np.array([[0.0, 0.0, 0.0, 1.0]]))
    assert spheres.intersect(origins[:1] * 0 + [0, 0, 5], directions[:1])["instance"][0] == -1


def test_misses_are_inf_and_minus_one():
    scene = quiver.from_arrays(spheres=np.array([[0.0, 0.0, 0.0, 1.0]]))
    origins = np.array([[0.0, 0.0, 5.0], [0.0, 3.0, 5.0]])
    directions = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, -1.0]])
    result = scene.intersect(origins, directions)
    assert result["t"][0] == np.float32(4.0)
    assert np.isinf(result["t"][1]) and result["t"][1] > 0
    assert result["primitive"][1] == -1 and result["kind"][1] == -1
    assert result["u"][1] == 0 and result["v"][1] == 0 and not result["normal"][1].any()
    # Outside (tmin, tmax) counts as a miss too.
    assert np.isinf(scene.intersect(origins[:1], directions[:1], tmax=3.5)["t"][0])
    assert scene.intersect(origins[:1], directions[:1], tmin=4.5)["t"][0] == np.float32(6.0)


def test_hit_points_are_the_origin_plus_t_times_the_direction():
    scene = quiver.from_arrays(spheres=np.array([[0.0, 0.0, 0.0, 1.0]]))
    origins = np.array([[0.0, 0.0, 5.0], [0.0, 3.0, 5.0], [0.25, 0.5, -4.0]])
    directions = np.array([[0.0, 0.0, -2.0], [0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    result = scene.intersect(origins, directions, points=True)
    assert "points" not in scene.intersect(origins, directions)
    points = result["points"]
    assert points.dtype == np.float32 and points.shape == (3, 3)
    np.testing.assert_array_equal(points[0], np.float32([0.0, 0.0, 1.0]))  # t = 2 along a direction of length 2
    assert np.isnan(points[1]).all()  # a miss
    t = np.float64(result["t"][2])
    np.testing.assert_array_equal(points[2], (origins[2] + t * directions[2]).astype(np.float32))
    assert abs(np.linalg.norm(points[2]) - 1.0) < 1e-6  # on the sphere
    with pytest.raises(TypeError):
        scene.intersect(origins, directions, 0.0, np.inf, 0, None, True)  # points is keyword-only


def test_hit_points_of_float64_rays_come_from_the_float32_rays_traced():
    scene = quiver.from_arrays(spheres=np.array([[0.0, 0.0, 0.0, 1.0]]))
    k = np.arange(200, dtype=np.float64)
    origins = np.stack([0.3 + k * 1e-9, np.zeros_like(k), np.full_like(k, -4.0)], axis=1)
    directions = np.tile([0.01, 0.0, 1.0], (len(k), 1))
    result = scene.intersect(origins, directions, points=True)
    t = result["t"].astype(np.float64)[:, None]
    as_traced = lambda a: a.astype(np.float32).astype(np.float64)
    traced = (as_traced(origins) + t * as_traced(directions)).astype(np.float32)
    unrounded = (origins + t * directions).astype(np.float32)
    assert (traced != unrounded).any()  # rays whose float64 values would give other points
    np.testing.assert_array_equal(result["points"], traced)


def test_occluded_agrees_with_intersect():
    scene = quiver.load(TINY)
    rays = quiver.camera_rays(scene, width=32, height=24)
    o, d = rays["origins"], rays["directions"]
    t = scene.intersect(o, d)["t"]
    blocked = scene.occluded(o, d)
    assert blocked.dtype == np.bool_ and blocked.shape == t.shape
    np.testing.assert_array_equal(blocked, np.isfinite(t))
    hit = np.isfinite(t)
    short = scene.occluded(o[hit], d[hit], tmax=float(t[hit].min()) * 0.5)
    assert not short.any()  # nothing before the closest hit of all


def test_python_threads_may_query_one_scene_at_once():
    import threading
    scene = quiver.load(TINY)
    rays = quiver.camera_rays(scene, width=64, height=48)
    o, d = rays["origins"], rays["directions"]
    reference = scene.intersect(o, d)["t"]
    results = [None] * 4

    def query(k):
        results[k] = [scene.intersect(o, d)["t"] for _ in range(20)]

    threads = [threading.Thread(target=query, args=(k,)) for k in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for per_thread in results:
        assert len(per_thread) == 20
        for t in per_thread:
            np.testing.assert_array_equal(t, reference)


def test_results_kept_alive_are_not_reused_by_later_calls():
    # The six arrays share one buffer that is reused only once all are freed
    # (python/output_buffers.h): keeping one of them keeps its values.
    scene = quiver.load(TINY)
    rays = quiver.camera_rays(scene, width=64, height=48)
    o, d = rays["origins"], rays["directions"]
    first = scene.intersect(o, d)
    kept_t, kept_normal = first["t"], first["normal"]
    expected_t, expected_normal = kept_t.copy(), kept_normal.copy()
    del first
    for _ in range(5):
        scene.intersect(o[::-1].copy(), d[::-1].copy())  # other values, same size
    np.testing.assert_array_equal(kept_t, expected_t)
    np.testing.assert_array_equal(kept_normal, expected_normal)
    assert not kept_t.flags["OWNDATA"] and kept_t.base is not None
