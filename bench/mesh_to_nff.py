#!/usr/bin/python3
"""Writes an OBJ mesh as an NFF scene of three-vertex `p` polygons, one per
triangle (faces of more corners as fans), with no viewpoint and no light
(quiver frames it with its default view and light): the "bunny as NFF" of
bench/README.md.

  mesh_to_nff.py MESH.obj OUT.nff

Vertices keep the OBJ's decimal text (no rounding on the way); normals,
texture coordinates and materials are left out (a `p` has none).
"""

import pathlib
import sys


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    source, target = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    vertices: list[str] = []
    polygons: list[str] = []
    for number, line in enumerate(source.read_text().splitlines(), 1):
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            vertices.append(" ".join(words[1:4]))
        elif words[0] == "f":
            corners = [int(w.split("/")[0]) for w in words[1:]]
            corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
            if len(corners) < 3 or not all(0 <= c < len(vertices) for c in corners):
                print(f"{source}:{number}: expected a face of 3 or more valid vertex indices", file=sys.stderr)
                return 1
            for k in range(1, len(corners) - 1):
                triangle = (corners[0], corners[k], corners[k + 1])
                polygons.append("p 3\n" + "\n".join(vertices[c] for c in triangle))
    if not polygons:
        print(f"{source}: expected at least one face", file=sys.stderr)
        return 1
    temporary = target.with_name(target.name + ".partial")
    temporary.write_text("f 0.8 0.8 0.8 1 0 0 0 0\n" + "\n".join(polygons) + "\n")
    temporary.replace(target)
    print(f"{target}: {len(polygons)} triangles as `p` polygons", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
