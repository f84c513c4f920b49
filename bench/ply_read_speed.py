#!/usr/bin/env python3
"""Times reading a large binary PLY: an OBJ mesh (the bunny by default)
tiled TILES x TILES side by side into one little-endian PLY (mesh_formats.py's
layout: float x y z, uchar-counted int triangles), read by each given
quiver build with `quiver info --crease-angle 0` (faceted, so the load is
mostly the reader); prints each build's load time and the file's size over
it in MB/s.

    /usr/bin/python3 bench/ply_read_speed.py [--tiles 4] [--runs 1] build/bin/quiver [OTHER/quiver ...]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mesh_formats  # noqa: E402


def tiled(vertices, faces, tiles):
    """tiles x tiles copies of the mesh, each shifted by its width along x and z."""
    width = max(v[0] for v in vertices) - min(v[0] for v in vertices)
    depth = max(v[2] for v in vertices) - min(v[2] for v in vertices)
    all_vertices, all_faces = [], []
    for i in range(tiles):
        for j in range(tiles):
            base = len(all_vertices)
            all_vertices += [(x + 1.1 * width * i, y, z + 1.1 * depth * j) for x, y, z in vertices]
            all_faces += [(a + base, b + base, c + base) for a, b, c in faces]
    return all_vertices, all_faces


def load_ms(quiver, path):
    out = subprocess.run([quiver, "info", path, "--crease-angle", "0"], capture_output=True, text=True,
                         check=True).stdout
    return float(re.search(r"^load\s+([\d.]+) ms", out, re.M).group(1))


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("quivers", nargs="+", help="quiver binaries to compare")
    parser.add_argument("--tiles", type=int, default=4)
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--mesh", default=os.path.join(root, "..", "shared", "meshes", "stanford-bunny.obj"))
    args = parser.parse_args()
    vertices, faces = tiled(*mesh_formats.read_obj(args.mesh), args.tiles)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "tiled.ply")
        mesh_formats.write_ply(path, vertices, faces)
        megabytes = os.path.getsize(path) / 1e6
        print("%s tiled %dx%d: %d vertices, %d triangles, %.1f MB binary PLY; quiver info --crease-angle 0, "
              "best of %d" % (os.path.basename(args.mesh), args.tiles, args.tiles, len(vertices), len(faces),
                              megabytes, args.runs))
        for quiver in args.quivers:
            ms = min(load_ms(quiver, path) for _ in range(args.runs))
            print("| %s | %.0f ms | %.0f MB/s |" % (quiver, ms, megabytes / (ms / 1e3)))


if __name__ == "__main__":
    main()
