#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each on its seed corpus (fuzz/corpus/TARGET, read only: new
# inputs go to BUILD/corpus/TARGET), with the contract's dictionary, one target per core at a
# time (each target is one process on one core: the same executions as one after the other, in
# less wall time). Prints each target's executions per second and corpus size; exits 1 when a
# target found a crash (kept as BUILD/crash-TARGET-*: add it to the corpus and a regression test).
# Usage: fuzz/run.sh BUILD_DIR SECONDS
set -u
BUILD=$1
SECONDS_EACH=$2
SRC=$(cd "$(dirname "$0")" && pwd)
TARGETS=(fuzz_scenario fuzz_plan fuzz_geojson fuzz_movingai fuzz_gdal)
JOBS=$(nproc 2>/dev/null || echo 1)

fuzz_one() {  # fuzz_one TARGET: runs it; its exit status in BUILD/TARGET.rc
  local t=$1 work="$BUILD/corpus/$1"
  mkdir -p "$work"
  "$BUILD/fuzz/$t" "$work" "$SRC/corpus/$t" -dict="$SRC/scenario.dict" -max_total_time="$SECONDS_EACH" \
    -max_len=65536 -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 -artifact_prefix="$BUILD/crash-$t-" \
    >"$BUILD/$t.log" 2>&1
  echo $? >"$BUILD/$t.rc"
}

running=0
for t in "${TARGETS[@]}"; do
  if [ $running -ge "$JOBS" ]; then
    wait -n
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
wait

status=0
printf '%-16s %10s %12s %10s %8s\n' target seconds execs exec/s corpus
for t in "${TARGETS[@]}"; do
  log="$BUILD/$t.log"
  rc=$(cat "$BUILD/$t.rc" 2>/dev/null || echo 1)
  execs=$(grep -m1 '^stat::number_of_executed_units' "$log" | awk '{print $2}')
  rate=$(grep -m1 '^stat::average_exec_per_sec' "$log" | awk '{print $2}')
  size=$(ls "$BUILD/corpus/$t" | wc -l)
  printf '%-16s %10s %12s %10s %8s\n' "$t" "$SECONDS_EACH" "${execs:-?}" "${rate:-?}" "$size"
  if [ "$rc" -ne 0 ]; then
    echo "$t: crash (exit $rc); the input and the report:"
    ls "$BUILD"/crash-"$t"-* 2>/dev/null
    grep -m5 -E 'ERROR|SUMMARY|escaped|not printable' "$log"
    status=1
  fi
done
exit $status
