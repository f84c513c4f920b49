#!/usr/bin/env python3
"""Instancing against flattening: a field of bunnies (a grid, each turned
about its up axis) as TOML [[instances]] of one mesh and as the same
placements copied into world space ([[meshes]]), traced by `quiver trace`
(primary rays, one thread). Prints memory (stores and tables, and BVHs),
build time and primary rays/s.

[[meshes]] add at most 2^24 triangles to a scene (kMaxObjTriangles): 241
bunnies. --flat-count (default 240) sets the field compared both ways, and
--count (default 1000) the instanced field measured against one bunny.

    /usr/bin/python3 bench/instances.py [--count 1000] [--flat-count 240] [--size 512] [--repeat 7] [--rounds 3]
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time


def write_field(path, mesh, count, table):
    """count bunnies on a grid (spacing 0.2, the bunny is ~0.16 wide), seen from above its front edge."""
    cols = max(1, math.ceil(math.sqrt(count * 1.6)))
    rows = math.ceil(count / cols)
    width, depth = (cols - 1) * 0.2, (rows - 1) * 0.2
    span = max(width, depth, 0.4)
    lines = ["[camera]",
             "from = [%g, %g, %g]" % (width / 2, 0.8 * span + 0.3, 0.6 * span + 0.3),
             "at = [%g, 0.05, %g]" % (width / 2, -depth / 2),
             "up = [0, 1, 0]", "fov = 50", "",
             "[[lights]]", 'type = "point"', "position = [%g, %g, %g]" % (width / 2, 3 * span, 2 * span), ""]
    for i in range(count):
        x, z = (i % cols) * 0.2, -(i // cols) * 0.2
        lines += ["[[%s]]" % table, 'file = "%s"' % mesh, "translate = [%g, 0, %g]" % (x, z),
                  "rotate = [0, %d, 0]" % (i * 37 % 360), ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def trace(quiver, scene, size, repeat):
    start = time.perf_counter()
    # The generated scene names the mesh where it lies, outside the scene's folder.
    out = subprocess.run([quiver, "trace", scene, "--width", str(size), "--height", str(size), "--threads", "1",
                          "--repeat", str(repeat), "--allow-outside-paths"],
                         capture_output=True, text=True, check=True).stdout
    line = json.loads(out.strip().splitlines()[-1])
    line["process_s"] = time.perf_counter() - start
    return line


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=1000)
    parser.add_argument("--flat-count", type=int, default=240)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--mesh", default=os.path.join(root, "..", "shared", "meshes", "stanford-bunny.obj"))
    parser.add_argument("--quiver", default=os.path.join(root, "build", "bin", "quiver"))
    args = parser.parse_args()
    if not os.path.isfile(args.mesh):
        sys.exit("instances.py: no mesh at %s (--mesh)" % args.mesh)
    mesh = os.path.abspath(args.mesh)
    runs, ratios = {}, []
    with tempfile.TemporaryDirectory() as folder:
        scenes = {}
        for name, count, table in (("one", 1, "instances"), ("instanced", args.count, "instances"),
                                   ("instanced-flat-count", args.flat_count, "instances"),
                                   ("flattened", args.flat_count, "meshes")):
            scenes[name] = os.path.join(folder, name + ".toml")
            write_field(scenes[name], mesh, count, table)
        # The two fields of flat-count bunnies back to back, round by round
        # (the ratio of each round; the machine's speed drifts between processes).
        for _ in range(args.rounds):
            for name in scenes:
                if name in ("one", "instanced") and name in runs:
                    continue
                runs[name] = trace(args.quiver, scenes[name], args.size, args.repeat)
                print("%s: %s" % (name, json.dumps(runs[name])), file=sys.stderr)
            ratios.append(runs["instanced-flat-count"]["mrays_per_s"] / runs["flattened"]["mrays_per_s"])

    def total(r):
        return r["memory_bytes"] + r["acceleration_bytes"]

    one, many = runs["one"], runs["instanced"]
    per_instance = (total(many) - total(one)) / (args.count - 1)
    print("%s, %dx%d primary rays, 1 thread, medians of %d passes (the last round's)" % (
        os.path.basename(args.mesh), args.size, args.size, args.repeat))
    print("| scene | triangles stored | memory (stores + BVHs) | build | primary rays |")
    print("|---|---|---|---|---|")
    for name, label in (("one", "1 bunny"), ("instanced", "%d instances" % args.count),
                        ("instanced-flat-count", "%d instances" % args.flat_count),
                        ("flattened", "%d flattened" % args.flat_count)):
        r = runs[name]
        print("| %s | %d | %.1f MB | %.0f ms | %.1f Mrays/s |" % (label, r["primitives"], total(r) / 1e6,
                                                                 r["build_ms"], r["mrays_per_s"]))
    print()
    bound = total(one) + many["instance_table_bytes"]
    print("%d instances: memory %.4fx one bunny plus the instance table and top-level BVH (%.1f KB); "
          "%.0f bytes per instance" % (args.count, total(many) / bound, many["instance_table_bytes"] / 1e3,
                                       per_instance))
    inst, flat = runs["instanced-flat-count"], runs["flattened"]
    print("%d bunnies: instanced primary rays %.2fx the flattened scene's (median of %d rounds: %s); hits %d vs %d; "
          "memory %.3fx; build %.3fx; whole process %.1f s vs %.1f s" % (
              args.flat_count, statistics.median(ratios), len(ratios), ", ".join("%.2f" % r for r in ratios),
              inst["hits"], flat["hits"],
              total(inst) / total(flat), inst["build_ms"] / flat["build_ms"], inst["process_s"], flat["process_s"]))


if __name__ == "__main__":
    main()
