#!/usr/bin/python3
"""The README's table of headline figures, measured on this machine.

Prints one Markdown table on stdout (progress goes to stderr), naming the CPU
(lscpu's "Model name") and the kernel unit quiver picked, with three kinds
of rows; every figure is a ratio of times, above 1 when quiver is faster:

  Embree   build/bin/quiver_bench_embree --width 512 --height 512 --repeat 7
           (bench/README.md, "Against Embree"): per scene and ray kind
           (primary, reflection, diffuse, shadow), one thread, the time of
           Embree's fastest API on those rays over quiver's on the same
           rays, with that API's name (e1, e4, e8, e16): the fastest, as the
           harness picks it (fastest_embree and quiver_over_fastest_embree
           in its JSON), of rtcIntersect1 and each of rtcIntersect4/8/16
           that Embree runs natively on this CPU (rtcOccluded1/4/8/16 for
           shadow rays).
           Skipped, with a note, when that program is not built (it needs
           libembree-dev when CMake configures).
  POV-Ray  POV-Ray 3.7 and quiver side by side on the SPD scenes balls-s4,
           gears-s4 and teapot-s12 at 512x512, run back to back --runs
           times (medians):
             povray +I<scene>.pov +O<out>.png +W512 +H512 -D +A0.3 +AM2 +R3 -J
             quiver render <scene>.nff --width 512 --height 512
                 --aa adaptive:0.3:3 --threads 2 --quiet --stats S.json
           two ratios: whole-process wall time, and POV-Ray's reported
           "Trace Time" over quiver's render phase (render_ms of the stats).
           Each with its ceiling: the ratio quiver would reach if nothing but
           its BVH walks took time (the stats' traversal_ms, thread time,
           over the threads: a lower bound on the walks' wall time).
           Skipped, with a note, when povray is not on the PATH.
  SIMD     quiver's widest unit against --simd scalar, one thread, whole
           renders of balls-s4 and gears-s4 (--preset spd, 512x512) and of
           the built-in scene (its own 640x480), render_ms medians over
           --runs runs, the two widths interleaved; with its ceiling, the
           scalar render over the widest unit's walks alone (traversal_ms).

The SPD scenes come from the shared folder: --shared, else
$QUIVER_SHARED_DIR, else ../shared beside the repository (scenes/spd holds
the .nff and .pov files, meshes/ the OBJ meshes the Embree rows use).
QUIVER_SIMD is removed from the environment of every run, so quiver picks
its widest unit itself (the SIMD rows' scalar runs pass --simd scalar).

--quick: tiny images, one run, Embree --repeat 1: checks that the script and
the programs work; its figures mean nothing.

Run from anywhere: /usr/bin/python3 bench/headline.py [--runs 5] [--quick]
  [--shared DIR] [--quiver PATH] [--embree PATH] [--povray PATH]
"""

import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
POV_SCENES = ["balls-s4", "gears-s4", "teapot-s12"]
SIMD_SCENES = ["balls-s4", "gears-s4", None]  # None: the built-in scene
EMBREE_RAYS = ["primary", "reflection", "diffuse", "shadow"]
TIMEOUT_S = 3600


def log(message):
    print(message, file=sys.stderr, flush=True)


def cpu_model():
    """lscpu's "Model name", else /proc/cpuinfo's "model name"."""
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, env={**os.environ, "LC_ALL": "C"}).stdout
        for line in out.splitlines():
            if line.startswith("Model name:"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def clean_env(**extra):
    env = {k: v for k, v in os.environ.items() if k != "QUIVER_SIMD"}
    env.update(extra)
    return env


def run(command, cwd=None, env=None):
    """(completed process, wall seconds). Exits on a failure to start."""
    start = time.perf_counter()
    try:
        result = subprocess.run(command, cwd=cwd, env=env or clean_env(), capture_output=True, text=True,
                                timeout=TIMEOUT_S)
    except (OSError, subprocess.TimeoutExpired) as error:
        sys.exit(f"headline: {' '.join(map(str, command))}: {error}")
    return result, time.perf_counter() - start


def quiver_render(quiver, scene, out_dir, tag, args):
    """Runs `quiver render` with --stats; returns (stats dict, wall seconds)."""
    stats = Path(out_dir) / f"{tag}.json"
    command = [str(quiver), "render"] + ([str(scene)] if scene else []) + \
        ["-o", str(Path(out_dir) / f"{tag}.png")] + args + ["--quiet", "--stats", str(stats)]
    result, wall = run(command)
    if result.returncode != 0:
        sys.exit(f"headline: {' '.join(command)} failed ({result.returncode}):\n{result.stderr}")
    return json.loads(stats.read_text()), wall


def unit_name(stats):
    lanes = stats["lanes"]
    return f"{stats['kernel_unit']} ({lanes} lane{'s' if lanes != 1 else ''})"


def ratio(numerator, denominator):
    return f"{numerator / denominator:.2f}x" if denominator > 0 else "-"


def embree_rows(options, cpu, notes):
    if not os.access(options.embree, os.X_OK):
        notes.append(f"Embree rows skipped: {options.embree} is not built (CMake builds it when it finds "
                     "Embree 3: apt-get install libembree-dev, then configure again).")
        return []
    size, repeat = ("64", "1") if options.quick else ("512", "7")
    with tempfile.TemporaryDirectory() as tmp:
        json_path = Path(tmp) / "embree.json"
        command = [str(options.embree), "--width", size, "--height", size, "--repeat", repeat, "--json", str(json_path)]
        log("headline: " + " ".join(command))
        result, _ = run(command, env=clean_env(QUIVER_SHARED_DIR=str(options.shared)))
        if result.returncode != 0:
            notes.append(f"Embree rows skipped: `{' '.join(command[1:])}` failed: "
                         f"{result.stderr.strip().splitlines()[-1] if result.stderr.strip() else result.returncode}")
            return []
        scenes = json.loads(json_path.read_text())
    isa = next((line for line in result.stdout.splitlines() if line.startswith("Embree ISA")), "")
    if isa:
        notes.append(f"Embree rows: {isa.strip()}; quiver unit {scenes[0]['quiver_unit'] if scenes else '-'}.")
    how = f"`quiver_bench_embree --width {size} --height {size} --repeat {repeat}`"
    if any("quiver_over_fastest_embree" not in r for scene in scenes for r in scene["runs"]):
        notes.append(f"Embree rows skipped: {options.embree} does not report Embree's fastest API "
                     "(quiver_over_fastest_embree): build it again.")
        return []
    rows = []
    for scene in scenes:
        by_rays = {r["rays"]: r for r in scene["runs"] if r["threads"] == 1}
        figures = ", ".join(f"{rays} {by_rays[rays]['quiver_over_fastest_embree']:.2f}x "
                            f"({by_rays[rays]['fastest_embree']})" for rays in EMBREE_RAYS if rays in by_rays)
        rows.append(("quiver against Intel Embree 3, its fastest of `rtcIntersect1/4/8/16` per ray kind (named): "
                     "rays/s, same rays, 1 thread", cpu, scene["scene"], figures, how))
    return rows


POV_TRACE = re.compile(r"Trace Time:.*\(\s*([0-9.]+) seconds\)\s*\n\s*using (\d+) thread")


def pov_rows(options, cpu, notes):
    povray = options.povray or shutil.which("povray")
    if not povray or not os.access(povray, os.X_OK):
        notes.append(f"POV-Ray rows skipped: {options.povray or 'povray'} is not "
                     f"{'an executable file' if options.povray else 'on the PATH'} (apt-get install povray).")
        return []
    size = "64" if options.quick else "512"
    spd = options.shared / "scenes" / "spd"
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in POV_SCENES:
            pov, nff = spd / f"{name}.pov", spd / f"{name}.nff"
            if not (pov.exists() and nff.exists()):
                notes.append(f"POV-Ray row for {name} skipped: {pov} or {nff} is missing.")
                continue
            pov_wall, pov_trace, q_wall, q_render, q_walks, threads = [], [], [], [], [], set()
            for r in range(options.runs):
                log(f"headline: POV-Ray against quiver, {name}, run {r + 1} of {options.runs}")
                # POV-Ray writes only below its working directory by default: a relative +O.
                command = [povray, f"+I{pov}", "+Opov.png", f"+W{size}", f"+H{size}", "-D", "+A0.3", "+AM2",
                           "+R3", "-J"]
                result, wall = run(command, cwd=tmp)
                match = POV_TRACE.search(result.stderr + result.stdout)
                if result.returncode != 0 or not match:
                    tail = (result.stderr.strip().splitlines() or ["no output"])[-1]
                    notes.append(f"POV-Ray row for {name} skipped: `{' '.join(command)}` "
                                 f"{'failed' if result.returncode else 'printed no Trace Time'} ({tail}).")
                    break
                pov_wall.append(wall)
                pov_trace.append(float(match.group(1)))
                threads.add(int(match.group(2)))
                stats, wall = quiver_render(options.quiver, nff, tmp, "pov_quiver",
                                            ["--width", size, "--height", size, "--aa", "adaptive:0.3:3",
                                             "--threads", "2"])
                q_wall.append(wall)
                q_render.append(stats["render_ms"] / 1000)
                q_walks.append(stats["traversal_ms"] / 1000 / stats["threads"])
            else:
                walks = statistics.median(q_walks)
                figure = (f"wall time {ratio(statistics.median(pov_wall), statistics.median(q_wall))} "
                          f"(ceiling {ratio(statistics.median(pov_wall), walks)}), "
                          f"trace {ratio(statistics.median(pov_trace), statistics.median(q_render))} "
                          f"(ceiling {ratio(statistics.median(pov_trace), walks)})")
                rows.append(("quiver against POV-Ray 3.7: POV-Ray time / quiver time, 2 threads", cpu, f"{name}, {size}x{size}", figure,
                             f"`povray +A0.3 +AM2 +R3` against `quiver render --aa adaptive:0.3:3`, "
                             f"medians of {options.runs}"))
                if threads != {2}:
                    notes.append(f"POV-Ray used {', '.join(map(str, sorted(threads)))} thread(s) on {name}, "
                                 "quiver 2.")
    return rows


def simd_rows(options, cpu, notes):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in SIMD_SCENES:
            if name:
                scene = options.shared / "scenes" / "spd" / f"{name}.nff"
                if not scene.exists():
                    notes.append(f"SIMD row for {name} skipped: {scene} is missing.")
                    continue
                size = ["--width", "64", "--height", "64"] if options.quick else ["--width", "512", "--height", "512"]
                flags = ["--preset", "spd"] + size
                label = f"{name}, --preset spd, {size[1]}x{size[3]}"
            else:
                scene = None
                flags = ["--width", "64", "--height", "48"] if options.quick else []
                label = "built-in scene" + (", 64x48" if options.quick else ", 640x480")
            times = {"auto": [], "scalar": []}
            widest_walks = []
            units = {}
            for r in range(options.runs):
                log(f"headline: widest unit against scalar, {label}, run {r + 1} of {options.runs}")
                order = ["auto", "scalar"] if r % 2 == 0 else ["scalar", "auto"]  # interleaved, alternating
                for simd in order:
                    stats, _ = quiver_render(options.quiver, scene, tmp, f"simd_{simd}",
                                             flags + ["--threads", "1", "--simd", simd])
                    times[simd].append(stats["render_ms"])
                    units[simd] = unit_name(stats)
                    if simd == "auto":
                        widest_walks.append(stats["traversal_ms"])
            rows.append(("widest unit against `--simd scalar`: scalar time / widest time, 1 thread", cpu, label,
                         f"{ratio(statistics.median(times['scalar']), statistics.median(times['auto']))} "
                         f"(ceiling {ratio(statistics.median(times['scalar']), statistics.median(widest_walks))})",
                         f"`quiver render --simd auto` and `--simd scalar`, `--threads 1`, render_ms medians of {options.runs}, "
                         f"{units['auto']} against {units['scalar']}"))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    default_shared = Path(os.environ.get("QUIVER_SHARED_DIR", REPO.parent / "shared"))
    parser.add_argument("--shared", type=Path, default=default_shared,
                        help=f"the shared folder (scenes/spd, meshes); default {default_shared}")
    parser.add_argument("--runs", type=int, default=5, help="runs per POV-Ray and SIMD figure, medians (default 5)")
    parser.add_argument("--quick", action="store_true", help="tiny images, one run: checks the script works")
    parser.add_argument("--quiver", type=Path, default=REPO / "build" / "bin" / "quiver",
                        help="the quiver program (default build/bin/quiver)")
    parser.add_argument("--embree", type=Path, default=REPO / "build" / "bin" / "quiver_bench_embree",
                        help="the Embree benchmark (default build/bin/quiver_bench_embree)")
    parser.add_argument("--povray", help="the povray program (default: povray on the PATH)")
    options = parser.parse_args()
    if options.quick:
        options.runs = 1
    if options.runs < 1:
        sys.exit("headline: --runs must be at least 1")
    if not os.access(options.quiver, os.X_OK):
        sys.exit(f"headline: {options.quiver} is not an executable file (build quiver, or give --quiver PATH)")
    options.shared = options.shared.resolve()

    cpu = cpu_model()
    notes = []
    if not (options.shared / "scenes" / "spd").is_dir():
        notes.append(f"{options.shared / 'scenes' / 'spd'} not found: the rows that need the SPD scenes are "
                     "skipped (give --shared DIR or set QUIVER_SHARED_DIR).")
    with tempfile.TemporaryDirectory() as tmp:
        stats, _ = quiver_render(options.quiver, None, tmp, "unit", ["--width", "16", "--height", "12"])
    unit = unit_name(stats)

    rows = embree_rows(options, cpu, notes) + pov_rows(options, cpu, notes) + simd_rows(options, cpu, notes)

    print(f"CPU: {cpu}. quiver's kernel unit: {unit}."
          + (" --quick: tiny images, one run; these figures mean nothing." if options.quick else ""))
    print()
    print("| comparison (above 1: quiver, or its widest unit, is faster) | CPU | scene | ratio | measured with |")
    print("| --- | --- | --- | --- | --- |")
    for row in rows:
        print("| " + " | ".join(row) + " |")
    if notes:
        print()
        for note in notes:
            print(f"- {note}")


if __name__ == "__main__":
    main()
