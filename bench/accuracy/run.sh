#!/usr/bin/env bash
# Regenerates every measurement and chart of bench/ACCURACY.md: builds
# quiver_accuracy (release preset, build/; or QUIVER_BUILD_DIR, configured
# Release), runs it into bench/accuracy/results/ (a few minutes on 2 cores;
# extra arguments go to quiver_accuracy, e.g. --quick or --only speed), then
# draws bench/accuracy/charts/*.png with /usr/bin/python3 and matplotlib.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
if [[ -n "${QUIVER_BUILD_DIR:-}" ]]; then
  build="$QUIVER_BUILD_DIR"
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
else
  build=build
  cmake --preset release
fi
cmake --build "$build" --target quiver_accuracy -j2
"$build/bin/quiver_accuracy" --out bench/accuracy/results "$@"
/usr/bin/python3 bench/accuracy/plot_accuracy.py bench/accuracy/results bench/accuracy/charts
