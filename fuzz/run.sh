#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each on its seed corpus (fuzz/corpus/TARGET, read only: new
# inputs go to BUILD/corpus/TARGET), with the contract's dictionary. Prints each target's
# executions per second and corpus size; exits 1 when a target found a crash (kept as
# BUILD/crash-TARGET-*: add it to the corpus and a regression test).
# Usage: fuzz/run.sh BUILD_DIR SECONDS
set -u
BUILD=$1
SECONDS_EACH=$2
SRC=$(cd "$(dirname "$0")" && pwd)
status=0
printf '%-16s %10s %12s %10s %8s\n' target seconds execs exec/s corpus
for t in fuzz_scenario fuzz_plan fuzz_geojson fuzz_movingai; do
  work="$BUILD/corpus/$t"
  mkdir -p "$work"
  log="$BUILD/$t.log"
  "$BUILD/fuzz/$t" "$work" "$SRC/corpus/$t" -dict="$SRC/scenario.dict" -max_total_time="$SECONDS_EACH" \
    -max_len=65536 -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 -artifact_prefix="$BUILD/crash-$t-" \
    >"$log" 2>&1
  rc=$?
  execs=$(grep -m1 '^stat::number_of_executed_units' "$log" | awk '{print $2}')
  rate=$(grep -m1 '^stat::average_exec_per_sec' "$log" | awk '{print $2}')
  size=$(ls "$work" | wc -l)
  printf '%-16s %10s %12s %10s %8s\n' "$t" "$SECONDS_EACH" "${execs:-?}" "${rate:-?}" "$size"
  if [ $rc -ne 0 ]; then
    echo "$t: crash (exit $rc); the input and the report:"
    ls "$BUILD"/crash-"$t"-* 2>/dev/null
    grep -m5 -E 'ERROR|SUMMARY|escaped|spans lines' "$log"
    status=1
  fi
done
exit $status
