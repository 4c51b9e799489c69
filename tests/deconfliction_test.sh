#!/usr/bin/env bash
# Space-time deconfliction through the command line: six UAVs swapping across a circle, which
# departure delays cannot all place. Delays alone fail with a message naming the option; the
# default (auto) and every space-time method solve all six, also round moving obstacles; the
# verifier holds each plan, the same bytes come out twice and on one thread, the exports read
# back; a bad option value is one line, exit 2.
# Usage: deconfliction_test.sh UAVPLAN_BINARY SOURCE_DIR
set -u
BIN=$1
SRC=$2
SCEN="$SRC/tests/data/deconfliction/swap6.yaml"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

"$BIN" plan "$SCEN" -o "$TMP/delays" --set deconfliction=delays >"$TMP/log" 2>&1
grep -q "failed" "$TMP/log" || fail "delays: every UAV placed (the scenario no longer needs space and time)"
grep -q -- "--set deconfliction=space_time" "$TMP/delays/plan.json" || fail "delays: the conflict message does not name the option"

for how in "" "--set deconfliction=space_time --set space_time_method=prioritized" \
  "--set deconfliction=space_time --set space_time_method=ecbs" "--set deconfliction=space_time --set space_time_method=cbs"; do
  name=$(echo "x$how" | tr -c 'a-z\n' '_')
  # shellcheck disable=SC2086
  "$BIN" plan "$SCEN" -o "$TMP/$name" $how >"$TMP/log" 2>&1 || { fail "plan $how: exit $?"; cat "$TMP/log"; continue; }
  grep -q "status: solved" "$TMP/log" || { fail "plan $how: not solved"; cat "$TMP/log"; }
  grep -q "space-time deconfliction" "$TMP/$name/plan.json" || fail "plan $how: not planned in space and time"
  "$BIN" verify "$SCEN" "$TMP/$name/plan.json" >"$TMP/v" 2>&1 || { fail "verify $how"; cat "$TMP/v"; }
done

"$BIN" plan "$SCEN" -o "$TMP/again" >/dev/null 2>&1
cmp -s "$TMP/x/plan.json" "$TMP/again/plan.json" || fail "two runs wrote different plans"
"$BIN" plan "$SCEN" -o "$TMP/threads" --threads 1 >/dev/null 2>&1
cmp -s "$TMP/x/plan.json" "$TMP/threads/plan.json" || fail "one thread wrote a different plan"

# Moving obstacles known in advance are kept off in space and time too.
MOVING="$SRC/tests/data/deconfliction/swap6_moving.yaml"
"$BIN" plan "$MOVING" -o "$TMP/moving" --set deconfliction=space_time >"$TMP/log" 2>&1 || { fail "moving: exit $?"; cat "$TMP/log"; }
grep -q "status: solved" "$TMP/log" || { fail "moving: not solved"; cat "$TMP/log"; }
"$BIN" verify "$MOVING" "$TMP/moving/plan.json" >"$TMP/v" 2>&1 || { fail "moving: verify"; cat "$TMP/v"; }

bash "$SRC/tests/exports_test.sh" "$BIN" "$SRC" "$SCEN" >"$TMP/exports" 2>&1 || { fail "exports"; cat "$TMP/exports"; }

"$BIN" plan "$SCEN" -o "$TMP/bad" --set deconfliction=sideways >"$TMP/out" 2>"$TMP/err"
rc=$?
[ "$rc" = 2 ] || fail "bad deconfliction: exit $rc, expected 2"
if [ "$(wc -l <"$TMP/err")" != 1 ] || ! grep -q "deconfliction" "$TMP/err"; then
  fail "bad deconfliction: message"
  cat "$TMP/err"
fi
[ ! -e "$TMP/bad/plan.json" ] || fail "bad deconfliction: wrote a plan"

[ "$fails" = 0 ] && echo "deconfliction_test: ok"
exit $((fails > 0))
