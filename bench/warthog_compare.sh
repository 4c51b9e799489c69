#!/usr/bin/env bash
# Per-query medians of our grid searches beside warthog's JPS variants (ShortestPathLab's
# warthog-jps, built by the user: it is not a Debian package), on one MovingAI map, run one
# after the other on this machine. Each side times its own search loop per query; ours runs
# without the textbook A* beside it (--no-reference), as warthog does.
# Usage: bench/warthog_compare.sh WARTHOG_JPS_BINARY OUR_MOVINGAI_BINARY MAP SCEN
set -euo pipefail
if [ $# -ne 4 ]; then
  echo "usage: $0 WARTHOG_JPS_BINARY OUR_MOVINGAI_BINARY MAP SCEN" >&2
  exit 2
fi
warthog=$1 ours=$2 map=$3 scen=$4
median() { sort -g | awk '{v[NR] = $1} END {if (NR) printf "%.4f", v[int((NR + 1) / 2)]; else printf "-"}'; }
mean() { awk '{s += $1} END {if (NR) printf "%.1f", s / NR; else printf "-"}'; }
printf '%-24s %10s %8s %14s\n' "search" "median_ms" "problems" "mean_expanded"
for alg in jps jps2 jps+ jps2+; do
  # warthog prints one row per problem: id alg expanded generated reopen surplus heapops nanos ...
  rows=$("$warthog" --alg "$alg" --scen "$scen" --map "$map" 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 8')
  printf '%-24s %10s %8d %14s\n' "warthog $alg" "$(awk '{printf "%.6f\n", $8 / 1e6}' <<< "$rows" | median)" \
    "$(wc -l <<< "$rows")" "$(awk '{print $3}' <<< "$rows" | mean)"
done
for alg in jps jps+; do
  out=$("$ours" "$map" "$scen" "$alg" 0 --no-reference)
  row=$(awk '$1 == "all" {print $5, $2}' <<< "$out")
  expanded=$(sed -n 's/.*; \([0-9.]*\) expansions per problem.*/\1/p' <<< "$out")
  printf '%-24s %10s %8s %14s\n' "uavplan $alg" ${row} "$expanded"
  grep -h "jump table" <<< "$out" | sed 's/^/    /' || true
done
