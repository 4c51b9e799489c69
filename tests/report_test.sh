#!/usr/bin/env bash
# Plans the demo (terrain, buildings, a radar), P1's moving-obstacle scenario, P5's phased
# mission and a route through via points (nyc_block), writes their reports, and opens each in headless Chromium (report_browser_test.mjs).
# Usage: report_test.sh UAVPLAN_BINARY SOURCE_DIR NODE_MODULES SCREENSHOT
set -euo pipefail
BIN=$1
SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
for sc in demo p1_moving p5_mission nyc_block; do
  "$BIN" plan "$SRC/scenarios/$sc.yaml" -o "$TMP/$sc" >/dev/null
  "$BIN" report "$SRC/scenarios/$sc.yaml" "$TMP/$sc/plan.json" -o "$TMP/$sc/report.html" >/dev/null
done
node "$SRC/tests/report_browser_test.mjs" "$TMP/demo/report.html" "$3" "$4"
node "$SRC/tests/report_browser_test.mjs" "$TMP/p1_moving/report.html" "$3" "${4%.png}_p1_moving.png"
node "$SRC/tests/report_browser_test.mjs" "$TMP/p5_mission/report.html" "$3" "${4%.png}_p5_mission.png"
node "$SRC/tests/report_browser_test.mjs" "$TMP/nyc_block/report.html" "$3" "${4%.png}_nyc_block.png"
