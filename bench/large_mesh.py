#!/usr/bin/python3
"""Writes a large triangle mesh as binary little-endian PLY, made in memory
(no data committed): a sphere of radius 1 with bumps along latitude and
longitude, r = 1 + 0.05 sin(13 theta) sin(17 phi), as a grid of
`rings` x `segments` quads cut into two triangles each (the poles closed
by fans), at least the requested triangle count. The "10-million-triangle
scene" of bench/README.md:

  large_mesh.py --triangles 10000000 OUT.ply

Deterministic: the same count gives the same bytes.
"""

import argparse
import array
import math
import pathlib
import sys


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--triangles", type=int, default=10_000_000, help="at least this many triangles (default 10M)")
    parser.add_argument("out", type=pathlib.Path)
    args = parser.parse_args()
    if not 8 <= args.triangles <= 16_000_000:
        parser.error("--triangles: expected 8 to 16,000,000 (quiver reads at most 2^24 triangles per mesh)")
    # 2 (rings - 2) segments triangles between the rings and segments at each
    # pole: 2 (rings - 1) segments in all, at least the count asked for.
    rings = max(2, round(math.sqrt(args.triangles / 2)))
    segments = max(3, -(-args.triangles // (2 * (rings - 1))))
    positions = array.array("f")
    for i in range(1, rings):  # ring i at polar angle pi i / rings
        theta = math.pi * i / rings
        s, c = math.sin(theta), math.cos(theta)
        for j in range(segments):
            phi = 2.0 * math.pi * j / segments
            r = 1.0 + 0.05 * math.sin(13.0 * theta) * math.sin(17.0 * phi)
            positions.extend((r * s * math.cos(phi), r * c, r * s * math.sin(phi)))
    north, south = (rings - 1) * segments, (rings - 1) * segments + 1
    positions.extend((0.0, 1.0, 0.0, 0.0, -1.0, 0.0))
    faces = bytearray()
    face = array.array("I", [0, 0, 0])
    count = 0

    def add(a: int, b: int, c: int) -> None:
        nonlocal count
        face[0], face[1], face[2] = a, b, c
        faces.append(3)
        faces.extend(face.tobytes())
        count += 1

    for j in range(segments):
        k = (j + 1) % segments
        add(north, k, j)
        for i in range(rings - 2):
            a, b = i * segments + j, i * segments + k
            add(a, b, b + segments)
            add(a, b + segments, a + segments)
        base = (rings - 2) * segments
        add(south, base + j, base + k)
    if sys.byteorder != "little":
        positions.byteswap()
    header = (f"ply\nformat binary_little_endian 1.0\ncomment bench/large_mesh.py --triangles {args.triangles}\n"
              f"element vertex {len(positions) // 3}\nproperty float x\nproperty float y\nproperty float z\n"
              f"element face {count}\nproperty list uchar uint vertex_indices\nend_header\n")
    partial = args.out.with_name(args.out.name + ".partial")
    with open(partial, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(positions.tobytes())
        out.write(faces)
    partial.replace(args.out)
    print(f"{args.out}: {count} triangles, {len(positions) // 3} vertices", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
