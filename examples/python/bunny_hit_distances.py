#!/usr/bin/python3
"""Rays made with NumPy against the Stanford bunny: a pinhole camera's rays
through every pixel, the closest hits from quiver, and a figure of the hit
distances (an image of t, and their histogram).

Usage: bunny_hit_distances.py [BUNNY.obj] [--output FIGURE.png]
The mesh defaults to $QUIVER_SHARED_DIR/meshes/stanford-bunny.obj. Without a
display (or with --output) the figure is written to a PNG (matplotlib's Agg
backend); else it is shown. Run from the checkout after building:
    PYTHONPATH=build/python /usr/bin/python3 examples/python/bunny_hit_distances.py
"""
import argparse
import os
import sys

import numpy as np
import quiver
from figure_output import pyplot, show_or_save


def pinhole_rays(eye, target, width, height, fov_degrees):
    """Unit rays from eye through each pixel centre, row by row, +y up."""
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half = np.tan(np.radians(fov_degrees) / 2)
    x = (np.arange(width) + 0.5) / width * 2 - 1
    y = 1 - (np.arange(height) + 0.5) / height * 2
    px, py = np.meshgrid(x * half * width / height, y * half)
    directions = forward + px[..., None] * right + py[..., None] * up
    directions /= np.linalg.norm(directions, axis=-1, keepdims=True)
    origins = np.broadcast_to(eye, directions.shape)
    return np.ascontiguousarray(origins.reshape(-1, 3)), directions.reshape(-1, 3)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    shared = os.environ.get("QUIVER_SHARED_DIR", "")
    parser.add_argument("mesh", nargs="?", default=os.path.join(shared, "meshes", "stanford-bunny.obj"))
    parser.add_argument("--output", help="write the figure to this PNG instead of showing it")
    args = parser.parse_args()
    if not os.path.isfile(args.mesh):
        sys.exit("no mesh at '%s': give its path, or set QUIVER_SHARED_DIR" % args.mesh)
    plt = pyplot(args.output)

    scene = quiver.load(args.mesh)
    low, high = (np.array(b) for b in scene.bounds)
    centre, size = (low + high) / 2, np.linalg.norm(high - low)
    width, height = 480, 360
    origins, directions = pinhole_rays(centre + np.array([0.3, 0.2, 1.0]) * size, centre, width, height, 35)
    hits = scene.intersect(origins, directions)  # float64 rays are read as float32
    t = hits["t"].reshape(height, width)
    hit = np.isfinite(t)
    print("%s: %d of %d rays hit; t in [%.4g, %.4g]" % (scene, hit.sum(), t.size, t[hit].min(), t[hit].max()))

    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    shown = left.imshow(np.where(hit, t, np.nan), cmap="viridis")
    left.set_title("hit distance t (misses blank)")
    left.axis("off")
    figure.colorbar(shown, ax=left)
    right.hist(t[hit], bins=80)
    right.set_xlabel("t")
    right.set_ylabel("rays")
    right.set_title("%d hits" % hit.sum())
    show_or_save(figure, args.output, "bunny_hit_distances.png")


if __name__ == "__main__":
    main()
