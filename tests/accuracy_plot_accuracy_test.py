#!/usr/bin/python3
"""bench/accuracy/plot_accuracy.py draws every chart from results holding
widths it has no marker of its own for: the fixture tests/data/accuracy_results
has 16-wide rows (the avx512 unit) and 32-wide ones (no unit yet). Given
quiver_accuracy, it also draws them from a fresh `--quick` run (this CPU's
units; about 5 s), so the script keeps up with the columns the study writes.
The charts go to a temporary directory; each must be written, as a PNG.
Every width in the fixture's speed.csv must get its own marker.

Usage: accuracy_plot_accuracy_test.py [QUIVER_ACCURACY] (run by ctest; exit
77 = skipped, when matplotlib is missing: .ci/install-deps installs
python3-matplotlib).
"""
import csv
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "bench", "accuracy", "plot_accuracy.py")
FIXTURE = os.path.join(HERE, "data", "accuracy_results")
CHARTS = (["pareto_%s.png" % k for k in ("sphere", "plane", "triangle", "polygon", "cone")]
          + ["sweep_%s.png" % d for d in ("distance", "size", "far", "grazing")]
          + ["watertight.png", "self_intersection.png", "anti_aliasing.png"])
SKIP = 77


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def plot(results, charts):
    """Runs the plotting script on results; every chart must be a PNG in charts."""
    run = subprocess.run([sys.executable, SCRIPT, results, charts], capture_output=True, text=True)
    if run.returncode != 0:
        fail("plot_accuracy.py %s exited with %d:\n%s%s" % (results, run.returncode, run.stdout, run.stderr))
    for name in CHARTS:
        path = os.path.join(charts, name)
        if not os.path.isfile(path):
            fail("%s was not written from %s" % (name, results))
        with open(path, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                fail("%s is not a PNG" % name)


def main():
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("SKIP: %s has no matplotlib (install python3-matplotlib, as .ci/install-deps does)" % sys.executable)
        sys.exit(SKIP)
    with open(os.path.join(FIXTURE, "speed.csv"), newline="") as f:
        widths = {(r["precision"], r["width"]) for r in csv.DictReader(f)}
    if ("float", "16") not in widths or ("float", "32") not in widths:
        fail("the fixture lost its width-16 or width-32 rows")

    with tempfile.TemporaryDirectory(prefix="quiver_plot_accuracy-") as work:
        plot(FIXTURE, os.path.join(work, "fixture_charts"))
        if len(sys.argv) > 1:
            quick = os.path.join(work, "quick_results")
            run = subprocess.run([sys.argv[1], "--quick", "--out", quick], capture_output=True, text=True)
            if run.returncode != 0:
                fail("%s --quick exited with %d:\n%s" % (sys.argv[1], run.returncode, run.stderr))
            plot(quick, os.path.join(work, "quick_charts"))

    # One marker per (precision, width) present, none shared.
    sys.path.insert(0, os.path.dirname(SCRIPT))
    import plot_accuracy
    markers = {key: plot_accuracy.width_marker(*key) for key in widths}
    if len(set(markers.values())) != len(markers):
        fail("widths share a marker: %s" % sorted(markers.items()))
    print("PASS: %d charts from the fixture (widths %s)%s" % (len(CHARTS), sorted(markers),
                                                               " and from a --quick run" if len(sys.argv) > 1 else ""))


if __name__ == "__main__":
    main()
