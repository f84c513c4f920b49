#!/usr/bin/env python3
"""Times mesh import per format: converts an OBJ mesh with mesh_formats.py
(binary PLY, binary STL, GLB; positions only), then reads each file and the
OBJ with `quiver info`, interleaved, and prints the medians of its `load`
time against OBJ's, at the default crease angle and at 0 (faceted).

    /usr/bin/python3 bench/mesh_import.py [--runs 7] [--mesh ../shared/meshes/stanford-bunny.obj]
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mesh_formats  # noqa: E402

FORMATS = ["obj", "ply", "stl", "glb"]


def load_ms(quiver, path, crease):
    out = subprocess.run([quiver, "info", path, "--crease-angle", crease], capture_output=True, text=True,
                         check=True).stdout
    return float(re.search(r"^load\s+([\d.]+) ms", out, re.M).group(1))


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--mesh", default=os.path.join(root, "..", "shared", "meshes", "stanford-bunny.obj"))
    parser.add_argument("--quiver", default=os.path.join(root, "build", "bin", "quiver"))
    args = parser.parse_args()
    if not os.path.isfile(args.mesh):
        sys.exit("mesh_import.py: no mesh at %s (--mesh)" % args.mesh)
    with tempfile.TemporaryDirectory() as folder:
        stem = os.path.join(folder, "mesh")
        vertices, faces = mesh_formats.read_obj(args.mesh)
        mesh_formats.write_ply(stem + ".ply", vertices, faces)
        mesh_formats.write_stl(stem + ".stl", vertices, faces)
        mesh_formats.write_glb(stem + ".glb", vertices, faces)
        shutil.copyfile(args.mesh, stem + ".obj")
        times = {}
        for _ in range(args.runs):
            for crease in ("60", "0"):
                for f in FORMATS:
                    times.setdefault((crease, f), []).append(load_ms(args.quiver, stem + "." + f, crease))
    print("%s: %d vertices, %d triangles; quiver info's load, medians of %d" %
          (os.path.basename(args.mesh), len(vertices), len(faces), args.runs))
    print("| crease angle | " + " | ".join(FORMATS) + " |")
    for crease in ("60", "0"):
        base = statistics.median(times[(crease, "obj")])
        cells = ["%.0f ms" % base] + ["%.0f ms (%.2fx)" % (statistics.median(times[(crease, f)]),
                                                          statistics.median(times[(crease, f)]) / base)
                                      for f in FORMATS[1:]]
        print("| %s | %s |" % (crease, " | ".join(cells)))


if __name__ == "__main__":
    main()
