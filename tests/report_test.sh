#!/usr/bin/env bash
# Plans the demo, writes its report, and opens it in headless Chromium (report_browser_test.mjs).
# Usage: report_test.sh UAVPLAN_BINARY SOURCE_DIR NODE_MODULES SCREENSHOT
set -euo pipefail
BIN=$1
SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP" >/dev/null
"$BIN" report "$SRC/scenarios/demo.yaml" "$TMP/plan.json" -o "$TMP/report.html" >/dev/null
node "$SRC/tests/report_browser_test.mjs" "$TMP/report.html" "$3" "$4"
