#!/usr/bin/python3
"""Where a frame's time goes (bench/README.md, "Phases of a frame").

For each scene (SPD balls-s4, gears-s4, teapot-s12 and the Stanford bunny
from the shared folder) and each quiver binary given, runs

    quiver render SCENE --width 512 --height 512 --aa none --threads 1
        --quiet -o OUT.png --stats S.json

--runs times (the binaries interleaved) and takes the median of each phase
of the stats' phases_ms (camera_and_film, intersection, shading, shadows;
integrator/trace_stats.h) and of render_ms. It also times the scene's
primary rays alone (`quiver trace --threads 1 --repeat 5`) and reports the
render's rays per second as a share of those, and the share's ceiling: the
render's rays over its BVH walks' time alone (the stats' traversal_ms), as a
share of the same. Writes
bench/results/phases.json and bench/phases.png (stacked bars of the phases
per scene and binary), and prints a Markdown table.

--binary PATH[=LABEL] may be repeated (default: build/bin/quiver as "now"):
give the build before a change and the build after it to chart both.

Run from anywhere: /usr/bin/python3 bench/phases.py [--runs 5]
  [--binary PATH[=LABEL] ...] [--shared DIR] [--quick] [--plot-only]
"""

import argparse
import json
import os
import statistics
import sys
import tempfile
from pathlib import Path

from headline import cpu_model, run  # bench/headline.py, beside this script

REPO = Path(__file__).resolve().parent.parent
SCENES = {
    "balls-s4": "scenes/spd/balls-s4.nff",
    "gears-s4": "scenes/spd/gears-s4.nff",
    "teapot-s12": "scenes/spd/teapot-s12.nff",
    "bunny": "meshes/stanford-bunny.obj",
}
PHASES = ["camera_and_film", "intersection", "shading", "shadows"]
RESULTS = REPO / "bench" / "results" / "phases.json"
CHART = REPO / "bench" / "phases.png"


def run_json(command):
    done, _ = run(command)  # without QUIVER_SIMD: quiver picks its widest unit
    if done.returncode != 0:
        sys.exit(f"phases.py: {' '.join(map(str, command))} failed:\n{done.stderr}")
    return done


def measure(binaries, shared, runs, size):
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for scene, relative in SCENES.items():
            path = shared / relative
            if not path.exists():
                print(f"phases.py: {path} missing, {scene} skipped", file=sys.stderr)
                continue
            samples = {label: [] for _, label in binaries}
            for run in range(runs):
                for binary, label in binaries:
                    stats = Path(tmp) / "stats.json"
                    run_json([binary, "render", path, "--width", str(size), "--height", str(size), "--aa", "none",
                              "--threads", "1", "--quiet", "-o", Path(tmp) / "out.png", "--stats", stats])
                    samples[label].append(json.loads(stats.read_text()))
                    print(f"phases.py: {scene} {label} run {run + 1}/{runs}", file=sys.stderr)
            results[scene] = {}
            for binary, label in binaries:
                trace = json.loads(run_json([binary, "trace", path, "--width", str(size), "--height", str(size),
                                             "--threads", "1", "--repeat", "5"]).stdout)
                runs_of = samples[label]
                render_ms = statistics.median(s["render_ms"] for s in runs_of)
                rays = runs_of[0]["rays"]["total"]
                walks = [s["traversal_ms"] for s in runs_of if "traversal_ms" in s]
                results[scene][label] = {
                    "render_ms": render_ms,
                    "phases_ms": {p: statistics.median(s["phases_ms"][p] for s in runs_of) for p in PHASES},
                    # Builds from before traversal_ms was reported have none.
                    "traversal_ms": statistics.median(walks) if walks else None,
                    "rays": rays,
                    "render_mrays_per_s": rays / render_ms / 1e3,
                    "trace_mrays_per_s": trace["mrays_per_s"],
                    "simd": runs_of[0]["simd"],
                }
    return results


def table(data):
    lines = ["| scene | build | render ms | " + " | ".join(PHASES) + " | render Mrays/s | share of trace's | "
             "ceiling (walks alone) |",
             "| --- | --- | ---: | " + " | ".join("---:" for _ in PHASES) + " | ---: | ---: | ---: |"]
    for scene, builds in data["scenes"].items():
        for label, r in builds.items():
            total = sum(r["phases_ms"].values())
            shares = " | ".join(f"{100 * r['phases_ms'][p] / total:.0f}%" for p in PHASES)
            walks = r.get("traversal_ms")
            ceiling = f"{100 * r['rays'] / walks / 1e3 / r['trace_mrays_per_s']:.0f}%" if walks else "-"
            lines.append(f"| {scene} | {label} | {r['render_ms']:.0f} | {shares} | {r['render_mrays_per_s']:.1f} | "
                         f"{100 * r['render_mrays_per_s'] / r['trace_mrays_per_s']:.0f}% | {ceiling} |")
    return "\n".join(lines)


def plot(data):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [(scene, label, r) for scene, builds in data["scenes"].items() for label, r in builds.items()]
    fig, ax = plt.subplots(figsize=(8, 0.45 * len(rows) + 1.5))
    names = [f"{scene} ({label})" for scene, label, _ in rows]
    left = [0.0] * len(rows)
    for phase in PHASES:
        widths = [r["phases_ms"][phase] for _, _, r in rows]
        ax.barh(names, widths, left=left, label=phase.replace("_", " "))
        left = [a + b for a, b in zip(left, widths)]
    ax.invert_yaxis()
    ax.set_xlabel("thread time per frame (ms), 512x512, one ray per pixel, 1 thread")
    ax.set_title(f"Phases of a frame, {data['cpu']}")
    ax.legend(loc="lower right", fontsize="small")
    fig.tight_layout()
    fig.savefig(CHART, dpi=100)


def main():
    default_shared = Path(os.environ.get("QUIVER_SHARED_DIR", REPO.parent / "shared"))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", action="append", default=[], help="PATH[=LABEL], repeatable")
    parser.add_argument("--runs", type=int, default=5, help="renders per scene and binary, medians (default 5)")
    parser.add_argument("--shared", type=Path, default=default_shared, help="the shared folder (default ../shared)")
    parser.add_argument("--quick", action="store_true", help="64x64, one run: checks the script works")
    parser.add_argument("--plot-only", action="store_true", help="redraw the chart from bench/results/phases.json")
    args = parser.parse_args()
    if args.plot_only:
        data = json.loads(RESULTS.read_text())
    else:
        binaries = []
        for spec in args.binary or [str(REPO / "build" / "bin" / "quiver") + "=now"]:
            path, _, label = spec.partition("=")
            binaries.append((Path(path), label or Path(path).parent.parent.name))
        runs, size = (1, 64) if args.quick else (args.runs, 512)
        data = {"cpu": cpu_model(), "size": size, "runs": runs,
                "scenes": measure(binaries, args.shared, runs, size)}
        if not args.quick:
            RESULTS.write_text(json.dumps(data, indent=1) + "\n")
    if not args.quick:
        plot(data)
    print(f"CPU: {data['cpu']}; {data['size']}x{data['size']}, --aa none, 1 thread, medians of {data['runs']}")
    print(table(data))


if __name__ == "__main__":
    main()
