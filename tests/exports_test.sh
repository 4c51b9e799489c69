#!/usr/bin/env bash
# Exports of a planned scenario, each read back by an independent reader: the .plan and WPL by
# a checker of QGroundControl's and MAVSDK's import rules, GeoJSON and KML by GDAL's ogr2ogr.
# Usage: exports_test.sh UAVPLAN_BINARY SOURCE_DIR SCENARIO [firmware]
set -euo pipefail
BIN=$1
SRC=$2
SCEN=$3
FIRMWARE=${4:-px4}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

"$BIN" plan "$SCEN" -o "$TMP" --export qgc,wpl,geojson,kml,csv --firmware "$FIRMWARE" >"$TMP/log" || {
  cat "$TMP/log"; echo "FAIL: plan did not solve $SCEN"; exit 1; }
# The ids NUL-separated: an id may hold spaces or any other character.
mapfile -d '' ids < <(node -e 'const p=require(process.argv[1]); for (const u of p.uavs) if (u.trajectory.length>=2) process.stdout.write(u.id + "\0")' "$TMP/plan.json")
obstacles=$("$BIN" info "$SCEN" | awk '$1 == "obstacles" {print $2}')
node "$SRC/tests/qgc_plan_check.mjs" "$TMP" "${ids[@]}"
node "$SRC/tests/gis_readback_check.mjs" "$TMP" "$obstacles" "${ids[@]}"
# The standalone command writes the same files as plan --export.
"$BIN" export "$SCEN" "$TMP/plan.json" --format qgc --firmware "$FIRMWARE" -o "$TMP/again" >/dev/null
for id in "${ids[@]}"; do
  stem=$(node --input-type=module -e "import {fileStem} from '$SRC/tests/file_stem.mjs'; console.log(fileStem(process.argv[1]))" "$id")
  cmp "$TMP/$stem.plan" "$TMP/again/$stem.plan"
done
echo "exports_test: ok ($SCEN)"
