#!/usr/bin/env bash
# What the tool writes and prints cannot be turned against its user: export file names distinct
# by construction, nothing written for an empty -o, exports all or nothing (a full disk leaves the
# folder as it was, exit 3 naming ENOSPC), a manifest cannot make an export delete other files,
# names from the scenario escaped on the terminal, in the report's data and in KML.
# Usage: output_safety_test.sh UAVPLAN_BINARY SOURCE_DIR
set -u
BIN=$1
SRC=$2
TMP=$(mktemp -d)
MNT=""
cleanup() {
  if [ -n "$MNT" ]; then umount "$MNT" 2>/dev/null; fi
  rm -rf "$TMP"
}
trap cleanup EXIT
fails=0
pass=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL $*"; fails=$((fails + 1)); }
check() { if [ "$2" = "$3" ]; then ok; else bad "$1: exit $3, expected $2"; fi; }

# Three UAVs whose ids make the same safe file name; one id carries terminal escapes.
scenario() {  # scenario FILE NAME ID3
  cat >"$1" <<EOF
version: 1
name: "$2"
origin: {lat: 47.3977, lon: 8.5456, alt: 488.0}
world:
  bounds: {min: [0, 0, 0], max: [300, 300, 60]}
  obstacles:
    - {type: box, id: "hangar\u0001", min: [140, 140, 0], max: [160, 160, 30]}
uavs:
  - {id: a_b_2, start: [10, 10, 20], goal: [290, 10, 20]}
  - {id: a_b, start: [10, 100, 20], goal: [290, 100, 20]}
  - {id: "$3", start: [10, 200, 20], goal: [290, 200, 20]}
mission: {type: independent, separation: 5}
EOF
}
sc=$TMP/s.yaml
scenario "$sc" "three" "a b"

# 1. Distinct names: three files, each written once, the renamed one saying whose it is.
"$BIN" plan "$sc" -o "$TMP/o1" --export csv,qgc >"$TMP/stdout" 2>"$TMP/stderr"; check stems.plan 0 $?
[ "$(ls "$TMP/o1" | grep -c '\.csv$')" = 3 ] || bad "stems: $(ls "$TMP/o1")"
[ "$(grep -c '^wrote' "$TMP/stdout")" = 7 ] || bad "stems: wrote lines (3 csv, 3 .plan, schedule.json): $(cat "$TMP/stdout")"
[ "$(grep '^wrote' "$TMP/stdout" | sort | uniq -d | wc -l)" = 0 ] || bad "stems: a file written twice"
grep -q "(UAV 'a b')" "$TMP/stdout" || bad "stems: the renamed file does not name its UAV"
# The file of 'a b' holds its route (y = 200), not another UAV's.
renamed=$(grep "(UAV 'a b')" "$TMP/stdout" | grep '\.csv' | sed 's/^wrote \([^ ]*\) .*/\1/')
awk -F, 'NR > 2 && ($3 < 150 || $3 > 250) { exit 1 }' "$renamed" || bad "stems: $renamed is not the route of 'a b'"
ok

# 2. An empty -o writes nothing anywhere (it used to mean the root folder).
mkdir -p "$TMP/cwd" && cd "$TMP/cwd" || exit 1
"$BIN" plan "$sc" -o "" >/dev/null 2>"$TMP/stderr"; check empty_o.plan 2 $?
"$BIN" export "$sc" "$TMP/o1/plan.json" --format csv -o "" >/dev/null 2>&1; check empty_o.export 2 $?
"$BIN" report "$sc" "$TMP/o1/plan.json" -o "" >/dev/null 2>&1; check empty_o.report 2 $?
[ -z "$(ls -A "$TMP/cwd")" ] || bad "empty -o wrote $(ls -A "$TMP/cwd")"
[ ! -e /plan.json ] || bad "empty -o: /plan.json exists"
cd "$TMP" || exit 1

# 3. A hand-written manifest cannot make the next export delete plan.json or a user's file.
echo "mine" >"$TMP/o1/notes.txt"
printf 'plan.json\nnotes.txt\tcbf29ce484222325\nplan.json\t0123456789abcdef\n' >>"$TMP/o1/.uavplan-export"
# (--end loiter: another export of the plan, so the last one's files of other formats go too)
"$BIN" export "$sc" "$TMP/o1/plan.json" --format csv --end loiter -o "$TMP/o1" >/dev/null 2>&1; check manifest.export 0 $?
[ -f "$TMP/o1/plan.json" ] && [ -f "$TMP/o1/notes.txt" ] || bad "manifest: an export deleted a file it did not write"
[ ! -e "$TMP/o1/a_b.plan" ] || bad "manifest: the last export's .plan files were not removed"

# 4. Terminal escapes in an id reach no terminal: no ESC, BEL or CR byte on stdout or stderr.
esc=$TMP/esc.yaml
scenario "$esc" "esc" 'x\e]0;pwned\a\rstatus: solved\e[2J'
"$BIN" plan "$esc" -o "$TMP/o2" --export csv >"$TMP/stdout" 2>"$TMP/stderr"; check escapes.plan 0 $?
"$BIN" info "$esc" >>"$TMP/stdout" 2>>"$TMP/stderr"
"$BIN" verify "$esc" "$TMP/o2/plan.json" >>"$TMP/stdout" 2>>"$TMP/stderr"
if LC_ALL=C grep -q $'[\x1b\x07\r]' "$TMP/stdout" "$TMP/stderr"; then bad "escapes: a control byte reached the terminal"; else ok; fi
grep -qF '\x1b' "$TMP/stdout" || bad "escapes: the id is not shown escaped"

# 5. Names in the report's data and in KML: no '<!--<script' in the data, no raw control byte.
html=$TMP/html.yaml
scenario "$html" '<!--<script>' 'u3'
"$BIN" plan "$html" -o "$TMP/o3" --export kml >/dev/null 2>&1; check html.plan 0 $?
"$BIN" report "$html" "$TMP/o3/plan.json" -o "$TMP/o3/report.html" >/dev/null 2>&1; check html.report 0 $?
if grep -q '<!--<script' "$TMP/o3/report.html"; then bad "report: the name is not escaped in the data"; else ok; fi
if LC_ALL=C grep -q $'\x01' "$TMP/o3/plan.kml"; then bad "kml: a raw control character"; else ok; fi

# 6. A full disk: the export fails with exit 3 naming ENOSPC and leaves the folder as it was.
MNT=$TMP/small
mkdir -p "$MNT"
if mount -t tmpfs -o size=160k tmpfs "$MNT" 2>/dev/null; then
  "$BIN" plan "$sc" -o "$MNT/o" --export csv >/dev/null 2>&1; check enospc.first 0 $?
  before=$(cd "$MNT/o" && ls -A | sort && cat -- * .uavplan-export | cksum)
  head -c 120000 /dev/zero >"$MNT/filler"
  "$BIN" plan "$sc" -o "$MNT/o" --export csv,qgc,geojson,kml >/dev/null 2>"$TMP/stderr"; rc=$?
  check enospc.exit 3 $rc
  grep -q ENOSPC "$TMP/stderr" || bad "enospc: the message does not name ENOSPC: $(cat "$TMP/stderr")"
  after=$(cd "$MNT/o" && ls -A | sort && cat -- * .uavplan-export | cksum)
  [ "$before" = "$after" ] || bad "enospc: the folder changed: $(ls -A "$MNT/o")"
  umount "$MNT" && MNT=""
else
  echo "note: no tmpfs mount here (not root?): the full-disk case is covered by the unit tests only"
fi

echo "$pass passed, $fails failed"
[ "$fails" = 0 ]
