#!/usr/bin/python3
"""Renders a matrix of scenes x anti-aliasing modes x SIMD widths to EXR
with every AOV, and compares two such matrices byte for byte: the proof
that a refactor left every image, depth, normal and id unchanged.

  render_matrix.py render QUIVER OUT_DIR [--shared DIR]
  render_matrix.py compare DIR_A DIR_B

`render` runs QUIVER (a quiver binary) once per case (64 x 48, seed 7;
every thread count gives the same image) and writes
OUT_DIR/<scene>.<aa>.<simd>.exr for each SIMD width this CPU has: the
built-in scene, the project's examples and test scenes, and SPD scenes and
two meshes from --shared (default ../shared beside the repository) where
it has them. `compare` prints each case that differs or is missing and
exits 1 if any does. Render the matrix with the binary of the old tree,
then of the new one, then compare.
"""

import argparse
import filecmp
import pathlib
import subprocess
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent

PROJECT_SCENES = [
    "io/examples/adaptive_aa.toml",
    "io/examples/glass_tir.toml",
    "io/examples/instances.toml",
    "io/examples/mesh_include.toml",
    "io/examples/reflection_depth.toml",
    "io/examples/shadows_hard.toml",
    "io/examples/shadows_soft.toml",
    "io/examples/textures.toml",
    "io/examples/transparent_shadows.toml",
    "tests/data/nff/every_entity.nff",
    "tests/data/obj/polygons.obj",
]
SHARED_SCENES = [
    "scenes/spd/balls-s1.nff",
    "scenes/spd/gears-s1.nff",
    "scenes/spd/tetra-s1.nff",
    "scenes/spd/teapot-s2.nff",
    "meshes/spot.obj",
    "meshes/stanford-bunny.obj",
]
AA_MODES = ["none", "grid:2", "jitter:2", "adaptive:0.1:2", "corners", "refine:0.05:4"]
SIMD = ["scalar", "avx2", "avx512"]


def scenes(shared):
    """The scene files, None standing for the built-in scene."""
    found = [None] + [REPO / s for s in PROJECT_SCENES]
    for s in SHARED_SCENES:
        path = shared / s
        if path.exists():
            found.append(path)
        else:
            print(f"render_matrix: {path} is absent; left out", file=sys.stderr)
    return found


def render(args):
    out = pathlib.Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    supported = [s for s in SIMD if subprocess.run([args.quiver, "render", "--simd", s, "--width", "1",
                                                     "--height", "1", "-o", str(out / "probe.exr")],
                                                    capture_output=True).returncode == 0]
    (out / "probe.exr").unlink(missing_ok=True)
    count = 0
    for scene in scenes(pathlib.Path(args.shared)):
        for aa in AA_MODES:
            for simd in supported:
                name = f"{scene.name if scene else 'built-in'}.{aa.replace(':', '_')}.{simd}.exr"
                command = [args.quiver, "render", *([str(scene)] if scene else []), "--width", "64", "--height", "48", "--aa", aa,
                           "--simd", simd, "--seed", "7", "--aov", "depth,normal,id", "-o", str(out / name)]
                result = subprocess.run(command, capture_output=True, text=True)
                if result.returncode != 0:
                    sys.exit(f"render_matrix: {' '.join(command)} failed ({result.returncode}):\n{result.stderr}")
                count += 1
    print(f"render_matrix: {count} renders in {out} ({', '.join(supported)})")


def compare(args):
    a, b = pathlib.Path(args.dir_a), pathlib.Path(args.dir_b)
    names = sorted({p.name for p in a.glob("*.exr")} | {p.name for p in b.glob("*.exr")})
    differing = [n for n in names if not ((a / n).exists() and (b / n).exists()
                                          and filecmp.cmp(a / n, b / n, shallow=False))]
    for n in differing:
        print(f"differs or missing: {n}")
    print(f"render_matrix: {len(names) - len(differing)} of {len(names)} renders byte-identical")
    return 1 if differing or not names else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    r = sub.add_parser("render", help="render the matrix with one quiver binary")
    r.add_argument("quiver")
    r.add_argument("out_dir")
    r.add_argument("--shared", default=str(REPO.parent / "shared"))
    c = sub.add_parser("compare", help="compare two rendered matrices byte for byte")
    c.add_argument("dir_a")
    c.add_argument("dir_b")
    args = parser.parse_args()
    if args.command == "render":
        render(args)
        return 0
    return compare(args)


if __name__ == "__main__":
    sys.exit(main())
