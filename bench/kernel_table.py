#!/usr/bin/env python3
"""Turns one quiver_bench JSON run into the kernel table of bench/README.md.

Usage: kernel_table.py RESULTS.json [README.md]
Prints the table; with README.md, replaces the text between the
<!-- kernel-table --> and <!-- /kernel-table --> markers.
Ratios come from the one run, so machine noise between runs cancels.
"""
import json
import re
import sys

# Floating-point operations per ray-primitive test on the hit path, counted
# from each kernel's formula (add, sub, mul, div, sqrt = 1; fma = 2; compares
# and selects not counted). See bench/README.md for how each was counted.
FLOPS_PER_TEST = {
    "plane/seed": 12,
    "plane/anchored": 14,
    "sphere/algebraic": 34,
    "sphere/geometric": 30,
    "sphere/robust": 49,
    "triangle/moller_trumbore": 61,
    "triangle/watertight": 59,
    "cone/quadric": 141,
}


def main():
    data = json.load(open(sys.argv[1]))
    rate = {}
    peak = {}  # width -> FLOP/s
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        name = b["run_name"] if "run_name" in b else b["name"]
        ips = b.get("items_per_second")
        if ips is None:
            continue
        pm = re.match(r"^peak/fma/w(\d+)", name)
        if pm:
            peak[int(pm.group(1))] = ips
            continue
        m = re.match(r"^(\w+/\w+)/w(\d+)/(\w+)(/\w+)?$", name)
        if not m:
            continue
        kernel, width, mix, variant = m.group(1), int(m.group(2)), m.group(3), (m.group(4) or "")[1:]
        rate[(kernel, mix + ("/" + variant if variant else ""), width)] = ips

    rows = sorted({(k, mix) for (k, mix, _) in rate})
    lines = [
        "| kernel/method | rays | w1 Mtests/s | w4 Mtests/s | w8 Mtests/s | w16 Mtests/s | w4/w1 | w8/w1 | w16/w1 "
        "| FLOP/test | w8 % of 8-wide FMA peak | w16 % of 16-wide FMA peak |",
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for kernel, mix in rows:
        r = [rate.get((kernel, mix, w)) for w in (1, 4, 8, 16)]
        cell = lambda v: f"{v / 1e6:,.0f}" if v else "-"
        ratio = lambda a, b: f"{a / b:.1f}x" if a and b else "-"
        flops = FLOPS_PER_TEST.get(kernel)
        frac = lambda v, w: f"{100 * v * flops / peak[w]:.0f}%" if (flops and v and peak.get(w)) else "-"
        lines.append(
            f"| {kernel} | {mix} | {cell(r[0])} | {cell(r[1])} | {cell(r[2])} | {cell(r[3])} | "
            f"{ratio(r[1], r[0])} | {ratio(r[2], r[0])} | {ratio(r[3], r[0])} | {flops or '-'} | "
            f"{frac(r[2], 8)} | {frac(r[3], 16)} |"
        )
    for w in sorted(peak):
        lines.append("")
        lines.append(f"Measured {w}-wide FMA peak of one core in the same run: {peak[w] / 1e9:.1f} GFLOP/s "
                     f"(`peak/fma/w{w}`).")
    table = "\n".join(lines)
    print(table)
    if len(sys.argv) > 2:
        readme = open(sys.argv[2]).read()
        new = re.sub(r"(<!-- kernel-table -->\n).*?(<!-- /kernel-table -->)",
                     lambda mm: mm.group(1) + table + "\n" + mm.group(2), readme, flags=re.S)
        open(sys.argv[2], "w").write(new)


if __name__ == "__main__":
    main()
