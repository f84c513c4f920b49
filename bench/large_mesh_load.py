#!/usr/bin/python3
"""Load and build of one large mesh in each format quiver reads: the sphere
of bench/large_mesh.py (at least --triangles triangles) written as binary
PLY, binary STL and OBJ (generated in a temporary folder, nothing kept),
each read by `quiver info` faceted (--crease-angle 0) and with smooth
normals (the default 60 degrees), --runs times; prints one Markdown row per
format and crease angle: the file's size, load ms (median) and MB/s, ms per
million triangles, build ms, and the process's peak resident memory
against the build's own peak, what it held as read (when the build began)
and what the scene keeps (quiver info's "peak memory" and "build peak"
lines). The STL
and OBJ are written by a child process: a child's peak resident memory
counts the parent's at the fork, so this process never holds the mesh.
Then, where Embree applies (its build of the same triangles), the
harness's build table for the PLY (build/bin/quiver_bench_embree, when
built; --embree none skips it): quiver's and Embree's build ms, medians of
--runs, and bytes per triangle.

Usage: /usr/bin/python3 bench/large_mesh_load.py [--triangles 1000000] [--runs 5] [--quiver build/bin/quiver]
           [--embree build/bin/quiver_bench_embree]
"""
import argparse
import multiprocessing
import os
import re
import statistics
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def ply_counts(data):
    """The header's end and the vertex and face counts of large_mesh.py's PLY."""
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    count = lambda name: int(next(l for l in header if l.startswith("element " + name)).split()[2])
    return end, count("vertex"), count("face")


def read_ply(path):
    """Vertices and triangles of large_mesh.py's PLY (float x y z; uchar-counted int triangles)."""
    data = open(path, "rb").read()
    end, vertices, faces = ply_counts(data)
    positions = struct.unpack_from("<%df" % (3 * vertices), data, end)
    triangles = []
    at = end + 12 * vertices
    for _ in range(faces):
        triangles.append(struct.unpack_from("<3i", data, at + 1))
        at += 13
    return positions, triangles


def write_stl(path, positions, triangles):
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", len(triangles)))
        for a, b, c in triangles:
            f.write(struct.pack("<12fH", 0, 0, 0, *positions[3 * a:3 * a + 3], *positions[3 * b:3 * b + 3],
                                *positions[3 * c:3 * c + 3], 0))


def write_obj(path, positions, triangles):
    with open(path, "w") as f:
        for i in range(0, len(positions), 3):
            f.write("v %r %r %r\n" % positions[i:i + 3])
        for a, b, c in triangles:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def info(quiver, path, crease):
    out = subprocess.run([quiver, "info", path, "--crease-angle", str(crease)], capture_output=True, text=True,
                         check=True).stdout
    number = lambda pattern: float(re.search(pattern, out, re.M).group(1))
    return {"load": number(r"^load\s+([\d.]+) ms"), "build": number(r"^build\s+([\d.]+) ms"),
            "peak": number(r"^peak memory\s+(\d+) bytes"), "kept": number(r"for (\d+) kept"),
            "build peak": number(r"^build peak\s+(\d+) bytes"), "read": number(r"from (\d+) when it began")}


def embree_builds(harness, ply, runs):
    """The harness's build row for the PLY: quiver and Embree build ms and bytes per primitive."""
    out = subprocess.run([harness, "--width", "16", "--height", "16", "--repeat", str(runs), "--scenes", ply],
                         capture_output=True, text=True, check=True).stdout
    header = next(line for line in out.splitlines() if line.startswith("| scene | primitives |"))
    row = next(line for line in out.splitlines()[out.splitlines().index(header) + 2:] if line.startswith("| "))
    return [cell.strip() for cell in row.strip("|").split("|")]


def write_other_formats(files):
    positions, triangles = read_ply(files["binary PLY"])
    write_stl(files["binary STL"], positions, triangles)
    write_obj(files["OBJ"], positions, triangles)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--triangles", type=int, default=1_000_000)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--quiver", default=os.path.join(HERE, "..", "build", "bin", "quiver"))
    parser.add_argument("--embree", default=os.path.join(HERE, "..", "build", "bin", "quiver_bench_embree"),
                        help="the Embree harness, or none")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        ply = os.path.join(folder, "sphere.ply")
        subprocess.run([sys.executable, os.path.join(HERE, "large_mesh.py"), "--triangles", str(args.triangles), ply],
                       check=True, capture_output=True)
        files = {"binary PLY": ply, "binary STL": os.path.join(folder, "sphere.stl"),
                 "OBJ": os.path.join(folder, "sphere.obj")}
        writer = multiprocessing.get_context("fork").Process(target=write_other_formats, args=(files,))
        writer.start()
        writer.join()
        if writer.exitcode != 0:
            sys.exit("large_mesh_load.py: writing the STL and OBJ failed")
        with open(ply, "rb") as f:
            _, vertices, faces = ply_counts(f.read(1 << 16))
        millions = faces / 1e6
        print("%d triangles, %d vertices; quiver info, medians of %d" % (faces, vertices, args.runs))
        print("| format | crease angle | file MB | load ms | MB/s | load ms per M triangles | build ms | "
              "peak / build's peak / as read / kept MB |")
        print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for name, path in files.items():
            size = os.path.getsize(path) / 1e6
            for crease in (0, 60):
                runs = [info(args.quiver, path, crease) for _ in range(args.runs)]
                median = {key: statistics.median(r[key] for r in runs) for key in runs[0]}
                print("| %s | %d | %.1f | %.0f | %.0f | %.0f | %.0f | %.0f / %.0f / %.0f / %.0f |" % (
                    name, crease, size, median["load"], size / (median["load"] / 1000), median["load"] / millions,
                    median["build"], median["peak"] / 1e6, median["build peak"] / 1e6, median["read"] / 1e6,
                    median["kept"] / 1e6), flush=True)
        if args.embree == "none":
            return
        if not os.access(args.embree, os.X_OK):
            print("no Embree comparison: %s is not built (CMake builds it where Embree is installed)" % args.embree)
            return
        cells = embree_builds(args.embree, ply, args.runs)
        print("\nThe binary PLY's builds, `quiver_bench_embree --width 16 --height 16 --repeat %d` (medians, every "
              "thread; quiver's geometry with its smooth normals):" % args.runs)
        print("| quiver build ms | Embree build ms (commit) | Embree low / high quality ms "
              "| quiver geometry + BVH B/tri | Embree buffers + rest B/tri |")
        print("| ---: | ---: | ---: | ---: | ---: |")
        print("| %s | %s | %s | %s + %s | %s + %s |" % (cells[3], cells[4], cells[5], cells[6], cells[7], cells[8],
                                                        cells[9]))


if __name__ == "__main__":
    main()
