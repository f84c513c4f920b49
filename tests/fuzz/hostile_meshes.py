#!/usr/bin/python3
"""A hostile-file campaign against quiver's mesh readers (glTF, GLB, STL, PLY, OBJ).

    /usr/bin/python3 tests/fuzz/hostile_meshes.py run [--quiver build/bin/quiver] [--count 2000]
        [--timeout 20] [--memory-limit-mb 4096] [--seed 1] [--keep DIR]
    /usr/bin/python3 tests/fuzz/hostile_meshes.py seeds DIR (gltf|glb)
    /usr/bin/python3 tests/fuzz/hostile_meshes.py inputs DIR [--count 2000] [--seed 1]

`run` generates COUNT hostile files (structural mutations of valid files,
offsets and counts near 2^64, deep and duplicated node graphs, cycles,
refused extensions, huge lists, extreme numbers, byte flips) and runs
`quiver info FILE` on each under TIMEOUT seconds and an address-space
limit (RLIMIT_AS, so that a memory bomb fails instead of taking the
machine), measuring the child's peak RSS (os.wait4). It prints, per format and in all, the counts of
crashes (a signal), hangs (the timeout), runs above 1 GB, errors whose
message does not name the file given, and successes; the files of the
findings are kept in DIR (default: none kept). Exit status 1 when any
crash, hang, run above 1 GB or unnamed error was found.

`seeds` writes structure-aware seeds for mesh_fuzzer (tests/fuzz/run.sh):
each file is the fuzzer's selector byte (2 glTF, 3 GLB), then the file.
`inputs` writes the campaign's glTF, GLB, STL and PLY files (the same ones
`run` makes with that seed) as mesh_fuzzer inputs, so that
`build-fuzz/bin/mesh_fuzzer DIR/*` runs each once under ASan and UBSan
(quiver's PLY reader and the checks before Assimp; buffer files named by
URI resolve in tests/data/mesh there, not beside the file).
Standard library only.
"""

import argparse
import base64
import copy
import json
import os
import random
import resource
import signal
import struct
import subprocess
import sys
import tempfile
import time

BIG = [2**64 - 1, 2**64 - 4, 2**63, 2**63 - 1, 2**32, 2**32 - 1, 2**31, 2**24 + 1, 10**12, 65536]
SMALL = [0, 1, 3, 4, 5, 252, 255, 256]
ODD = [-1, -(2**63), 1.5, 1e300, "7", None, True, [], {}]
EXTREME_FLOATS = [3.4e38, -3.4e38, 3.4028235e38, 1e-45, float("inf"), float("-inf"), float("nan"), 0.0]
LIMIT_RSS_KB = 1 << 20  # 1 GB


# ---- glTF ------------------------------------------------------------------

def triangle_buffer(positions=None):
    """Three float positions and three ushort indices (padded to 44 bytes)."""
    positions = positions or [0, 0, 0, 1, 0, 0, 0, 1, 0]
    return struct.pack("<9f", *positions) + struct.pack("<3H", 0, 1, 2) + b"\0\0"


def triangle_document(buffer_uri):
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": 44} if buffer_uri is None else {"byteLength": 44, "uri": buffer_uri}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def glb(document, binary, version=2, length_extra=0):
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary is not None:
        binary += b"\0" * (-len(binary) % 4)
        chunks += struct.pack("<II", len(binary), 0x004E4942) + binary
    return b"glTF" + struct.pack("<II", version, 12 + len(chunks) + length_extra) + chunks


def deep_chain(depth, duplicate=False):
    """Nodes 0 -> 1 -> ... -> depth-1, the last naming the mesh; each child listed twice when duplicate."""
    doc = triangle_document(data_uri(triangle_buffer()))
    nodes = []
    for i in range(depth - 1):
        nodes.append({"children": [i + 1, i + 1] if duplicate else [i + 1]})
    nodes.append({"mesh": 0})
    doc["nodes"] = nodes
    return doc


def hostile_value(rng):
    pick = rng.random()
    if pick < 0.45:
        return rng.choice(BIG)
    if pick < 0.75:
        return rng.choice(SMALL)
    return copy.deepcopy(rng.choice(ODD))


def mutate_document(doc, rng, copies=(10, 1000, 5000)):
    """One to three structural mutations of a triangle document; `copies`
    are the lengths of the repeated lists (primitives, samplers) it may write."""
    edits = [
        lambda: doc["bufferViews"][rng.randrange(2)].__setitem__(
            rng.choice(["byteOffset", "byteLength", "byteStride", "buffer"]), hostile_value(rng)),
        lambda: doc["accessors"][rng.randrange(2)].__setitem__(
            rng.choice(["byteOffset", "count", "componentType", "bufferView", "byteStride"]), hostile_value(rng)),
        lambda: doc["accessors"][rng.randrange(2)].__setitem__("type", rng.choice(["MAT4", "VEC5", "", 3, "SCALAR"])),
        lambda: doc["accessors"][0].__setitem__("sparse", {
            "count": hostile_value(rng),
            "indices": {"bufferView": 1, "byteOffset": hostile_value(rng), "componentType": rng.choice([5123, 5125, 5126])},
            "values": {"bufferView": rng.choice([0, 1, 9]), "byteOffset": hostile_value(rng)}}),
        lambda: doc["meshes"][0]["primitives"][0].__setitem__(
            rng.choice(["indices", "mode", "material"]), hostile_value(rng)),
        lambda: doc["meshes"][0]["primitives"][0]["attributes"].__setitem__(
            rng.choice(["POSITION", "NORMAL", "TEXCOORD_0", "COLOR_0"]), hostile_value(rng)),
        lambda: doc["nodes"].append({"children": [rng.randrange(3) for _ in range(rng.randrange(1, 4))], "mesh": 0}),
        lambda: doc["nodes"][0].__setitem__(rng.choice(["mesh", "children"]), hostile_value(rng)),
        lambda: doc["scenes"][0].__setitem__("nodes", [hostile_value(rng)]),
        lambda: doc.__setitem__("scene", hostile_value(rng)),
        lambda: doc["buffers"][0].__setitem__("byteLength", hostile_value(rng)),
        lambda: doc.__setitem__(rng.choice(["extensionsRequired", "extensionsUsed"]), [rng.choice(
            ["KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_mesh_quantization", "KHR_materials_ior"])]),
        lambda: doc["meshes"][0]["primitives"][0].__setitem__("extensions", {"KHR_draco_mesh_compression": {
            "bufferView": 0, "attributes": {"POSITION": 0}}}),
        lambda: doc["bufferViews"][0].__setitem__("extensions", {"EXT_meshopt_compression": {
            "buffer": 0, "byteOffset": hostile_value(rng), "byteLength": 36, "byteStride": 12, "count": 3}}),
        lambda: doc.__setitem__("images", [{"bufferView": hostile_value(rng), "mimeType": "image/png"}]),
        lambda: doc["meshes"][0]["primitives"].extend([doc["meshes"][0]["primitives"][0]] * rng.choice(copies)),
        lambda: doc.__setitem__("animations", [{"samplers": [{"input": 0, "output": 0}] * rng.choice(copies),
                                                "channels": []}]),
        lambda: doc["accessors"].__setitem__(0, {"componentType": 5126, "count": hostile_value(rng), "type": "VEC3"}),
    ]
    for _ in range(rng.randrange(1, 4)):
        rng.choice(edits)()
    return doc


def gltf_cases(rng, binary):
    """(kind, document, binary chunk or None, buffer files {name: bytes}) of one hostile glTF."""
    buffer = triangle_buffer()
    pick = rng.random()
    if pick < 0.08:
        return "deep", deep_chain(rng.choice([300, 2000, 20000, 60000])), None, {}
    if pick < 0.16:
        return "doubling", deep_chain(rng.choice([16, 22, 30, 64]), duplicate=True), None, {}
    if pick < 0.22:
        doc = deep_chain(rng.choice([3, 10]))
        doc["nodes"][-1]["children"] = [rng.randrange(len(doc["nodes"]))]  # a cycle
        return "cycle", doc, None, {}
    if pick < 0.30:
        values = [rng.choice(EXTREME_FLOATS) if rng.random() < 0.5 else rng.random() for _ in range(9)]
        doc = triangle_document(None if binary else data_uri(triangle_buffer(values)))
        return "extreme", doc, triangle_buffer(values) if binary else None, {}
    if pick < 0.40:
        doc = triangle_document("tri.bin")
        return "buffer-file", mutate_document(doc, rng), None, {"tri.bin": buffer}
    doc = triangle_document(None if binary else data_uri(buffer))
    return "structure", mutate_document(doc, rng), buffer if binary else None, {}


def gltf_files(rng, binary):
    kind, doc, chunk, extra = gltf_cases(rng, binary)
    if binary:
        if chunk is None:
            chunk = b""
        data = glb(doc, chunk)
        if rng.random() < 0.15:  # the container itself
            at = rng.choice([4, 8, 12, 16, 20 + len(json.dumps(doc)) // 4 * 4])
            at = min(at, len(data) - 4)
            data = data[:at] + struct.pack("<I", rng.choice([0, 1, 2**31, 2**32 - 1])) + data[at + 4:]
            kind += "-container"
        return kind, data, extra
    text = json.dumps(doc).encode()
    return kind, text, extra


# ---- STL, PLY, OBJ ----------------------------------------------------------

def stl_file(rng):
    pick = rng.random()
    if pick < 0.4:
        count = rng.choice([1, 2, 2**31, 2**32 - 1, 10**6])
        facets = rng.randrange(0, 3)
        data = b"\0" * 80 + struct.pack("<I", count)
        for _ in range(facets):
            values = [rng.choice(EXTREME_FLOATS) if rng.random() < 0.4 else rng.random() for _ in range(12)]
            data += struct.pack("<12fH", *values, 0)
        return "binary", data
    if pick < 0.8:
        lines = ["solid x"]
        for _ in range(rng.randrange(1, 4)):
            lines.append("facet normal 0 0 1\nouter loop")
            for _ in range(rng.choice([3, 3, 3, 0, 1000])):
                lines.append("vertex " + " ".join(repr(rng.choice(EXTREME_FLOATS + [1.0, 2.0, "1e99999", "x"]))
                                                  for _ in range(3)))
            lines.append("endloop\nendfacet")
        if rng.random() < 0.7:
            lines.append("endsolid x")
        return "ascii", "\n".join(str(line) for line in lines).encode()
    return "bytes", bytes(rng.randrange(256) for _ in range(rng.randrange(0, 300)))


def ply_file(rng):
    fmt = rng.choice(["ascii", "binary_little_endian", "binary_big_endian"])
    vertices = rng.choice([3, 0, 2**32 - 1, 2**63, 10**9])
    faces = rng.choice([1, 0, 2**31, 10**9])
    count_type = rng.choice(["uchar", "int", "uint", "char", "float"])
    header = (f"ply\nformat {fmt} 1.0\nelement vertex {vertices}\nproperty float x\nproperty float y\n"
              f"property float z\nelement face {faces}\nproperty list {count_type} int vertex_indices\nend_header\n")
    if fmt == "ascii":
        values = [rng.choice(EXTREME_FLOATS + [0.0, 1.0]) for _ in range(9)]
        body = "\n".join(" ".join(repr(v) for v in values[i:i + 3]) for i in range(0, 9, 3))
        body += "\n" + rng.choice(["3 0 1 2", "4000000000 0 1 2", "-1 0 1 2", "255 " + "0 " * 255, "3 0 1 9999999"])
        return "ply-" + fmt, (header + body + "\n").encode()
    order = "<" if fmt == "binary_little_endian" else ">"
    body = b"".join(struct.pack(order + "f", rng.choice(EXTREME_FLOATS + [0.0, 1.0])) for _ in range(9))
    body += bytes([rng.choice([3, 255, 0])]) + struct.pack(order + "3i", 0, 1, rng.choice([2, -5, 2**31 - 1]))
    return "ply-" + fmt, header.encode() + body


def obj_file(rng):
    """(kind, bytes, the files it names: MTL libraries, relative to it)."""
    lines = []
    named = []
    pick = rng.random()
    if pick < 0.3:
        for _ in range(3):
            lines.append("v " + " ".join(repr(rng.choice(EXTREME_FLOATS + [0.0, 1.0, "1e39", "0x1p128"]))
                                         for _ in range(3)))
        lines.append("f 1 2 3")
    elif pick < 0.6:
        lines += ["v 0 0 0", "v 1 0 0", "v 0 1 0"]
        lines.append("f " + " ".join(str(rng.choice([1, 2, 3, 0, -4, 2**31, 2**64, 18446744073709551617]))
                                     for _ in range(rng.choice([3, 3, 256, 3000]))))
    elif pick < 0.8:
        named.append(rng.choice(["../../../../etc/passwd", "x" * 5000, "nowhere.mtl"]))
        lines += ["mtllib " + named[-1], "usemtl a"]
        lines += ["v 0 0 0", "v 1 0 0", "v 0 1 0", "f 1 2 3"]
    else:
        lines += ["v 0 0 0"] * rng.choice([10, 100000]) + ["f " + " ".join(["1"] * 3)]
    return "obj", ("\n".join(lines) + "\n").encode(), named


def byte_flips(data, rng):
    data = bytearray(data)
    for _ in range(rng.randrange(1, 8)):
        if not data:
            break
        at = rng.randrange(len(data))
        action = rng.random()
        if action < 0.5:
            data[at] = rng.randrange(256)
        elif action < 0.8:
            data[at:at] = rng.choice([b"9999999999999999999999", b"[", b"{", b"-", b"e308", b"\0"])
        else:
            del data[at:at + rng.randrange(1, 16)]
    return bytes(data)


def hostile_file(index, rng):
    """(format, kind, main file name, {name: bytes}, names of other files it reads) of the index-th file."""
    fmt = ["gltf", "glb", "stl", "ply", "obj"][index % 5]
    named = []
    if fmt in ("gltf", "glb"):
        kind, data, extra = gltf_files(rng, fmt == "glb")
    elif fmt == "stl":
        kind, data = stl_file(rng)
        extra = {}
    elif fmt == "ply":
        kind, data = ply_file(rng)
        extra = {}
    else:
        kind, data, named = obj_file(rng)
        extra = {}
    if rng.random() < 0.15 and kind not in ("deep", "doubling"):
        data = byte_flips(data, rng)
        kind += "-flipped"
    name = f"h{index:05d}.{fmt}"
    return fmt, kind, name, dict(extra, **{name: data}), named


# ---- running ------------------------------------------------------------------

def run_one(quiver, path, timeout, other_files, memory_limit_mb):
    """(outcome, peak RSS in KB, stderr text) of `quiver info path`. An
    error names the file holding the fault when it names `path` or one of
    other_files (an MTL library the OBJ names). The peak RSS is Linux's
    high-water mark, which exec keeps: it includes this script's size when
    it forked (tens of MB), an upper bound on quiver's."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        limit = memory_limit_mb << 20

        def limit_memory():
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

        process = subprocess.Popen([quiver, "info", path], stdout=out, stderr=err, start_new_session=True,
                                   preexec_fn=limit_memory)
        deadline = time.monotonic() + timeout
        while True:
            pid, status, usage = os.wait4(process.pid, os.WNOHANG)
            if pid != 0:
                break
            if time.monotonic() > deadline:
                os.killpg(process.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(process.pid, 0)
                process.returncode = -signal.SIGKILL
                return "hang", usage.ru_maxrss, ""
            time.sleep(0.005)
        process.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        text = err.read().decode(errors="replace")
    if process.returncode < 0:
        return "crash", usage.ru_maxrss, text
    if process.returncode == 0:
        return "success", usage.ru_maxrss, text
    named = any(name in text for name in [path] + other_files)
    return ("error" if named else "unnamed"), usage.ru_maxrss, text


def campaign(args):
    rng = random.Random(args.seed)
    totals = {}
    findings = []
    with tempfile.TemporaryDirectory(prefix="quiver_hostile_") as work:
        for index in range(args.count):
            fmt, kind, name, files, named = hostile_file(index, rng)
            folder = os.path.join(work, f"{index:05d}")
            os.mkdir(folder)
            for file_name, data in files.items():
                with open(os.path.join(folder, file_name), "wb") as f:
                    f.write(data)
            path = os.path.join(folder, name)
            others = [os.path.normpath(os.path.join(folder, other)) for other in named]
            outcome, rss, text = run_one(args.quiver, path, args.timeout, others, args.memory_limit_mb)
            row = totals.setdefault(fmt, {"files": 0, "crash": 0, "hang": 0, "over 1 GB": 0, "unnamed": 0,
                                          "error": 0, "success": 0})
            row["files"] += 1
            row[outcome] += 1
            big = rss > LIMIT_RSS_KB
            if big:
                row["over 1 GB"] += 1
            if outcome in ("crash", "hang", "unnamed") or big:
                findings.append((outcome + (" >1GB" if big else ""), fmt, kind, path, rss, text.strip()[:300]))
                if args.keep:
                    keep = os.path.join(args.keep, f"{index:05d}")
                    os.makedirs(keep, exist_ok=True)
                    for file_name, data in files.items():
                        with open(os.path.join(keep, file_name), "wb") as f:
                            f.write(data)
            for file_name in files:
                os.unlink(os.path.join(folder, file_name))
            os.rmdir(folder)
    columns = ["files", "crash", "hang", "over 1 GB", "unnamed", "error", "success"]
    print("format  " + "  ".join(f"{c:>9}" for c in columns))
    total = {c: 0 for c in columns}
    for fmt, row in totals.items():
        print(f"{fmt:<6}  " + "  ".join(f"{row[c]:>9}" for c in columns))
        for c in columns:
            total[c] += row[c]
    print(f"{'all':<6}  " + "  ".join(f"{total[c]:>9}" for c in columns))
    print("(unnamed: an error whose message names neither the file given nor a file it names; error: one that "
          "does; over 1 GB: peak RSS, this script's size at fork included)")
    for outcome, fmt, kind, path, rss, text in findings[:40]:
        print(f"FINDING {outcome} {fmt}/{kind} rss={rss} KB {os.path.basename(path)}: {text}")
    return 1 if findings else 0


def write_seeds(folder, fmt):
    """Structure-aware seeds for mesh_fuzzer: its selector byte, then the file."""
    os.makedirs(folder, exist_ok=True)
    selector = b"\x02" if fmt == "gltf" else b"\x03"
    rng = random.Random(7)
    seeds = {"deep300": deep_chain(300), "doubling22": deep_chain(22, duplicate=True)}
    for i in range(40):
        # Short lists: libFuzzer's inputs are at most 64 KB, and small ones run faster.
        seeds[f"mutated{i:02d}"] = mutate_document(triangle_document(None if fmt == "glb" else data_uri(
            triangle_buffer())), rng, copies=(2, 10))
    plain = triangle_document(None if fmt == "glb" else data_uri(triangle_buffer()))
    seeds["plain"] = plain
    sparse = copy.deepcopy(plain)
    sparse["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                                        "values": {"bufferView": 0, "byteOffset": 24}}
    seeds["sparse"] = sparse
    near = copy.deepcopy(sparse)
    near["accessors"][0]["sparse"]["indices"]["byteOffset"] = 2**63
    seeds["sparse-near-2-63"] = near
    for name, doc in seeds.items():
        data = glb(doc, triangle_buffer()) if fmt == "glb" else json.dumps(doc).encode()
        with open(os.path.join(folder, f"seed-{fmt}-{name}"), "wb") as f:
            f.write(selector + data)


def write_inputs(folder, count, seed):
    """The campaign's files but OBJ, each behind mesh_fuzzer's selector byte."""
    os.makedirs(folder, exist_ok=True)
    rng = random.Random(seed)
    selector = {"ply": b"\x00", "stl": b"\x01", "gltf": b"\x02", "glb": b"\x03"}
    written = 0
    for index in range(count):
        fmt, _, name, files, _ = hostile_file(index, rng)
        if fmt in selector:
            with open(os.path.join(folder, name), "wb") as f:
                f.write(selector[fmt] + files[name])
            written += 1
    print(f"wrote {written} mesh_fuzzer inputs to {folder}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run")
    run.add_argument("--quiver", default="build/bin/quiver")
    run.add_argument("--count", type=int, default=2000)
    run.add_argument("--timeout", type=float, default=20.0)
    run.add_argument("--memory-limit-mb", type=int, default=4096)
    run.add_argument("--seed", type=int, default=1)
    run.add_argument("--keep", default="")
    seeds = sub.add_parser("seeds")
    seeds.add_argument("folder")
    seeds.add_argument("format", choices=["gltf", "glb"])
    inputs = sub.add_parser("inputs")
    inputs.add_argument("folder")
    inputs.add_argument("--count", type=int, default=2000)
    inputs.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if args.command == "seeds":
        write_seeds(args.folder, args.format)
        return 0
    if args.command == "inputs":
        write_inputs(args.folder, args.count, args.seed)
        return 0
    return campaign(args)


if __name__ == "__main__":
    sys.exit(main())
