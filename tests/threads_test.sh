#!/usr/bin/env bash
# --threads changes nothing in a plan: every bundled scenario gives the same bytes with 1, 2 and
# 8 threads. Usage: threads_test.sh UAVPLAN_BINARY SOURCE_DIR
set -u
BIN=$1
SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fails=0
for sc in "$SRC"/scenarios/*.yaml; do
  n=$(basename "$sc" .yaml)
  for t in 1 2 8; do "$BIN" plan "$sc" -o "$TMP/$n.$t" --threads $t >/dev/null 2>&1; done
  if ! cmp -s "$TMP/$n.1/plan.json" "$TMP/$n.2/plan.json" || ! cmp -s "$TMP/$n.1/plan.json" "$TMP/$n.8/plan.json"; then
    echo "FAIL $n: plan.json differs between thread counts"
    fails=$((fails + 1))
  fi
done
echo "$fails scenarios differ"
[ "$fails" = 0 ]
