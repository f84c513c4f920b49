#!/usr/bin/python3
"""Regenerates every chart of bench/ACCURACY.md from quiver_accuracy's CSV files.

Usage: /usr/bin/python3 bench/accuracy/plot_accuracy.py [RESULTS_DIR] [CHARTS_DIR]
(defaults: bench/accuracy/results and bench/accuracy/charts next to this file).
Charts: pareto_<kind>.png (tests/s against error, each method x width x
float/double), sweep_<distribution>.png (error and wrong answers along each
stress sweep), watertight.png, self_intersection.png, anti_aliasing.png.
Reads only the CSV columns it plots; writes PNG at 110 dpi.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "results")
CHARTS = sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "charts")
KINDS = ["sphere", "plane", "triangle", "polygon", "cone"]
DISTRIBUTIONS = {
    "distance": "origin distance / primitive size",
    "size": "primitive size (whole case scaled)",
    "far": "primitive distance from the world origin",
    "grazing": "distance to the silhouette (relative) or angle to the surface (rad)",
}
COLORS = {
    "sphere/algebraic": "tab:red",
    "sphere/geometric": "tab:orange",
    "sphere/robust": "tab:green",
    "plane/seed": "tab:blue",
    "plane/anchored": "tab:pink",
    "triangle/moller_trumbore": "tab:purple",
    "triangle/watertight": "tab:cyan",
    "polygon/crossing": "tab:brown",
    "cone/quadric": "tab:olive",
}
FLOOR = 1e-3  # log axes: zeros are drawn at this value


def read(name):
    with open(os.path.join(RESULTS, name), newline="") as f:
        return list(csv.DictReader(f))


def floor(value):
    return max(float(value), FLOOR)


def save(fig, name):
    os.makedirs(CHARTS, exist_ok=True)
    fig.savefig(os.path.join(CHARTS, name), dpi=110, bbox_inches="tight")
    plt.close(fig)
    print("wrote", os.path.join(CHARTS, name))


def method_key(row):
    return row["kind"] + "/" + row["method"]


WIDTH_MARKERS = {("float", "1"): "o", ("float", "4"): "s", ("float", "8"): "^", ("float", "16"): "P",
                 ("double", "1"): "D"}
SPARE_MARKERS = ["X", "v", "<", ">", "h", "p", "*", "d", "8"]  # widths without a marker of their own


def width_marker(precision, width):
    """The marker of a (precision, width) pair; a width the table lacks gets
    the next spare marker (the same one for the rest of the run), never a KeyError."""
    key = (precision, width)
    if key not in WIDTH_MARKERS:
        used = set(WIDTH_MARKERS.values())
        WIDTH_MARKERS[key] = next((m for m in SPARE_MARKERS if m not in used), "x")
    return WIDTH_MARKERS[key]


def width_order(key):
    """Float before double, then by width."""
    precision, width = key
    return (precision != "float", int(width) if width.isdigit() else 0, width)


def pareto_charts(errors, speed, leaks):
    """Per kind: tests/s against worst p99 ULP, against the wrong-answer rate,
    and (triangles, polygons) against the leak rate through shared edges."""
    summary = {}
    for row in errors:
        if row["built"] != "1" or row["distribution"] == "grazing":
            continue
        key = (method_key(row), row["precision"])
        s = summary.setdefault(key, {"ulp": 0.0, "wrong": 0, "counted": 0})
        s["ulp"] = max(s["ulp"], float(row["ulp_p99"]))
        if row["precision"] == "double" or row["width"] == "1":
            s["wrong"] += int(row["false_miss"]) + int(row["false_hit"])
            s["counted"] += int(row["counted"])
    leak_rate = {}
    for r in leaks:
        total = leak_rate.setdefault(method_key(r), [0, 0])
        total[0] += int(r["edge_leaks"]) + int(r["vertex_leaks"])
        total[1] += int(r["edge_rays"]) + int(r["vertex_rays"])
    widths = sorted({(row["precision"], row["width"]) for row in speed}, key=width_order)
    float_widths = "/".join("w" + w for p, w in widths if p == "float")
    for kind in KINDS:
        with_leaks = any(k.startswith(kind + "/") for k in leak_rate)
        fig, axes = plt.subplots(1, 3 if with_leaks else 2, figsize=(16 if with_leaks else 11, 4.2))
        for row in speed:
            if row["kind"] != kind:
                continue
            key = method_key(row)
            s = summary[(key, row["precision"])]
            rate = float(row["tests_per_second"])
            marker = width_marker(row["precision"], row["width"])
            values = [floor(s["ulp"]), max(s["wrong"] / max(s["counted"], 1), 1e-6)]
            if with_leaks:
                leaked, rays = leak_rate.get(key, (0, 0))
                values.append(max(leaked / rays, 1e-8) if rays and row["precision"] == "float" else None)
            for ax, y in zip(axes, values):
                if y is not None:
                    ax.scatter(rate, y, color=COLORS[key], marker=marker, s=55,
                               facecolors="none" if row["precision"] == "double" else COLORS[key])
        axes[0].set_ylabel("worst p99 error of t (float ulps; %g = 0)" % FLOOR)
        axes[1].set_ylabel("wrong answers / counted rays (1e-6 = none)")
        if with_leaks:
            axes[2].set_ylabel("rays leaked at shared edges and vertices (1e-8 = none)")
        for ax in axes:
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("tests per second (64 primitives, 4096 rays, packets)")
            ax.grid(True, which="both", alpha=0.3)
        handles = [plt.Line2D([], [], color=c, marker="o", linestyle="", label=k)
                   for k, c in COLORS.items() if k.startswith(kind + "/")]
        handles += [plt.Line2D([], [], color="gray", marker=width_marker(p, w), linestyle="", label="%s w%s" % (p, w),
                               markerfacecolor="none" if p == "double" else "gray")
                    for p, w in widths]
        axes[0].legend(handles=handles, fontsize=7, loc="best")
        fig.suptitle("%s: speed against accuracy (distance, size and far sweeps; %s float kernels, "
                     "hollow diamond = the same template in double, one ray at a time)" % (kind, float_widths),
                     fontsize=10)
        save(fig, "pareto_%s.png" % kind)


def sweep_charts(errors):
    """Per distribution: relative t error and wrong-answer rate along the sweep."""
    for distribution, xlabel in DISTRIBUTIONS.items():
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        series = {}
        for row in errors:
            if row["distribution"] != distribution or row["built"] != "1":
                continue
            if row["precision"] == "float" and row["width"] != "1":
                continue  # every width gives the same bits (same_bits_as_width1)
            key = (method_key(row), row["precision"])
            series.setdefault(key, []).append(row)
        for (key, precision), rows in sorted(series.items()):
            x = [float(r["parameter"]) for r in rows]
            rel = [max(float(r["relative_max"]), 1e-17) for r in rows]
            wrong = [max((int(r["false_miss"]) + int(r["false_hit"])) / max(int(r["counted"]), 1), 1e-6) for r in rows]
            style = "-" if precision == "float" else ":"
            label = key + ("" if precision == "float" else " (double)")
            axes[0].plot(x, rel, style, color=COLORS[key], marker="o", markersize=3, label=label)
            axes[1].plot(x, wrong, style, color=COLORS[key], marker="o", markersize=3, label=label)
        axes[0].axhline(1e-3, color="k", linewidth=0.8, linestyle="--")
        axes[0].set_ylabel("max relative error of t (counted rays)")
        axes[1].set_ylabel("wrong answers / counted rays (1e-6 = none)")
        for ax in axes:
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.grid(True, which="both", alpha=0.3)
        axes[1].legend(fontsize=7, loc="best")
        fig.suptitle("%s sweep (width 1 float = every width; dotted: the same kernel in double)" % distribution,
                     fontsize=10)
        save(fig, "sweep_%s.png" % distribution)


def watertight_chart(rows):
    fig, ax = plt.subplots(figsize=(max(8, 0.9 * len(rows)), 4.4))
    labels, values, colors = [], [], []
    for r in rows:
        rays = int(r["edge_rays"]) + int(r["vertex_rays"])
        leaks = int(r["edge_leaks"]) + int(r["vertex_leaks"])
        labels.append("%s\n%s\n%.1fM rays" % (r["mesh"].replace("_", "\n"), r["method"], rays / 1e6))
        values.append(max(leaks, 0.5))
        colors.append(COLORS[method_key(r)])
    bars = ax.bar(range(len(values)), values, color=colors)
    for bar, v in zip(bars, values):
        ax.annotate("0" if v < 1 else "%d" % v, (bar.get_x() + bar.get_width() / 2, v), ha="center",
                    va="bottom", fontsize=8)
    ax.set_xticks(range(len(labels)))
    ax.set_xticklabels(labels, fontsize=7)
    ax.set_yscale("log")
    ax.set_ylabel("rays leaked through shared edges and vertices")
    ax.set_title("Watertightness: rays from inside closed meshes aimed exactly at edges and vertices", fontsize=10)
    save(fig, "watertight.png")


def self_intersection_chart(rows):
    methods = []
    for r in rows:
        if method_key(r) not in methods:
            methods.append(method_key(r))
    fig, axes = plt.subplots(2, 4, figsize=(15, 7), sharex=True, sharey=True)
    for ax, key in zip(axes.flat, methods):
        for rule, style in (("zero", ":"), ("epsilon", "--"), ("robust", "-")):
            pts = [(float(r["scale"]), max(float(r["acne_fraction"]), 1e-5)) for r in rows
                   if method_key(r) == key and r["rule"] == rule]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, marker="o", markersize=3,
                    label={"zero": "no offset", "epsilon": "tmin = 1e-4", "robust": "robust offset"}[rule])
        ax.set_title(key, fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("scene scale")
    for ax in axes[:, 0]:
        ax.set_ylabel("acne fraction (1e-5 = none)")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Self-intersection: spawned rays re-hitting their own primitive", fontsize=10)
    save(fig, "self_intersection.png")


def anti_aliasing_chart(rows):
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    columns = min(3, len(scenes))
    rows_of_charts = (len(scenes) + columns - 1) // columns
    fig, axes = plt.subplots(rows_of_charts, columns, figsize=(6 * columns, 4.5 * rows_of_charts), squeeze=False)
    axes = axes.flatten()
    for ax in axes[len(scenes):]:
        ax.set_visible(False)
    families = {"none": "k", "grid": "tab:blue", "jitter": "tab:orange", "adaptive": "tab:green", "corners": "tab:red",
                "refine": "tab:purple", "refine:grid": "tab:brown"}

    def family_of(mode):
        """A mode's family: its name, with refine's grid strata apart (refine:T:N:grid)."""
        parts = mode.split(":")
        return parts[0] + (":" + parts[3] if parts[0] == "refine" and len(parts) == 4 else "")

    # Point-sampled textures solid, box-filtered ones dashed (scenes with textures only).
    filters = {"none": ("-o", ""), "box": ("--s", " (box-filtered textures)")}
    for ax, scene in zip(axes, scenes):
        for family, color in families.items():
            for texture_filter, (style, suffix) in filters.items():
                pts = [r for r in rows if r["scene"] == scene and family_of(r["mode"]) == family
                       and r.get("texture_filter", "none") == texture_filter]
                if not pts:
                    continue
                ax.plot([float(r["render_ms"]) for r in pts], [float(r["rmse"]) for r in pts], style, color=color,
                        label=family + suffix, markersize=4)
                for r in pts:
                    ax.annotate(r["mode"], (float(r["render_ms"]), float(r["rmse"])), fontsize=7, xytext=(3, 3),
                                textcoords="offset points")
        first = next(r for r in rows if r["scene"] == scene)
        ax.set_title("%s %sx%s (reference %s, %.0f ms)" % (scene, first["width"], first["height"],
                                                             first["reference_mode"], float(first["reference_ms"])),
                     fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("render time, ms (one thread)")
        ax.set_ylabel("RMSE against the reference (linear RGB in [0, 1])")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, "anti_aliasing.png")


def main():
    errors = read("kernel_errors.csv")
    leaks = read("watertight.csv")
    pareto_charts(errors, read("speed.csv"), leaks)
    sweep_charts(errors)
    watertight_chart(leaks)
    self_intersection_chart(read("self_intersection.csv"))
    anti_aliasing_chart(read("anti_aliasing.csv"))


if __name__ == "__main__":
    main()
