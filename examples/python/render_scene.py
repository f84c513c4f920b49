#!/usr/bin/python3
"""A quiver render shown with matplotlib: the image (linear RGB, encoded
for display with the sRGB curve) beside its depth AOV.

Usage: render_scene.py [SCENE] [--width W] [--height H] [--aa MODE] [--output FIGURE.png]
SCENE defaults to io/examples/shadows_soft.toml. Without a display (or with
--output) the figure is written to a PNG (matplotlib's Agg backend). Run
from the checkout after building:
    PYTHONPATH=build/python /usr/bin/python3 examples/python/render_scene.py
"""
import argparse
import os

import numpy as np
import quiver
from figure_output import pyplot, show_or_save

HERE = os.path.dirname(os.path.abspath(__file__))


def srgb(linear):
    """Linear RGB to display values in [0, 1] (the sRGB transfer curve)."""
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", default=os.path.join(HERE, "..", "..", "io", "examples", "shadows_soft.toml"))
    parser.add_argument("--width", type=int, default=480)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--aa", default="grid:2")
    parser.add_argument("--output", help="write the figure to this PNG instead of showing it")
    args = parser.parse_args()
    plt = pyplot(args.output)

    scene = quiver.load(args.scene)
    rendered = quiver.render(scene, width=args.width, height=args.height, aa=args.aa, aov="depth")
    image = rendered.color
    print("%s: %dx%d, mean linear value %.4f" % (scene, image.shape[1], image.shape[0], image.mean()))

    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    left.imshow(srgb(image))
    left.set_title(os.path.basename(args.scene))
    left.axis("off")
    depth = np.where(np.isfinite(rendered.depth), rendered.depth, np.nan)
    shown = right.imshow(depth, cmap="magma")
    right.set_title("depth AOV (misses blank)")
    right.axis("off")
    figure.colorbar(shown, ax=right)
    show_or_save(figure, args.output, "render_scene.png")


if __name__ == "__main__":
    main()
