#!/usr/bin/env bash
# Mutation campaign: for each single-line mutant of a list (tests/mutants.txt
# describes the format), applies it to a scratch copy of the tree, rebuilds
# incrementally, runs CTest until the first failure, restores the file, and
# prints a table killed / survived / did not compile / does not apply with
# the kill rate over live mutants (killed + survived). Not run by CI.
# Rules: the worktree is never modified (only the copy is); a mutant that no
# longer applies is reported, never skipped silently; the unmutated copy must
# build and pass first, or no verdict would mean anything.
#
# Usage: tests/mutants.sh [--list FILE] [--scratch DIR] [--only ID[,ID...]]
#                         [--target T]... [--ctest-exclude REGEX] [--jobs N] [--timeout S] [--check]
#                         [--gtest-only [FILTER]]
#   --check          only report whether each mutant applies (no build, no tests)
#   --gtest-only     run only the quiver_tests binary, in one process, stopping
#                    at the first failure (--gtest_fail_fast), with an optional
#                    gtest filter: much faster than CTest's process per test,
#                    but it leaves out the CMake-script, Python and MPI tests
#                    (say so when reporting a campaign run this way)
#   --list           mutant list (default tests/mutants.txt)
#   --scratch        where the copy and its build live (default build-mutants
#                    in the worktree: under the ccache base_dir, so the first
#                    build of the copy is mostly cache hits)
#   --only           run only these mutant ids
#   --target         build only these targets (default: all)
#   --ctest-exclude  a CTest -E regex of tests not run per mutant (say so when
#                    reporting a campaign run this way)
#   --jobs           parallel build and test jobs (default 2)
#   --timeout        per-test timeout in seconds (default 600); a mutant that
#                    hangs a test is killed by the timeout
# Results: <scratch>/results.tsv (id, verdict, first failing test) and a log
# per mutant in <scratch>/logs/.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
list=$repo/tests/mutants.txt
scratch=$repo/build-mutants
only=""
targets=()
ctest_exclude=""
jobs=2
timeout=600
check=0
gtest_only=0
gtest_filter="*"
while (($#)); do
  case $1 in
    --list) list=$(realpath "$2"); shift 2 ;;
    --scratch) scratch=$(realpath -m "$2"); shift 2 ;;
    --only) only=",$2,"; shift 2 ;;
    --target) targets+=("$2"); shift 2 ;;
    --ctest-exclude) ctest_exclude=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --check) check=1; shift ;;
    --gtest-only)
      gtest_only=1
      if [[ $# -gt 1 && $2 != --* ]]; then gtest_filter=$2; shift; fi
      shift ;;
    *) echo "mutants.sh: unknown argument '$1' (see the usage at the top of $0)" >&2; exit 2 ;;
  esac
done
[[ -f $list ]] || { echo "mutants.sh: no mutant list at $list" >&2; exit 2; }

tree=$scratch/tree
logs=$scratch/logs
mkdir -p "$tree" "$logs"

# The worktree's files as they are now (committed or not, ignored ones left
# out), with their times kept so an unchanged file is not rebuilt.
echo "copying $repo to $tree"
(cd "$repo" && git ls-files -z -co --exclude-standard | tar --null -T - -cf -) | tar -xf - -C "$tree"
# Files mutated since the copy's build last ran unmutated were restored
# after it: the copy above gives them back their old times, so make would
# keep a mutant's objects. Touch them so that they are rebuilt; the record
# is cleared once the unmutated copy has built again.
mutated=$scratch/mutated-files
if [[ -f $mutated ]]; then
  while IFS= read -r path; do [[ -f $tree/$path ]] && touch "$tree/$path"; done <"$mutated"
fi

build_args=(--build "$tree/build" -j "$jobs")
for t in "${targets[@]}"; do build_args+=(--target "$t"); done
ctest_args=(--test-dir "$tree/build" --stop-on-failure -j "$jobs" --timeout "$timeout" --output-on-failure)
[[ -n $ctest_exclude ]] && ctest_args+=(-E "$ctest_exclude")

build() { cmake "${build_args[@]}"; }
run_tests() {
  if ((gtest_only)); then
    timeout "$timeout" "$tree/build/bin/quiver_tests" --gtest_fail_fast --gtest_brief=1 "--gtest_filter=$gtest_filter"
  else
    ctest "${ctest_args[@]}"
  fi
}

# The copy's tests read ../shared beside the worktree, not beside the copy
# (without it the tests that need it skip, and mutants they would kill survive).
shared=${QUIVER_SHARED_DIR:-$(cd "$repo/.." && pwd)/shared}
if ((check == 0)); then
  if [[ ! -f $tree/build/CMakeCache.txt ]]; then
    (cd "$tree" && CMAKE_CXX_COMPILER_LAUNCHER=ccache CMAKE_C_COMPILER_LAUNCHER=ccache cmake --preset release) \
      >"$logs/configure.log" 2>&1 || { echo "configure failed: $logs/configure.log" >&2; exit 1; }
  fi
  cmake -DQUIVER_SHARED_DIR="$shared" "$tree/build" >>"$logs/configure.log" 2>&1 ||
    { echo "configure failed: $logs/configure.log" >&2; exit 1; }
fi
if ((check == 0)); then
echo "building and testing the unmutated copy"
if ! build >"$logs/baseline.log" 2>&1; then echo "the unmutated copy does not build: $logs/baseline.log" >&2; exit 1; fi
rm -f "$mutated"
start=$SECONDS
if ! run_tests >>"$logs/baseline.log" 2>&1; then
  echo "the unmutated copy fails its tests, so no mutant can be judged: $logs/baseline.log" >&2
  exit 1
fi
echo "baseline: suite passes in $((SECONDS - start)) s"
fi

# Applies mutant (file, text, replacement, nth) to the copy; prints why not on failure.
apply_mutant() {
  python3 - "$tree/$1" "$2" "$3" "$4" <<'EOF'
import sys
path, text, replacement, nth = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
try:
    lines = open(path, encoding="utf-8").read().split("\n")
except OSError as e:
    sys.exit(f"cannot read the file: {e.strerror}")
matches = [i for i, line in enumerate(lines) if text in line]
if not matches:
    sys.exit("the text is on no line")
if nth:
    k = int(nth)
    if len(matches) < k:
        sys.exit(f"the text is on {len(matches)} lines, fewer than {k}")
    at = matches[k - 1]
elif len(matches) > 1:
    sys.exit(f"the text is on {len(matches)} lines (lines {', '.join(str(m + 1) for m in matches)}); give which")
else:
    at = matches[0]
lines[at] = lines[at].replace(text, replacement, 1)
open(path, "w", encoding="utf-8").write("\n".join(lines))
print(at + 1)
EOF
}

results=$scratch/results.tsv
: >"$results"
killed=0 survived=0 broken=0 stale=0
# The list is read on fd 3: a build or test that reads stdin cannot eat a line.
while IFS= read -r -u 3 raw; do
  [[ -z ${raw//[[:space:]]/} || $raw =~ ^[[:space:]]*# ]] && continue
  # Split on " @@ " into id, file, text, replacement and an optional nth.
  mapfile -t f < <(python3 -c 'import sys; [print(p.strip()) for p in sys.argv[1].split(" @@ ")]' "$raw")
  id=${f[0]} file=${f[1]:-} text=${f[2]:-} replacement=${f[3]:-} nth=${f[4]:-}
  [[ -n $only && $only != *",$id,"* ]] && continue
  log=$logs/$id.log
  if [[ -z $file || -z $text || ${#f[@]} -lt 4 ]]; then
    printf '%s\tdoes-not-apply\tmalformed line\n' "$id" | tee -a "$results"; stale=$((stale + 1)); continue
  fi
  cp -p "$tree/$file" "$scratch/original" 2>/dev/null || true
  ((check == 0)) && printf '%s\n' "$file" >>"$mutated"
  if ! where=$(apply_mutant "$file" "$text" "$replacement" "$nth" 2>&1); then
    printf '%s\tdoes-not-apply\t%s: %s\n' "$id" "$file" "$where" | tee -a "$results"; stale=$((stale + 1)); continue
  fi
  echo "== $id: $file:$where" >"$log"
  if ((check == 1)); then
    verdict=applies detail="$file:$where"
  elif ! build >>"$log" 2>&1; then
    verdict=did-not-compile detail="$file:$where"; broken=$((broken + 1))
  elif run_tests >>"$log" 2>&1; then
    verdict=survived detail="$file:$where"; survived=$((survived + 1))
  else
    verdict=killed
    detail=$(grep -m1 -E '^[[:space:]]*[0-9]+ - .*\((Failed|Timeout|SEGFAULT|Subprocess aborted|Exception|Child aborted|Not Run)' "$log" |
             sed -E 's/^[[:space:]]*[0-9]+ - //' || true)
    [[ -z $detail ]] && detail=$(grep -m1 -E '\*\*\*(Failed|Timeout|Exception)' "$log" || true)
    [[ -z $detail ]] && detail=$(grep -m1 -E '^\[  FAILED  \] [^ ]+' "$log" | sed -E 's/^\[  FAILED  \] ([^ ]+).*/\1/' || true)
    [[ -z $detail ]] && detail="stopped: $(tail -n1 "$log")"
    killed=$((killed + 1))
  fi
  # Restored as a new file (a later time than its objects), so the next build recompiles it.
  cp "$scratch/original" "$tree/$file"
  printf '%s\t%s\t%s\n' "$id" "$verdict" "$detail" | tee -a "$results"
done 3<"$list"

echo
printf '%-34s %-16s %s\n' mutant verdict detail
while IFS=$'\t' read -r id verdict detail; do printf '%-34s %-16s %s\n' "$id" "$verdict" "$detail"; done <"$results"
live=$((killed + survived))
echo
echo "killed $killed, survived $survived, did not compile $broken, does not apply $stale"
if ((live > 0)); then
  echo "kill rate over live mutants: $killed / $live = $(awk -v k=$killed -v l=$live 'BEGIN { printf "%.1f%%", 100 * k / l }')"
fi
