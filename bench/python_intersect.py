#!/usr/bin/python3
"""scene.intersect against `quiver trace` on the same rays, and the module's
import time: the figures of docs/PYTHON.md, measured in one run.

  Rays: `quiver trace MESH --width W --height H` times the closest hits of
  its primary rays (median over --repeat passes, rays generated before
  timing). quiver.camera_rays gives those rays as NumPy arrays in trace's
  order; scene.intersect on them is timed with Python's clock around the
  whole call (checking the arrays, reading them into ray batches, the
  queries, writing the six output arrays, allocating them), median over the
  same number of passes. The two alternate --rounds times in this process
  (trace as a subprocess), and the hits and t sums must agree; the ratio
  reported is the median of the rounds' ratios (each pair ran back to back,
  so a busy machine slows both alike), with the lowest and highest.
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
    trace_command = [args.cli, "trace", args.mesh, "--width", str(args.width), "--height", str(args.height),
                     "--repeat", str(args.repeat), "--threads", str(args.threads)]
    trace_rates, python_rates = [], []
    for _ in range(args.rounds):
        line = json.loads(subprocess.run(trace_command, check=True, capture_output=True, text=True).stdout)
        trace_rates.append(line["mrays_per_s"])
        seconds = []
        for _ in range(args.repeat):
            start = time.perf_counter()
            result = scene.intersect(o, d, threads=args.threads)
            seconds.append(time.perf_counter() - start)
        python_rates.append(n / statistics.median(seconds) / 1e6)
        assert trace_totals(result, starts) == (line["hits"], line["t_sum"]), "intersect and trace disagree"

    module = import_seconds("import quiver", args.imports)
    numpy_alone = import_seconds("import numpy", args.imports)
    both = import_seconds("import numpy, quiver", args.imports)

    print("%s, %s x%d lanes, %d threads; %d rays (%dx%d), %d hits" % (
        cpu_name(), line["simd"], line["lanes"], line["threads"], n, args.width, args.height, line["hits"]))
    print()
    print("| measure | value |")
    print("| --- | --- |")
    tr, pr = statistics.median(trace_rates), statistics.median(python_rates)
    print("| `quiver trace` Mrays/s (median of %d rounds) | %.1f |" % (args.rounds, tr))
    print("| `scene.intersect` Mrays/s (median of %d rounds) | %.1f |" % (args.rounds, pr))
    ratios = sorted(p / t for p, t in zip(python_rates, trace_rates))
    print("| intersect / trace, median of the rounds' ratios | %.2f (%.2f to %.2f) |" % (
        statistics.median(ratios), ratios[0], ratios[-1]))
    print("| `import quiver` (median of %d) | %.1f ms |" % (args.imports, module * 1e3))
    print("| `import numpy` alone | %.1f ms |" % (numpy_alone * 1e3))
    print("| `import numpy, quiver` | %.1f ms |" % (both * 1e3))


if __name__ == "__main__":
    main()
