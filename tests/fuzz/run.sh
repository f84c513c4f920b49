#!/usr/bin/env bash
# Fuzzes the scene readers with libFuzzer + ASan + UBSan, each for SECONDS
# (default 60), one after another.
#   bash tests/fuzz/run.sh [SECONDS] [FUZZER...]    FUZZER: nff, toml, obj, mesh, ply, stl, gltf, glb, view
#                                                   (default: nff, toml, obj, mesh)
# ply, stl, gltf and glb run mesh_fuzzer on one format alone (QUIVER_FUZZ_MESH_KIND);
# view runs view_request_fuzzer (quiver view's request parameters).
# Configures the "fuzz" preset when needed (clang++) and builds the fuzzers
# in build-fuzz/, seeds build-fuzz/corpus-FUZZER from the repository's test
# data (and the small SPD scenes of ../shared for nff, when present), runs
# each fuzzer and prints libFuzzer's final stats line. Exits non-zero when
# any fuzzer crashed; crash inputs land in build-fuzz/crashes/. Idempotent;
# no network.
set -euo pipefail

usage() {
  echo "usage: $0 [SECONDS] [nff|toml|obj|mesh|ply|stl|gltf|glb|view ...]  (SECONDS a positive integer, default 60; default: nff toml obj mesh)" >&2
  exit 2
}

seconds=60
if [ $# -gt 0 ] && [[ "$1" =~ ^[0-9]+$ ]]; then
  seconds="$1"
  shift
fi
if [ "$seconds" -lt 1 ]; then usage; fi
fuzzers=("$@")
if [ ${#fuzzers[@]} -eq 0 ]; then fuzzers=(nff toml obj mesh); fi
for name in "${fuzzers[@]}"; do
  case "$name" in nff | toml | obj | mesh | ply | stl | gltf | glb | view) ;; *) usage ;; esac
done

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$root/build-fuzz"

cd "$root"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake --preset fuzz >/dev/null
fi
targets=()
# The target each name runs: ply, stl, gltf and glb are mesh_fuzzer with one reader forced.
binary_of() {
  case "$1" in ply | stl | gltf | glb) echo mesh ;; view) echo view_request ;; *) echo "$1" ;; esac
}
for name in "${fuzzers[@]}"; do targets+=("$(binary_of "$name")_fuzzer"); done
cmake --build "$build" -j2 --target "${targets[@]}" >/dev/null

crashes="$build/crashes"
mkdir -p "$crashes"

# Seed corpus: copies, so libFuzzer never writes into the repository.
seed_corpus() {
  local name="$1" corpus="$2" seed
  case "$name" in
    nff)
      for seed in "$root"/tests/data/nff/*.nff; do cp -f "$seed" "$corpus/seed-$(basename "$seed")"; done
      for seed in balls-s1 tetra-s1 gears-s1; do
        local spd="$root/../shared/scenes/spd/$seed.nff"
        if [ -f "$spd" ]; then cp -f "$spd" "$corpus/seed-spd-$seed.nff"; fi
      done
      ;;
    toml)
      for seed in "$root"/tests/data/toml/*.toml "$root"/io/examples/*.toml; do
        cp -f "$seed" "$corpus/seed-$(basename "$seed")"
      done
      ;;
    obj)
      # An OBJ that names an MTL library beside it gets it appended after a
      # NUL byte (the fuzzer's input format).
      for seed in "$root"/tests/data/obj/*.obj "$root"/io/examples/*.obj; do
        local out="$corpus/seed-$(basename "$seed")" library
        cp -f "$seed" "$out"
        library="$(sed -n 's/^mtllib[ \t]\{1,\}//p' "$seed" | head -n 1)"
        if [ -n "$library" ] && [ -f "$(dirname "$seed")/$library" ]; then
          printf '\0' >>"$out"
          cat "$(dirname "$seed")/$library" >>"$out"
        fi
      done
      ;;
    mesh)
      # The check's selector byte (0 PLY, 1 STL, 2 glTF; mesh_fuzzer.cpp), then the file.
      for seed in "$root"/tests/data/mesh/*; do
        local out="$corpus/seed-$(basename "$seed")"
        case "$seed" in
          *.ply) printf '\0' >"$out" ;;
          *.stl) printf '\1' >"$out" ;;
          *.gltf) printf '\2' >"$out" ;;
          *) continue ;;
        esac
        cat "$seed" >>"$out"
      done
      /usr/bin/python3 "$here/hostile_meshes.py" seeds "$corpus" gltf
      /usr/bin/python3 "$here/hostile_meshes.py" seeds "$corpus" glb
      ;;
    ply | stl)
      # The test data of that format behind its selector byte (0 PLY, 1 STL).
      local selector='\0'
      if [ "$name" = stl ]; then selector='\1'; fi
      for seed in "$root"/tests/data/mesh/*."$name"; do
        { printf "$selector"; cat "$seed"; } >"$corpus/seed-$(basename "$seed")"
      done
      ;;
    gltf | glb)
      # Structure-aware seeds (nested and doubled nodes, sparse accessors,
      # offsets near 2^64, extensions, data URIs) behind the selector byte.
      /usr/bin/python3 "$here/hostile_meshes.py" seeds "$corpus" "$name"
      if [ "$name" = gltf ]; then
        for seed in "$root"/tests/data/mesh/*.gltf; do
          { printf '\2'; cat "$seed"; } >"$corpus/seed-$(basename "$seed")"
        done
      fi
      ;;
    view)
      # The page's requests: a view of every stage, and one at the size limits.
      printf 'from=0,2.2,7&at=0,0.9,0&up=0,1,0&fov=45&width=640&height=360&aa=grid:2&max_depth=5&stage=final' \
        >"$corpus/seed-view"
      printf 'from=1e30,-2,3&at=0,0,0&up=0,0,1&fov=179.9&width=65536&height=4096&aa=refine:0.01:16&stage=coarse' \
        >"$corpus/seed-limits"
      ;;
  esac
  chmod u+w "$corpus"/seed-* 2>/dev/null || true
}

failed=0
for name in "${fuzzers[@]}"; do
  corpus="$build/corpus-$name"
  mkdir -p "$corpus"
  seed_corpus "$name" "$corpus"
  log="$build/fuzz-$name-last.log"
  status=0
  binary="$(binary_of "$name")"
  kind=""
  case "$name" in ply) kind=0 ;; stl) kind=1 ;; gltf) kind=2 ;; glb) kind=3 ;; esac
  # -print_final_stats=1 adds the stat:: lines; the last #N line is the final state.
  QUIVER_FUZZ_MESH_KIND="$kind" "$build/bin/${binary}_fuzzer" "$corpus" \
    -dict="$here/$binary.dict" \
    -max_total_time="$seconds" \
    -rss_limit_mb=2048 \
    -max_len=65536 \
    -artifact_prefix="$crashes/$name-" \
    -print_final_stats=1 \
    >"$log" 2>&1 || status=$?

  echo "== ${name}_fuzzer"
  grep -E '^#[0-9]+' "$log" | tail -n 1 || true
  grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' "$log" || true
  if [ "$status" -ne 0 ] || grep -qE '^(==[0-9]+==ERROR|SUMMARY: )|deadly signal|runtime error' "$log"; then
    echo "${name}_fuzzer: FAILED (exit $status); log: $log" >&2
    grep -E 'ERROR|runtime error|Test unit written|SUMMARY' "$log" >&2 || true
    failed=1
  else
    echo "${name}_fuzzer: no crash in ${seconds} s; log: $log"
  fi
done
exit "$failed"
