#!/usr/bin/env bash
# Per-query medians of our grid searches beside warthog's JPS variants (ShortestPathLab's
# warthog-jps, built by the user: it is not a Debian package), on one MovingAI map, run one
# after the other on this machine. Each side times its own search loop per query; ours runs
# without the textbook A* beside it (--no-reference), as warthog does.
# A shared machine's load moves a median of microsecond queries by 10-20 % from one run to the
# next, so the two sides take turns for ROUNDS rounds (default 5) and each row is the median of
# its rounds' medians, with the fastest and slowest round beside it.
# Usage: [ROUNDS=n] bench/warthog_compare.sh WARTHOG_JPS_BINARY OUR_MOVINGAI_BINARY MAP SCEN
set -euo pipefail
if [ $# -ne 4 ]; then
  echo "usage: [ROUNDS=n] $0 WARTHOG_JPS_BINARY OUR_MOVINGAI_BINARY MAP SCEN" >&2
  exit 2
fi
warthog=$1 ours=$2 map=$3 scen=$4 rounds=${ROUNDS:-5}
median() { sort -g | awk '{v[NR] = $1} END {if (NR) printf "%.4f", v[int((NR + 1) / 2)]; else printf "-"}'; }
mean() { awk '{s += $1} END {if (NR) printf "%.1f", s / NR; else printf "-"}'; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sides=("warthog jps" "warthog jps2" "warthog jps+" "warthog jps2+" "uavplan jps" "uavplan jps+")
for ((r = 0; r < rounds; ++r)); do
  for side in "${sides[@]}"; do
    who=${side%% *} alg=${side#* } file="$tmp/${who}_${alg}"
    if [ "$who" = warthog ]; then
      # One row per problem: id alg expanded generated reopen surplus heapops nanos ...
      rows=$("$warthog" --alg "$alg" --scen "$scen" --map "$map" 2>/dev/null | awk '$1 ~ /^[0-9]+$/ && NF >= 8')
      { awk '{printf "%.6f\n", $8 / 1e6}' <<< "$rows" | median; echo; } >> "$file.median"
      wc -l <<< "$rows" > "$file.problems"
      awk '{print $3}' <<< "$rows" | mean > "$file.expanded"
    else
      out=$("$ours" "$map" "$scen" "$alg" 0 --no-reference)
      awk '$1 == "all" {print $5}' <<< "$out" >> "$file.median"
      awk '$1 == "all" {print $2}' <<< "$out" > "$file.problems"
      sed -n 's/.*; \([0-9.]*\) expansions per problem.*/\1/p' <<< "$out" > "$file.expanded"
      grep -h "jump table" <<< "$out" | sed 's/^/    /' > "$file.note" || true
    fi
  done
done
printf '%-24s %10s %10s %10s %8s %14s   (%d rounds)\n' "search" "median_ms" "fastest" "slowest" "problems" \
  "mean_expanded" "$rounds"
for side in "${sides[@]}"; do
  who=${side%% *} alg=${side#* } file="$tmp/${who}_${alg}"
  sort -g "$file.median" > "$file.sorted"
  printf '%-24s %10s %10s %10s %8s %14s\n' "$side" "$(median < "$file.sorted")" "$(head -1 "$file.sorted")" \
    "$(tail -1 "$file.sorted")" "$(cat "$file.problems")" "$(cat "$file.expanded")"
  if [ -s "$file.note" ]; then cat "$file.note"; fi
done
