#!/usr/bin/env python3
"""Writes an OBJ mesh (its `v` and `f` lines) as binary PLY, binary STL and
GLB beside OUT_STEM, for the import benchmark in bench/README.md ("Mesh
import"): the same vertices and faces in every format, positions only.

    python3 bench/mesh_formats.py ../shared/meshes/stanford-bunny.obj /tmp/bunny
"""
import json
import struct
import sys


def read_obj(path):
    vertices, faces = [], []
    with open(path) as obj:
        for line in obj:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                vertices.append(tuple(float(x) for x in words[1:4]))
            elif words[0] == "f":
                corners = [int(w.split("/")[0]) for w in words[1:]]
                corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
                faces += [(corners[0], corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)]
    return vertices, faces


def write_ply(path, vertices, faces):
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (len(vertices), len(faces)))
    with open(path, "wb") as out:
        out.write(header.encode())
        out.write(b"".join(struct.pack("<3f", *v) for v in vertices))
        out.write(b"".join(struct.pack("<B3i", 3, *f) for f in faces))


def write_stl(path, vertices, faces):
    with open(path, "wb") as out:
        out.write(b"binary STL from bench/mesh_formats.py".ljust(80, b" "))
        out.write(struct.pack("<I", len(faces)))
        for f in faces:
            out.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            out.write(b"".join(struct.pack("<3f", *vertices[i]) for i in f))
            out.write(struct.pack("<H", 0))


def write_glb(path, vertices, faces):
    positions = b"".join(struct.pack("<3f", *v) for v in vertices)
    indices = b"".join(struct.pack("<3I", *f) for f in faces)
    lows = [min(v[k] for v in vertices) for k in range(3)]
    highs = [max(v[k] for v in vertices) for k in range(3)]
    document = {
        "asset": {"version": "2.0", "generator": "bench/mesh_formats.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(positions) + len(indices)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(vertices), "type": "VEC3",
                       "min": lows, "max": highs},
                      {"bufferView": 1, "componentType": 5125, "count": 3 * len(faces), "type": "SCALAR"}],
    }
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    binary = positions + indices
    binary += b"\0" * (-len(binary) % 4)
    with open(path, "wb") as out:
        out.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(binary)))
        out.write(struct.pack("<I4s", len(text), b"JSON") + text)
        out.write(struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: mesh_formats.py MESH.obj OUT_STEM")
    vertices, faces = read_obj(sys.argv[1])
    write_ply(sys.argv[2] + ".ply", vertices, faces)
    write_stl(sys.argv[2] + ".stl", vertices, faces)
    write_glb(sys.argv[2] + ".glb", vertices, faces)
    print("%d vertices, %d triangles: %s.ply, .stl, .glb" % (len(vertices), len(faces), sys.argv[2]))


if __name__ == "__main__":
    main()
