#!/usr/bin/python3
"""A whole scene built in Python: a mesh given as NumPy arrays, placed 96
times in a loop with materials of its own, on a checkered floor under a
spot light and a soft rectangle light, seen by a camera; rendered, saved,
written out as TOML (with the mesh as a PLY file beside it), and (given the
quiver program) rendered by the CLI from that file, which must give the
same bytes.

Usage: scene_from_python.py [--folder DIR] [--width W] [--height H] [--quiver PATH]
Writes DIR/scene.png, DIR/scene.toml and DIR/scene_array_mesh_0.ply (DIR
defaults to a new temporary folder); with --quiver (or $QUIVER_CLI), also
DIR/cli.png, and exits 1 if it differs from scene.png. Run from the checkout after building:
    PYTHONPATH=build/python /usr/bin/python3 examples/python/scene_from_python.py --quiver build/bin/quiver
"""
import argparse
import colorsys
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import quiver


def octahedron():
    vertices = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    faces = np.array([[0, 2, 4], [4, 2, 1], [1, 2, 5], [5, 2, 0], [4, 3, 0], [1, 3, 4], [5, 3, 1], [0, 3, 5]],
                     dtype=np.int32)
    return vertices, faces


def scene_dict(width, height):
    """The scene as the TOML format's tables, built with loops; every instance gives the same two
    arrays, so the scene holds one mesh."""
    vertices, faces = octahedron()
    scene = {
        "background": [0.05, 0.06, 0.08],
        "ambient": [0.08, 0.08, 0.08],
        "camera": {"from": [0.0, 10.0, 15.0], "at": [0.0, 0.0, 0.5], "fov": 40, "width": width, "height": height},
        "render": {"aa": "grid:2", "max_depth": 4},
        "lights": [
            {"type": "spot", "position": [0.0, 12.0, 2.0], "direction": [0.0, -1.0, -0.15],
             "inner_angle": 20, "outer_angle": 35, "color": [0.8, 0.75, 0.7]},
            {"type": "rectangle", "corner": [-6.0, 8.0, 6.0], "edge_u": [3.0, 0.0, 0.0], "edge_v": [0.0, 0.0, 2.0],
             "samples": 3, "color": [0.25, 0.3, 0.4]},
        ],
        "textures": [{"name": "checks", "type": "checker2d", "colors": [[0.8, 0.8, 0.8], [0.25, 0.25, 0.3]],
                      "scale": 12}],
        "materials": [{"name": "floor", "texture": "checks", "kr": 0.1},
                      {"name": "mirror", "color": [0.9, 0.9, 0.9], "kd": 0.1, "ks": 0.6, "shininess": 100, "kr": 0.8}],
        "planes": [{"point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"}],
        "spheres": [{"center": [0.0, 1.2, 0.0], "radius": 1.2, "material": "mirror"}],
        "instances": [],
    }
    for i in range(10):
        hue = i / 10
        scene["materials"].append({"name": "hue %d" % i, "color": list(colorsys.hsv_to_rgb(hue, 0.7, 0.9)),
                                   "ks": 0.4, "shininess": 40})
    for k in range(100):
        row, column = divmod(k, 10)
        x, z = (column - 4.5) * 1.3, (row - 4.5) * 1.3
        if math.hypot(x, z) < 1.8:
            continue  # room for the sphere
        scene["instances"].append({
            "vertices": vertices,
            "triangles": faces,
            "material": "hue %d" % ((row + column) % 10),
            "scale": 0.45,
            "rotate": [0, (17 * k) % 90, 0],
            "translate": [x, 0.45, z],
        })
    return scene


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--folder", help="where the files go (default: a new temporary folder)")
    parser.add_argument("--width", type=int, default=480)
    parser.add_argument("--height", type=int, default=320)
    parser.add_argument("--quiver", default=os.environ.get("QUIVER_CLI"), help="the quiver program, to compare")
    args = parser.parse_args()
    folder = args.folder or tempfile.mkdtemp(prefix="quiver-scene-")
    os.makedirs(folder, exist_ok=True)

    description = scene_dict(args.width, args.height)
    scene = quiver.from_dict(description)
    print("%s: %d instances of one mesh" % (scene, len(description["instances"])))
    image = quiver.render(scene)
    image.save(os.path.join(folder, "scene.png"))
    scene.to_toml(os.path.join(folder, "scene.toml"))
    print("wrote", os.path.join(folder, "scene.png"), "and", os.path.join(folder, "scene.toml"))
    if not args.quiver:
        return 0
    cli_png = os.path.join(folder, "cli.png")
    subprocess.run([args.quiver, "render", os.path.join(folder, "scene.toml"), "-o", cli_png, "-q"], check=True)
    with open(cli_png, "rb") as a, open(os.path.join(folder, "scene.png"), "rb") as b:
        same = a.read() == b.read()
    print("quiver render scene.toml:", "the same PNG, byte for byte" if same else "A DIFFERENT PNG")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
