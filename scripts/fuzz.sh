#!/usr/bin/env bash
# Fuzzes the loader with libFuzzer (docs/robustness.md, "Fuzzing the loader"): builds the fuzz
# targets with clang, ASan and UBSan (preset `fuzz`, build/fuzz), seeds each target's corpus from
# the scenes and the test data, and runs each target for SECONDS, one after another.
#   bash scripts/fuzz.sh SECONDS [scene] [obj] [stl] [msh]     (default: all four)
# The corpus grows in build/fuzz/work/corpus/KIND across runs; an input that crashes, hangs
# (> 20 s), takes over 4 GB, trips a sanitizer or is refused without naming the file is saved in
# build/fuzz/work/findings/KIND/ (replay: build/fuzz/fuzz/fuzz_KIND FILE). Fixed findings go to
# tests/fuzz/data/KIND/, which the test suite replays.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: bash scripts/fuzz.sh SECONDS [scene] [obj] [stl] [msh]}
shift
kinds=("$@")
[ ${#kinds[@]} -gt 0 ] || kinds=(scene obj stl msh)

bash scripts/setup.sh clang libclang-rt-14-dev
cmake --preset fuzz >/dev/null
targets=()
for kind in "${kinds[@]}"; do targets+=(--target "fuzz_$kind"); done
cmake --build --preset fuzz -j "$(nproc)" "${targets[@]}"

work=build/fuzz/work
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:suppressions=$PWD/scripts/sanitize/asan.supp"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export STIFFSOFT_MESH_CACHE="$PWD/$work/mesh_cache"   # soft bodies the scene fuzzer meshes

# seed_files KIND: the seed inputs of a kind (scenes under 64 KB, the scene and mesh test data)
seed_files() {
  case "$1" in
    scene) find scenes tests/scene/data tests/apps/data examples -name '*.json' -size -64k ;;
    *) find tests examples -name "*.$1" ;;
  esac
}

status=0
for kind in "${kinds[@]}"; do
  corpus=$work/corpus/$kind
  findings=$work/findings/$kind
  mkdir -p "$corpus" "$findings"
  seed_files "$kind" | while read -r f; do cp -n "$f" "$corpus/seed_$(basename "$f")"; done
  # -close_fd_mask=1: the loader's log lines (stdout) would drown libFuzzer's (stderr)
  fuzz_args=(-max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -print_final_stats=1 -close_fd_mask=1
             -artifact_prefix="$findings/")
  if [ "$kind" = scene ]; then
    # every key the scenes and test data use, as a libFuzzer dictionary
    grep -ohE '"[a-z_0-9]+"' scenes/*.json tests/scene/data/*/*.json | sort -u |
      sed 's/"/\\"/g; s/^/"/; s/$/"/' > "$work/scene.dict"
    fuzz_args+=(-dict="$work/scene.dict")
  fi
  echo "fuzz: $kind for ${seconds} s (log: $work/$kind.log)"
  if ! build/fuzz/fuzz/fuzz_"$kind" "${fuzz_args[@]}" "$corpus" > "$work/$kind.log" 2>&1; then
    status=1
  fi
  grep -E '^(stat::number_of_executed_units|stat::peak_rss_mb)|^==[0-9]+==ERROR|^SUMMARY|Test unit written' \
    "$work/$kind.log" | sed "s/^/  $kind: /" || true
done
echo "fuzz: findings so far: $(find "$work/findings" -type f | wc -l) file(s) in $work/findings"
exit $status
