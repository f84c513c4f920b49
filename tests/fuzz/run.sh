#!/usr/bin/env bash
# Fuzzes the NFF reader for SECONDS (default 60) with libFuzzer + ASan + UBSan.
#   bash tests/fuzz/run.sh [SECONDS]
# Configures and builds the "fuzz" preset when needed (clang++), seeds
# build-fuzz/corpus from tests/data/nff/*.nff and the small SPD scenes of
# ../shared/scenes/spd (when present), runs nff_fuzzer and prints libFuzzer's
# final stats line. Exits non-zero on any crash; crash inputs land in
# build-fuzz/crashes/. Idempotent; no network.
set -euo pipefail

seconds="${1:-60}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "usage: $0 [SECONDS]  (a positive integer, default 60)" >&2
  exit 2
fi

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$root/build-fuzz"
fuzzer="$build/bin/nff_fuzzer"

cd "$root"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake --preset fuzz >/dev/null
fi
cmake --build --preset fuzz >/dev/null

# Seed corpus: copies, so libFuzzer never writes into the repository.
corpus="$build/corpus"
crashes="$build/crashes"
mkdir -p "$corpus" "$crashes"
for seed in "$root"/tests/data/nff/*.nff; do
  cp -f "$seed" "$corpus/seed-$(basename "$seed")"
done
for name in balls-s1 tetra-s1 gears-s1; do
  spd="$root/../shared/scenes/spd/$name.nff"
  if [ -f "$spd" ]; then cp -f "$spd" "$corpus/seed-spd-$name.nff"; fi
done
chmod u+w "$corpus"/seed-* 2>/dev/null || true

log="$build/fuzz-last.log"
status=0
# -print_final_stats=1 adds the stat:: lines; the last #N line is the final state.
"$fuzzer" "$corpus" \
  -dict="$here/nff.dict" \
  -max_total_time="$seconds" \
  -rss_limit_mb=2048 \
  -max_len=65536 \
  -artifact_prefix="$crashes/" \
  -print_final_stats=1 \
  >"$log" 2>&1 || status=$?

grep -E '^#[0-9]+' "$log" | tail -n 1 || true
grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' "$log" || true

if [ "$status" -ne 0 ] || grep -qE '^(==[0-9]+==ERROR|SUMMARY: )|deadly signal|runtime error' "$log"; then
  echo "nff_fuzzer: FAILED (exit $status); log: $log" >&2
  grep -E 'ERROR|runtime error|Test unit written|SUMMARY' "$log" >&2 || true
  if [ "$status" -eq 0 ]; then status=1; fi
  exit "$status"
fi
echo "nff_fuzzer: no crash in ${seconds} s; log: $log"
