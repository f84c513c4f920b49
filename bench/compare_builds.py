#!/usr/bin/python3
"""Two builds of quiver against Embree, alternating (bench/README.md, "Against
Embree", the "paired" figures).

Runs `quiver_bench_embree --repeat R --scenes S --json FILE` of build A, then
of build B, RUNS times, and prints per scene, ray set and thread count the
median over the runs of quiver/e8 and quiver/e1 for each build and B's change
against A. Each run times Embree beside quiver, so its ratios are measured
against the machine's state at that moment; alternating the builds and taking
medians keeps a noisy, shared machine's drift out of the comparison. Give
the same binary twice (copied under another name) for the A/A spread.

Run from anywhere: /usr/bin/python3 bench/compare_builds.py A B [--runs 10]
  [--repeat 7] [--scenes stanford-bunny] [--env NAME=VALUE ...]
A and B are paths to quiver_bench_embree binaries; $QUIVER_SHARED_DIR must
name the shared data (as for the binaries themselves).
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def run_once(binary, args, env, json_path):
    command = [binary, "--repeat", str(args.repeat), "--scenes", args.scenes, "--json", json_path]
    result = subprocess.run(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        sys.exit(f"compare_builds: {' '.join(command)} failed ({result.returncode}):\n{result.stderr}")
    with open(json_path) as f:
        return json.load(f)


def ratios(scenes):
    """(scene, rays, threads) -> (quiver/e8, quiver/e1) of one run."""
    return {(s["scene"], r["rays"], r["threads"]): (r["quiver_over_embree8"], r["quiver_over_embree1"])
            for s in scenes for r in s["runs"]}


def parse_env(pairs):
    env = dict(os.environ)
    for pair in pairs:
        name, sep, value = pair.partition("=")
        if not sep or not name:
            sys.exit(f"compare_builds: --env expects NAME=VALUE, got '{pair}'")
        env[name] = value
    return env


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_a", help="quiver_bench_embree of the baseline")
    parser.add_argument("build_b", help="quiver_bench_embree of the change")
    parser.add_argument("--runs", type=int, default=10, help="runs of each build, alternating (default 10)")
    parser.add_argument("--repeat", type=int, default=7, help="--repeat of each run (default 7)")
    parser.add_argument("--scenes", default="stanford-bunny", help="--scenes of each run (default stanford-bunny)")
    parser.add_argument("--env", action="append", default=[], metavar="NAME=VALUE",
                        help="an environment variable for build B only (e.g. QUIVER_SIMD=avx2)")
    args = parser.parse_args()
    if args.runs < 1 or args.repeat < 1:
        sys.exit("compare_builds: --runs and --repeat must be at least 1")
    for binary in (args.build_a, args.build_b):
        if not os.access(binary, os.X_OK):
            sys.exit(f"compare_builds: {binary} is not an executable file")
    env_a, env_b = dict(os.environ), parse_env(args.env)

    per_build = ([], [])
    with tempfile.TemporaryDirectory() as tmp:
        for run in range(args.runs):
            for index, (binary, env) in enumerate(((args.build_a, env_a), (args.build_b, env_b))):
                path = os.path.join(tmp, f"run{run}_{index}.json")
                per_build[index].append(ratios(run_once(binary, args, env, path)))
            print(f"run {run + 1} of {args.runs} done", file=sys.stderr)

    print(f"medians over {args.runs} alternating runs of each build; change = B against A")
    print("| scene | rays | threads | A quiver/e8 | B quiver/e8 | change | A quiver/e1 | B quiver/e1 | change |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for key in per_build[0][0]:
        a8, b8, a1, b1 = (statistics.median(runs[key][which] for runs in per_build[build])
                          for which, build in ((0, 0), (0, 1), (1, 0), (1, 1)))
        print(f"| {key[0]} | {key[1]} | {key[2]} | {a8:.3f}x | {b8:.3f}x | {(b8 / a8 - 1) * 100:+.1f}% "
              f"| {a1:.3f}x | {b1:.3f}x | {(b1 / a1 - 1) * 100:+.1f}% |")


if __name__ == "__main__":
    main()
