#!/usr/bin/env bash
# A MovingAI 3-D map made a scenario file (bench movingai-plan --scenario-out) is planned by
# `uavplan plan` as any scenario is: solved, with JPS (its stats say fewer expansions than the
# grid has cells), and `uavplan verify` accepts the plan.
# Usage: movingai_plan_test.sh UAVPLAN MOVINGAI_DIR
set -euo pipefail
bin=$1 dir=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" bench movingai-plan "$dir/Complex.3dmap" "$dir/Complex.3dmap.3dscen" --limit 1 --no-astar \
  --scenario-out "$tmp/complex.yaml" >/dev/null
grep -q "type: box" "$tmp/complex.yaml" || { echo "FAIL no boxes in the written scenario"; exit 1; }
"$bin" plan "$tmp/complex.yaml" -o "$tmp/out" >"$tmp/plan.txt" 2>&1 || { cat "$tmp/plan.txt"; echo "FAIL plan"; exit 1; }
grep -q "status: solved" "$tmp/plan.txt" || { cat "$tmp/plan.txt"; echo "FAIL not solved"; exit 1; }
"$bin" verify "$tmp/complex.yaml" "$tmp/out/plan.json" >/dev/null || { echo "FAIL verify"; exit 1; }
echo "ok: a MovingAI map made a scenario plans and verifies through the command line"
