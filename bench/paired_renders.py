#!/usr/bin/python3
"""Two quiver programs rendering the same scenes, interleaved (A B, then
B A, ...) so drift on a shared machine falls on both alike: the median
render time (the stats JSON's render_ms, one thread) of each and their
ratio, per scene. For "speed unchanged" claims across a refactor.

  paired_renders.py BEFORE AFTER [--runs N] [--shared DIR]

Scenes: balls-s4 and gears-s4 under --preset spd at 512x512 (from
--shared, default ../shared beside the repository) and the built-in
default scene. bench/phases.py also compares builds, phase by phase, at
one ray per pixel on scene files (it times `quiver trace` too, so it
cannot take the built-in scene) and writes bench/results; this script
times whole renders with each scene's own anti-aliasing and writes nothing.
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile

REPO = pathlib.Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("before", type=pathlib.Path)
    parser.add_argument("after", type=pathlib.Path)
    parser.add_argument("--runs", type=int, default=5, help="renders per program and scene (default 5)")
    parser.add_argument("--shared", type=pathlib.Path, default=REPO.parent / "shared")
    args = parser.parse_args()
    spd = args.shared / "scenes" / "spd"
    cases = [(name, [str(spd / f"{name}.nff"), "--preset", "spd", "--width", "512", "--height", "512"])
             for name in ("balls-s4", "gears-s4") if (spd / f"{name}.nff").exists()]
    cases.append(("built-in", []))
    programs = [("before", args.before.resolve()), ("after", args.after.resolve())]
    times = {(case, p): [] for case, _ in cases for p, _ in programs}
    with tempfile.TemporaryDirectory() as tmp:
        image, stats = pathlib.Path(tmp) / "out.png", pathlib.Path(tmp) / "stats.json"
        for run in range(args.runs):
            for case, scene in cases:
                for p, program in programs if run % 2 == 0 else programs[::-1]:
                    subprocess.run([str(program), "render", *scene, "--threads", "1", "--quiet", "-o", str(image),
                                    "--stats", str(stats)], check=True, cwd=REPO)
                    times[(case, p)].append(json.loads(stats.read_text())["render_ms"])
    print("| scene | before ms | after ms | after / before |")
    print("| --- | --- | --- | --- |")
    for case, _ in cases:
        before, after = statistics.median(times[(case, "before")]), statistics.median(times[(case, "after")])
        print(f"| {case} | {before:.0f} | {after:.0f} | {after / before:.3f} |")


if __name__ == "__main__":
    main()
