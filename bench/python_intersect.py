#!/usr/bin/python3
"""scene.intersect and scene.occluded against `quiver trace` on the same rays, and the module's
import time: the figures of docs/PYTHON.md, measured in one run.

  Rays: `quiver trace MESH --width W --height H` times the closest hits of
  its primary rays (median over --repeat passes, rays generated before
  timing); with --occluded their any-hit queries, with --shuffle the same
  rays in a fixed random order (incoherent). quiver.camera_rays gives those
  rays as NumPy arrays in trace's tile order, and a NumPy permutation
  (seed 1) shuffles them; scene.intersect and scene.occluded on them are
  timed with Python's clock around the whole call (checking the arrays,
  reading them into ray batches, the queries, writing the output arrays,
  allocating them), median over the same number of passes. Each round runs
  the four pairs (tile order and shuffled, closest and any-hit), trace as a
  subprocess, and the hits (and t sums) must agree; a pair's ratio is the
  median of the rounds' ratios (each pair ran back to back, so a busy
  machine slows both alike), with the lowest and highest.
  Import: `import quiver` in a fresh interpreter, timed inside it
  (time.perf_counter around the import), median of --imports runs; also
  `import numpy` alone and both together, numpy being what any use of the
  module's arrays needs.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_intersect.py
           [--mesh MESH] [--width 1024] [--height 1024] [--repeat 5]
           [--rounds 3] [--imports 15] [--threads 0]
Prints a Markdown table; the CPU and quiver's ISA are named above it.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np
import quiver
from trace_totals import trace_totals

HERE = os.path.dirname(os.path.abspath(__file__))


def cpu_name():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return "unknown CPU"


def import_seconds(statement, runs):
    code = "import time; t = time.perf_counter(); %s; print(time.perf_counter() - t)" % statement
    times = [float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True,
                                  env=os.environ).stdout) for _ in range(runs)]
    return statistics.median(times)


QUERIES = [  # (row label, scene method, trace flags, rays shuffled)
    ("intersect, tile order", "intersect", [], False),
    ("occluded, tile order", "occluded", ["--occluded"], False),
    ("intersect, shuffled", "intersect", ["--shuffle"], True),
    ("occluded, shuffled", "occluded", ["--occluded", "--shuffle"], True),
]


def check_agreement(method, result, line, starts, shuffled):
    """The Python call found what trace found: hits (and t_sum, in trace's order of additions or near it)."""
    if method == "occluded":
        assert int(result.sum()) == line["hits"], "occluded and trace --occluded disagree"
        return
    if not shuffled:
        assert trace_totals(result, starts) == (line["hits"], line["t_sum"]), "intersect and trace disagree"
        return
    hit = result["kind"] >= 0
    t_sum = float(result["t"][hit].astype(np.float64).sum())
    assert int(hit.sum()) == line["hits"] and abs(t_sum - line["t_sum"]) <= 1e-9 * line["t_sum"], \
        "shuffled intersect and trace --shuffle disagree"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    shared = os.environ.get("QUIVER_SHARED_DIR", os.path.join(HERE, "..", "..", "shared"))
    parser.add_argument("--mesh", default=os.path.join(shared, "meshes", "stanford-bunny.obj"))
    parser.add_argument("--cli", default=os.path.join(HERE, "..", "build", "bin", "quiver"))
    parser.add_argument("--width", type=int, default=1024)
    parser.add_argument("--height", type=int, default=1024)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--imports", type=int, default=15)
    parser.add_argument("--threads", type=int, default=0)
    args = parser.parse_args()

    scene = quiver.load(args.mesh)
    rays = quiver.camera_rays(scene, width=args.width, height=args.height)
    o, d, starts = rays["origins"], rays["directions"], rays["tile_starts"]
    n = len(o)
    order = np.random.default_rng(1).permutation(n)
    shuffled_rays = (np.ascontiguousarray(o[order]), np.ascontiguousarray(d[order]))
    trace_command = [args.cli, "trace", args.mesh, "--width", str(args.width), "--height", str(args.height),
                     "--repeat", str(args.repeat), "--threads", str(args.threads)]
    trace_rates = {label: [] for label, *_ in QUERIES}
    python_rates = {label: [] for label, *_ in QUERIES}
    for _ in range(args.rounds):
        for label, method, flags, shuffled in QUERIES:
            line = json.loads(subprocess.run(trace_command + flags, check=True, capture_output=True,
                                             text=True).stdout)
            trace_rates[label].append(line["mrays_per_s"])
            origins, directions = shuffled_rays if shuffled else (o, d)
            query = getattr(scene, method)
            seconds = []
            for _ in range(args.repeat):
                start = time.perf_counter()
                result = query(origins, directions, threads=args.threads)
                seconds.append(time.perf_counter() - start)
            python_rates[label].append(n / statistics.median(seconds) / 1e6)
            check_agreement(method, result, line, starts, shuffled)

    module = import_seconds("import quiver", args.imports)
    numpy_alone = import_seconds("import numpy", args.imports)
    both = import_seconds("import numpy, quiver", args.imports)

    print("%s, %s x%d lanes, %d threads; %d rays (%dx%d), %d hits" % (
        cpu_name(), line["simd"], line["lanes"], line["threads"], n, args.width, args.height, line["hits"]))
    print()
    print("| rays, query | `quiver trace` Mrays/s | Python Mrays/s | Python / trace, median of %d rounds (range) |"
          % args.rounds)
    print("| --- | ---: | ---: | --- |")
    for label, *_ in QUERIES:
        ratios = sorted(p / t for p, t in zip(python_rates[label], trace_rates[label]))
        print("| %s | %.1f | %.1f | %.2f (%.2f to %.2f) |" % (
            label, statistics.median(trace_rates[label]), statistics.median(python_rates[label]),
            statistics.median(ratios), ratios[0], ratios[-1]))
    print()
    print("| import | ms (median of %d) |" % args.imports)
    print("| --- | ---: |")
    print("| `import quiver` | %.1f |" % (module * 1e3))
    print("| `import numpy` alone | %.1f |" % (numpy_alone * 1e3))
    print("| `import numpy, quiver` | %.1f |" % (both * 1e3))


if __name__ == "__main__":
    main()
