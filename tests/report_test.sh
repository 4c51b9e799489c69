#!/usr/bin/env bash
# Plans the demo (terrain, buildings, a radar), P1's moving-obstacle scenario, P5's phased
# mission, a route through via points (nyc_block) and zones from airspace files (a GeoJSON no-fly
# zone, a QGC fence), writes their reports, and opens each in headless Chromium (report_browser_test.mjs).
# The demo's report draws a flight beside the plan (report --flown): its routes moved 3 m east.
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
python3 - "$TMP/demo/plan.json" "$TMP/demo/flown.json" <<'PY'
import json, sys
plan = json.load(open(sys.argv[1]))
for u in plan['uavs']:
    u['trajectory'] = [[r[0], r[1] + 3.0, r[2], r[3]] for r in u['trajectory']]
json.dump(plan, open(sys.argv[2], 'w'))
PY
"$BIN" plan "$SRC/tests/data/airspace/air.yaml" -o "$TMP/air" >/dev/null
"$BIN" report "$SRC/tests/data/airspace/air.yaml" "$TMP/air/plan.json" -o "$TMP/air/report.html" >/dev/null
"$BIN" report "$SRC/scenarios/demo.yaml" "$TMP/demo/plan.json" --flown "$TMP/demo/flown.json" -o "$TMP/demo/report.html" >/dev/null
FLOWN_TRACKS=3 node "$SRC/tests/report_browser_test.mjs" "$TMP/demo/report.html" "$3" "$4"
node "$SRC/tests/report_browser_test.mjs" "$TMP/p1_moving/report.html" "$3" "${4%.png}_p1_moving.png"
node "$SRC/tests/report_browser_test.mjs" "$TMP/p5_mission/report.html" "$3" "${4%.png}_p5_mission.png"
node "$SRC/tests/report_browser_test.mjs" "$TMP/nyc_block/report.html" "$3" "${4%.png}_nyc_block.png"
EXPECT_ZONES=1 node "$SRC/tests/report_browser_test.mjs" "$TMP/air/report.html" "$3" "${4%.png}_air.png"
