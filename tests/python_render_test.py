"""quiver.render (python/scene_render.h): the image and AOVs `quiver render`
writes to an EXR, bit for bit, for the same options. OpenImageIO's idiff
reads both: the CLI's EXR, and the returned arrays written here as PFM
(the portable float map: a text header, then little-endian float32 rows
bottom to top), with a zero threshold: one differing ULP fails."""
import os
import subprocess
import tempfile

import numpy as np
import pytest

import quiver
from support.python_support import TINY, run_cli, shared_file, tool

# A scene with checker and image textures (filtered unless texture_filter="none").
TEXTURED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "io", "examples", "textures.toml")


def write_pfm(path, image):
    """An (H, W, 3) or (H, W) float32 array as PFM."""
    image = np.asarray(image, dtype=np.float32)
    colour = image.ndim == 3
    height, width = image.shape[:2]
    with open(path, "wb") as f:
        f.write(b"PF\n" if colour else b"Pf\n")
        f.write(b"%d %d\n-1.0\n" % (width, height))
        f.write(np.ascontiguousarray(image[::-1]).astype("<f4").tobytes())


def same_pixels(expected_exr, actual, folder, name, channels=None):
    """idiff of the CLI's EXR (optionally some channels of it) and the array."""
    idiff = tool("idiff")
    if channels:
        part = os.path.join(folder, name + ".exr")
        subprocess.run([tool("oiiotool"), expected_exr, "--ch", channels, "-o", part], check=True,
                       capture_output=True)
        expected_exr = part
    pfm = os.path.join(folder, name + ".pfm")
    write_pfm(pfm, actual)
    done = subprocess.run([idiff, "-fail", "0", "-warn", "0", expected_exr, pfm], capture_output=True, text=True)
    assert done.returncode == 0 and "PASS" in done.stdout, name + ":\n" + done.stdout + done.stderr


def cli_flags(options):
    flags = []
    for key, value in options.items():
        flags += ["--" + key.replace("_", "-"), str(value)]
    return flags


CASES = [
    (TINY, {"width": 40, "height": 30, "aa": "grid:2", "max_depth": 3}),
    (TINY, {"width": 33, "height": 17, "aa": "jitter:2", "seed": 12345, "simd": "sse4", "threads": 1}),
    (TINY, {"preset": "spd", "width": 24, "height": 24}),
    (TINY, {"width": 32, "height": 24, "look_from": "3,2,5", "fov": 50, "aa": "refine:0.05:4"}),
    (TEXTURED, {"width": 40, "height": 30, "aa": "grid:2"}),
    (TEXTURED, {"width": 40, "height": 30, "texture_filter": "none"}),
]


@pytest.mark.parametrize("scene_file,options", CASES)
def test_render_equals_the_cli_exr(scene_file, options):
    with tempfile.TemporaryDirectory() as folder:
        exr = os.path.join(folder, "cli.exr")
        code, _, err = run_cli("render", scene_file, "-o", exr, "-q", "--aov", "depth,normal,id", *cli_flags(options))
        assert code == 0, err
        rendered = quiver.render(quiver.load(scene_file), aov="depth,normal,id", **options)
        image = rendered.color
        assert image.dtype == np.float32 and image.flags["C_CONTIGUOUS"]
        assert image.shape == (rendered.height, rendered.width, 3)
        assert image.any()  # not an empty image compared with another
        same_pixels(exr, image, folder, "rgb", "R,G,B")
        same_pixels(exr, rendered.depth, folder, "depth", "Z")
        same_pixels(exr, rendered.normal, folder, "normal", "N.X,N.Y,N.Z")
        # kind and id: integers the EXR stores as floats (exact below 2^24).
        same_pixels(exr, rendered.kind.astype(np.float32), folder, "kind", "kind")
        same_pixels(exr, rendered.id.astype(np.float32), folder, "id", "id")


def test_render_of_a_mesh_without_camera_equals_the_cli_exr():
    bunny = shared_file("meshes", "stanford-bunny.obj")
    with tempfile.TemporaryDirectory() as folder:
        exr = os.path.join(folder, "cli.exr")
        code, _, err = run_cli("render", bunny, "-o", exr, "-q", "--width", 48, "--height", 36)
        assert code == 0, err
        image = quiver.render(quiver.load(bunny), width=48, height=36).color
        same_pixels(exr, image, folder, "bunny")


def test_render_from_arrays_frames_them_with_the_default_view():
    scene = quiver.from_arrays(spheres=np.array([[0.0, 0.0, 0.0, 1.0], [2.5, 0.0, 0.0, 0.5]]))
    rendered = quiver.render(scene, width=64, height=48, aov="id")
    image = rendered.color
    assert image.shape == (48, 64, 3)
    assert rendered.depth is None and rendered.normal is None  # only the AOVs asked for
    seen = set(np.unique(rendered.id))
    assert seen == {-1, 0, 1}  # both spheres and the background in view
    lit = image[rendered.id >= 0].max(axis=1)
    assert (lit > 0).all()  # the default light reaches every visible point's ambient at least
    # Camera flags as sequences of numbers read as the CLI's "x,y,z" text.
    as_text = quiver.render(scene, width=16, height=12, look_from="1,2,8", up="0,1,0")
    as_numbers = quiver.render(scene, width=16, height=12, look_from=(1, 2, 8), up=[0.0, 1.0, 0.0])
    np.testing.assert_array_equal(as_text.color, as_numbers.color)
    with pytest.raises(ValueError, match="look_from: expected"):
        quiver.render(scene, look_from=5)


def test_to_srgb_gives_the_bytes_the_png_writer_stores(tmp_path):
    codes = quiver.to_srgb(np.array([0.0, 0.5, 1.0, 2.0, np.nan, -1.0, 0.0031308]))
    assert codes.dtype == np.uint8
    np.testing.assert_array_equal(codes, [0, 188, 255, 255, 0, 0, 10])
    assert quiver.to_srgb(np.float64(0.5)).shape == ()
    image = quiver.render(quiver.load(TINY), width=24, height=16).color
    png = str(tmp_path / "cli.png")
    code, _, err = run_cli("render", TINY, "--width", "24", "--height", "16", "-o", png, "-q")
    assert code == 0, err
    ppm = str(tmp_path / "cli.ppm")
    subprocess.run([tool("oiiotool"), png, "-o", ppm], check=True, capture_output=True)
    with open(ppm, "rb") as f:
        data = f.read()
    header = data.split(b"\n", 3)  # P6, width height, maxval, then the rows
    assert header[0] == b"P6" and header[1] == b"24 16" and header[2] == b"255"
    written = np.frombuffer(header[3], dtype=np.uint8).reshape(16, 24, 3)
    srgb = quiver.to_srgb(image)
    assert srgb.shape == image.shape and srgb.any()
    np.testing.assert_array_equal(srgb, written)


def test_image_save_writes_the_files_of_the_cli(tmp_path):
    options = {"width": 20, "height": 14, "aa": "grid:2"}
    rendered = quiver.render(quiver.load(TINY), **options)
    assert rendered.kind is None and rendered.id is None
    assert repr(rendered) == "<quiver.Image 20x14>"
    png = tmp_path / "saved.png"
    rendered.save(png)  # os.PathLike
    code, _, err = run_cli("render", TINY, "-o", str(tmp_path / "cli.png"), "-q", *cli_flags(options))
    assert code == 0, err
    assert png.read_bytes() == (tmp_path / "cli.png").read_bytes()
    with_aovs = quiver.render(quiver.load(TINY), aov="depth,id", **options)
    assert repr(with_aovs) == "<quiver.Image 20x14, aov depth,id>"
    exr = str(tmp_path / "saved.exr")
    with_aovs.save(exr)
    same_pixels(exr, with_aovs.color, str(tmp_path), "rgb", "R,G,B")
    same_pixels(exr, with_aovs.depth, str(tmp_path), "depth", "Z")
    same_pixels(exr, with_aovs.id.astype(np.float32), str(tmp_path), "id", "id")
    # The arrays are views of the image: a change is what save writes, and a view keeps the image alive.
    color = quiver.render(quiver.load(TINY), **options).color
    color[:, :10] = 0.25
    assert color.base is not None
    with_aovs.color[:] = 0.5
    with_aovs.save(exr)
    same_pixels(exr, np.full((14, 20, 3), 0.5, dtype=np.float32), str(tmp_path), "changed", "R,G,B")
    with pytest.raises(ValueError, match="exr"):
        with_aovs.save(str(tmp_path / "aovs.png"))  # AOVs need EXR, as --aov does
    with pytest.raises(ValueError):
        with_aovs.save(str(tmp_path / "image.bmp"))
    with pytest.raises(ValueError):
        with_aovs.save(str(tmp_path / "missing-folder" / "x.exr"))
    assert not (tmp_path / "aovs.png").exists()


def test_render_options_are_checked_as_the_cli_flags():
    scene = quiver.load(TINY)
    bad = [{"aa": "grid:0"}, {"max_depth": 65}, {"min_weight": -1.0}, {"aov": "depth,depth"},
           {"preset": "spd", "aa": "none"}, {"preset": "fast"}, {"fov": 180.0}, {"look_from": "0,1"},
           {"seed": -1}, {"width": 70000}, {"texture_filter": "blur"}]
    for options in bad:
        with pytest.raises(quiver.UsageError) as error:
            quiver.render(scene, **options)
        _, _, err = run_cli("render", TINY, "-o", "unused.png", *cli_flags(options))
        assert err.strip() == "quiver: " + str(error.value), options



def test_two_sided_lights_a_surface_seen_from_behind(tmp_path):
    # An NFF triangle (opaque: one-sided) facing +z, seen from -z with its
    # light at the eye: one-sided, its back gets only the ambient light;
    # two-sided, the light reaches it. The CLI's --two-sided agrees.
    nff = tmp_path / "back.nff"
    nff.write_text("v\nfrom 0 0 -3\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 16 12\n"
                   "l 0 0.5 -3\nf 1 1 1 1 0 0 0 0\np 3\n-1 -1 0\n1 -1 0\n0 1 0\n")
    scene = quiver.load(str(nff))
    one_sided = quiver.render(scene, aov="id")
    two_sided = quiver.render(scene, two_sided=True, aov="id")
    seen = one_sided.id >= 0
    assert seen.any()
    np.testing.assert_array_equal(seen, two_sided.id >= 0)
    assert (two_sided.color[seen].sum(axis=1) > one_sided.color[seen].sum(axis=1)).all()
    exr = str(tmp_path / "cli.exr")
    code, _, err = run_cli("render", str(nff), "-o", exr, "-q", "--two-sided")
    assert code == 0, err
    same_pixels(exr, two_sided.color, str(tmp_path), "two_sided", "R,G,B")
