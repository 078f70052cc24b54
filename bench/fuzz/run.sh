#!/usr/bin/env bash
# Runs each libFuzzer target of bench/fuzz for a given time, each with a seed corpus made from
# the project's own files, and prints executions and findings per target.
#
#   bench/fuzz/run.sh [SECONDS] [TARGET...]     (default: 60 s each, every target)
#
# FUZZ_BUILD: the fuzz build (default build-fuzz), configured and built here when missing:
#   CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCOOPMAP_FUZZ=ON -DCOOPMAP_SANITIZE=ON \
#     -DCOOPMAP_BUILD_TESTS=OFF -DCOOPMAP_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
# COOPMAP: a coopmap binary, for the seeds that are coopmap outputs (a traverse log, a
#   recording, a map); default build/apps/coopmap, else the fuzz build's.
# Corpora grow in $FUZZ_BUILD/fuzz/corpus/<target>; inputs that crash, leak or allocate
# beyond the limit go to $FUZZ_BUILD/fuzz/findings/<target>/. Exit 1 when any target found
# something.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
SECONDS_EACH="${1:-60}"
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(world robot_model carmen traverse recording ros_map)
BUILD="${FUZZ_BUILD:-$ROOT/build-fuzz}"
JOBS="${JOBS:-$(nproc)}"

if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCOOPMAP_FUZZ=ON -DCOOPMAP_SANITIZE=ON \
    -DCOOPMAP_WERROR=ON -DCOOPMAP_BUILD_TESTS=OFF -DCOOPMAP_BUILD_BENCH=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$BUILD" -j "$JOBS" --target $(printf 'fuzz_%s ' "${TARGETS[@]}") >/dev/null

COOPMAP="${COOPMAP:-$ROOT/build/apps/coopmap}"
if [ ! -x "$COOPMAP" ]; then
  cmake --build "$BUILD" -j "$JOBS" --target coopmap >/dev/null
  COOPMAP="$BUILD/apps/coopmap"
fi

WORK="$BUILD/fuzz"
SEEDS="$WORK/seeds"
rm -rf "$SEEDS" "$WORK/run"
mkdir -p "$SEEDS" "$WORK/run"

# Seeds: the project's worlds and robot files, a short run's outputs, and a small CARMEN log.
pack() {  # pack OUT NAME=FILE...: one input of several files (bench/fuzz/fuzz_input.h)
  local out="$1"
  shift
  : >"$out"
  for pair in "$@"; do
    printf '=== %s ===\n' "${pair%%=*}" >>"$out"
    cat "${pair#*=}" >>"$out"
  done
}
mkdir -p "$SEEDS/world" "$SEEDS/robot_model" "$SEEDS/carmen" "$SEEDS/traverse" \
         "$SEEDS/recording" "$SEEDS/ros_map"
cp "$ROOT"/worlds/*.yaml "$SEEDS/world/"
for family in corridor lt loop open; do
  "$COOPMAP" world generate --seed 1 --family "$family" --out "$SEEDS/world/$family.yaml" \
    >/dev/null
done
cp "$ROOT/robots/b14/b14.yaml" "$SEEDS/robot_model/"
ASAN_OPTIONS=detect_leaks=0 "$COOPMAP" run "$ROOT/worlds/lab.yaml" --duration 1 --quiet \
  --record "$WORK/run/rec" --out "$WORK/run/out" >/dev/null
for log in "$WORK"/run/out/traverse_*.traverse; do
  { printf '\0'; cat "$log"; } >"$SEEDS/traverse/$(basename "$log")"
done
rec="$WORK/run/rec"
files=("dataset.yaml=$rec/dataset.yaml")
for robot_dir in "$rec"/*/; do
  robot="$(basename "$robot_dir")"
  for f in "$robot_dir"*.yaml "$robot_dir"*.csv; do
    [ -f "$f" ] && files+=("$robot/$(basename "$f")=$f")
  done
done
pack "$SEEDS/recording/lab" "${files[@]}"
sed 's/^image: .*/image: map.pgm/' "$WORK/run/out/map_jose.yaml" >"$WORK/run/map.yaml"
pack "$SEEDS/ros_map/lab" "map.yaml=$WORK/run/map.yaml" "map.pgm=$WORK/run/out/map_jose.pgm"
{
  echo "# CARMEN Logfile"
  echo "PARAM robot_frontlaser_offset 0.0 nohost 0"
  ranges="$(printf ' 2.000%.0s' $(seq 181))"
  for k in 0 1 2 3; do
    t=$((100 + k))
    echo "ODOM 0 0 0.$k 0 0.5 0 $t.0 robot $t.0"
    echo "FLASER 181$ranges 0 0 0.$k 0 0 0.$k $t.5 robot $t.5"
    echo "RLASER 181$ranges 0 0 0.$k 0 0 0.$k $t.6 robot $t.6"
    echo "TRUEPOS 0 0 0.$k 0 0 0.$k $t.7 robot $t.7"
  done
} >"$SEEDS/carmen/room.log"

fuzz() {  # fuzz TARGET: runs it for SECONDS_EACH, its log in $WORK/TARGET.log
  local target="$1" corpus="$WORK/corpus/$1" findings="$WORK/findings/$1"
  mkdir -p "$corpus" "$findings"
  # Each input alone: no leaks checked (llvmpipe and OpenCV keep process-lifetime
  # allocations); an allocation over 1 GiB is a finding (sizes are checked before allocating).
  ASAN_OPTIONS=detect_leaks=0 "$BUILD/bench/fuzz/fuzz_$target" "$corpus" "$SEEDS/$target" \
    -max_total_time="$SECONDS_EACH" -rss_limit_mb=2048 -malloc_limit_mb=1024 -timeout=25 \
    -detect_leaks=0 -print_final_stats=1 -artifact_prefix="$findings/" >"$WORK/$target.log" 2>&1 ||
    true
}
# JOBS targets at a time.
running=0
for target in "${TARGETS[@]}"; do
  fuzz "$target" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait

found=0
printf '| target | seconds | executions | executions/s | findings |\n|---|---|---|---|---|\n'
for target in "${TARGETS[@]}"; do
  log="$WORK/$target.log"
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  n="$(find "$WORK/findings/$target" -type f | wc -l)"
  found=$((found + n))
  printf '| %s | %s | %s | %s | %s |\n' "$target" "$SECONDS_EACH" "${runs:-?}" \
    "$((${runs:-0} / (SECONDS_EACH > 0 ? SECONDS_EACH : 1)))" "$n"
  if [ "$n" -gt 0 ]; then
    grep -m1 -A12 "ERROR: \|==ERROR\|runtime error\|deadly signal\|out-of-memory" "$log" |
      sed 's/^/    /'
  fi
done
[ "$found" -eq 0 ]
