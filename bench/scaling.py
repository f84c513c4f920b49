#!/usr/bin/python3
"""Render time against primitive count (bench/README.md, "Scaling").

Runs `quiver render SCENE --preset spd --width 256 --height 256 --stats ...`
on the SPD scenes of the issue (balls s1 s2 s4, tetra s1 s6, gears s1 s4,
teapot s2 s6 s12: only those present in $QUIVER_SHARED_DIR/scenes/spd) and on
every mesh in $QUIVER_SHARED_DIR/meshes, and writes bench/results/scaling.json
and bench/scaling.png (render wall time in the renderer, `render_ms` of the
stats, against primitives kept, log x). `quiver render` rather than `quiver
trace`: the issue asks for render time, and the SPD procedure fixes the ray
budget per image (corner rays, 4 bounces, shadow rays) so scenes compare
whole renders. The primitive count comes from a 1x1 `quiver trace`
(its "primitives"). The chart's second panel divides by the rays each
render cast. --with-trace also times the primary rays alone with `quiver
trace` (throughput without shading) and adds them to that panel. Each render runs --repeat
times (median of render_ms); a run past --timeout seconds is recorded as a
timeout and left out of the chart. --quick keeps the scenes below 2000
primitives. --plot-only redraws the chart from an existing JSON.

Run from the repository root: /usr/bin/python3 bench/scaling.py [--quick]
"""

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SPD_SCENES = ["balls-s1", "balls-s2", "balls-s4", "tetra-s1", "tetra-s6", "gears-s1", "gears-s4",
              "teapot-s2", "teapot-s6", "teapot-s12"]
QUICK_MAX_PRIMITIVES = 2000


def shared_dir():
    return Path(os.environ.get("QUIVER_SHARED_DIR", REPO.parent / "shared"))


def scene_list(shared):
    """(name, path) of every scene to run; names of missing SPD scenes."""
    scenes, missing = [], []
    for name in SPD_SCENES:
        path = shared / "scenes" / "spd" / (name + ".nff")
        if path.exists():
            scenes.append((name, path))
        else:
            missing.append(name)
    for path in sorted((shared / "meshes").glob("*.obj")):
        scenes.append((path.stem, path))
    return scenes, missing


def run(command, timeout):
    """(completed process or None on timeout, wall seconds)."""
    start = time.monotonic()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, time.monotonic() - start
    return done, time.monotonic() - start


def trace_json(binary, path, args, timeout):
    done, _ = run([str(binary), "trace", str(path)] + args, timeout)
    if done is None:
        return None
    if done.returncode != 0:
        raise RuntimeError(f"quiver trace {path} failed: {done.stderr.strip()}")
    return json.loads(done.stdout)


def measure(name, path, options, work):
    entry = {"scene": name, "file": str(path)}
    count = trace_json(options.binary, path, ["--width", "1", "--height", "1", "--repeat", "1"], options.timeout)
    if count is None:
        print(f"{name}: loading and building timed out after {options.timeout} s", file=sys.stderr)
        entry.update({"primitives": None, "timeout_s": options.timeout})
        return entry
    entry["primitives"] = count["primitives"]
    if options.quick and entry["primitives"] >= QUICK_MAX_PRIMITIVES:
        return None
    stats_path = work / "stats.json"
    command = [str(options.binary), "render", str(path), "--preset", "spd", "--width", str(options.width),
               "--height", str(options.height), "--threads", str(options.threads), "--stats", str(stats_path),
               "-o", str(work / "image.png"), "-q"]
    entry["command"] = " ".join(command[:2] + [path.name] + command[3:])
    render_ms, wall = [], []
    for _ in range(options.repeat):
        done, seconds = run(command, options.timeout)
        if done is None:
            entry["timeout_s"] = options.timeout
            print(f"{name}: timed out after {options.timeout} s", file=sys.stderr)
            return entry
        if done.returncode != 0:
            raise RuntimeError(f"quiver render {path} failed: {done.stderr.strip()}")
        stats = json.loads(stats_path.read_text())
        render_ms.append(stats["render_ms"])
        wall.append(seconds)
    entry.update({"render_ms": statistics.median(render_ms), "render_ms_all": render_ms,
                  "process_wall_s": statistics.median(wall), "build_ms": stats["build_ms"],
                  "load_ms": stats["load_ms"], "rays": stats["rays"]["total"],
                  "mrays_per_s": stats["mrays_per_s"], "threads": stats["threads"], "simd": stats["simd"],
                  "acceleration_bytes": stats["memory_bytes"]["acceleration"]})
    if options.with_trace:
        line = trace_json(options.binary, path, ["--width", str(options.width), "--height", str(options.height),
                                                 "--threads", str(options.threads), "--repeat", "3"],
                          options.timeout)
        entry["trace"] = line if line is not None else {"timeout_s": options.timeout}
    print(f"{name}: {entry['primitives']} primitives, render {entry['render_ms']:.1f} ms", file=sys.stderr)
    return entry


def plot(results, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    done = [r for r in results["scenes"] if "render_ms" in r]
    traced = [r for r in done if "ms_median" in r.get("trace", {})]
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.5))
    spd = [r for r in done if r["file"].endswith(".nff")]
    meshes = [r for r in done if not r["file"].endswith(".nff")]
    s = results["settings"]

    def labelled(ax, points):
        for name, x, y in points:
            ax.annotate(name, (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_xlabel("primitives (kept by the builders)")
        ax.grid(True, which="both", alpha=0.3)

    ax = axes[0]
    for group, marker, label in ((spd, "o", "SPD (--preset spd)"), (meshes, "s", "meshes (default view, --preset spd)")):
        if group:
            ax.scatter([r["primitives"] for r in group], [r["render_ms"] / 1000 for r in group], marker=marker,
                       label=label)
    labelled(ax, [(r["scene"], r["primitives"], r["render_ms"] / 1000) for r in done])
    ax.set_ylabel("render time (s)")
    ax.set_title(f"quiver render {s['width']}x{s['height']}, {s['threads_label']} threads")
    ax.legend(fontsize=8)

    # Per ray: the SPD scenes cast very different numbers of rays (lights, mirrors).
    ax = axes[1]
    ax.scatter([r["primitives"] for r in done], [r["render_ms"] * 1e6 / r["rays"] for r in done],
               label="render: render_ms / all rays (shading included)")
    if traced:
        ax.scatter([r["primitives"] for r in traced], [r["trace"]["ms_median"] * 1e6 / r["trace"]["rays"] for r in traced],
                   marker="^", label="quiver trace: primary rays only (closest hit)")
    labelled(ax, [(r["scene"], r["primitives"], r["render_ms"] * 1e6 / r["rays"]) for r in done])
    ax.set_ylabel("wall time per ray (ns, all threads together)")
    ax.set_title("time per ray")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", type=Path, default=REPO / "build" / "bin" / "quiver")
    parser.add_argument("--width", type=int, default=256)
    parser.add_argument("--height", type=int, default=256)
    parser.add_argument("--threads", type=int, default=0, help="0: every core (default)")
    parser.add_argument("--repeat", type=int, default=1, help="renders per scene; the median is kept")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per quiver run (default 600)")
    parser.add_argument("--quick", action="store_true", help=f"only scenes below {QUICK_MAX_PRIMITIVES} primitives")
    parser.add_argument("--with-trace", action="store_true", help="also time primary rays alone (quiver trace)")
    parser.add_argument("--json", type=Path, default=REPO / "bench" / "results" / "scaling.json")
    parser.add_argument("--png", type=Path, default=REPO / "bench" / "scaling.png")
    parser.add_argument("--plot-only", action="store_true", help="redraw the PNG from --json")
    options = parser.parse_args()

    if options.plot_only:
        plot(json.loads(options.json.read_text()), options.png)
        return 0
    if not options.binary.exists():
        print(f"{options.binary} does not exist: build quiver first (or pass --binary)", file=sys.stderr)
        return 2
    shared = shared_dir()
    scenes, missing = scene_list(shared)
    if not scenes:
        print(f"no scenes under {shared} (set QUIVER_SHARED_DIR)", file=sys.stderr)
        return 2
    for name in missing:
        print(f"{name}: not in {shared / 'scenes' / 'spd'}, skipped", file=sys.stderr)

    results = {"settings": {"width": options.width, "height": options.height, "threads": options.threads,
                            "threads_label": "all" if options.threads == 0 else str(options.threads),
                            "repeat": options.repeat, "timeout_s": options.timeout, "quick": options.quick,
                            "binary": str(options.binary), "machine": platform.node(),
                            "date": time.strftime("%Y-%m-%d %H:%M:%S"), "load_average": os.getloadavg()},
               "missing_spd_scenes": missing, "scenes": []}
    with tempfile.TemporaryDirectory(prefix="quiver_scaling_") as work:
        for name, path in scenes:
            entry = measure(name, path, options, Path(work))
            if entry is not None:
                results["scenes"].append(entry)
    results["scenes"].sort(key=lambda r: r["primitives"] or 0)
    options.json.parent.mkdir(parents=True, exist_ok=True)
    options.json.write_text(json.dumps(results, indent=2) + "\n")
    plot(results, options.png)
    print(f"wrote {options.json} and {options.png}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
