#!/usr/bin/env bash
# `uavplan bench mapf` through the command line: libMultiRobotPlanning's instances solved by every
# method, written in its output format and read back by an independent checker
# (tests/mapf_check.py), the same schedules on every run; bad instance files refused with one
# line naming the file and the place, nothing written.
# Usage: mapf_test.sh UAVPLAN_BINARY SOURCE_DIR
set -u
BIN=$1
SRC=$2
DATA="$SRC/tests/data/mapf"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

"$BIN" bench mapf "$DATA" --out "$TMP/a" >"$TMP/table" 2>"$TMP/err" || fail "bench mapf: exit $?"
[ "$(grep -cE '^ +(10|50|100) +1 \| +100%' "$TMP/table")" = 3 ] || { fail "not every instance solved:"; cat "$TMP/table"; }
python3 "$SRC/tests/mapf_check.py" "$DATA" "$TMP/a" || fail "a solution file does not hold"
"$BIN" bench mapf "$DATA" --out "$TMP/b" >/dev/null 2>&1
for f in "$TMP"/a/*.yaml; do  # the same schedules (runtime aside)
  cmp -s <(grep -v runtime "$f") <(grep -v runtime "$TMP/b/$(basename "$f")") || fail "$(basename "$f") differs between runs"
done

# The checker itself rejects a schedule where two agents meet.
mkdir -p "$TMP/tampered"
python3 - "$TMP/a/map_32by32_obst204_agents10_ex0.yaml" "$TMP/tampered/map_32by32_obst204_agents10_ex0.yaml" <<'PY'
import sys, yaml
s = yaml.safe_load(open(sys.argv[1]))
names = list(s["schedule"])
a, b = s["schedule"][names[0]], s["schedule"][names[1]]
b[:] = [dict(p) for p in a]  # agent 1 shadows agent 0
yaml.safe_dump(s, open(sys.argv[2], "w"))
PY
python3 "$SRC/tests/mapf_check.py" "$DATA" "$TMP/tampered" >/dev/null && fail "the checker let a tampered schedule through"

# Every method on the 10-agent instance (CBS optimal: no sum of costs below it).
mkdir -p "$TMP/ten" && cp "$DATA/map_32by32_obst204_agents10_ex0.yaml" "$TMP/ten/"
for m in prioritized ecbs cbs auto; do
  "$BIN" bench mapf "$TMP/ten" --method $m --time-limit 20 --out "$TMP/m_$m" >"$TMP/m_$m.table" 2>&1 || fail "--method $m: exit $?"
  python3 "$SRC/tests/mapf_check.py" "$TMP/ten" "$TMP/m_$m" >/dev/null || fail "--method $m: a solution does not hold"
done
cost() { awk '/cost:/ { print $2 }' "$TMP/m_$1/map_32by32_obst204_agents10_ex0.yaml"; }
for m in prioritized ecbs auto; do
  [ "$(cost "$m")" -ge "$(cost cbs)" ] || fail "$m's sum of costs $(cost "$m") is below CBS's optimum $(cost cbs)"
done

# Bad input: exit 2, one line naming the file and the place, nothing written.
expect_bad() {  # expect_bad NAME SED_EXPRESSION PART
  rm -rf "$TMP/bad" "$TMP/bad_out" && mkdir -p "$TMP/bad"
  sed "$2" "$DATA/map_32by32_obst204_agents10_ex0.yaml" >"$TMP/bad/inst.yaml"
  "$BIN" bench mapf "$TMP/bad" --out "$TMP/bad_out" >/dev/null 2>"$TMP/stderr"
  local rc=$?
  [ $rc = 2 ] || fail "$1: exit $rc, expected 2"
  if [ "$(wc -l <"$TMP/stderr")" != 1 ] || ! grep -qF "$TMP/bad/inst.yaml" "$TMP/stderr" || ! grep -qF -- "$3" "$TMP/stderr"; then
    fail "$1: stderr is not one line naming the file and '$3':"; cat "$TMP/stderr"
  fi
  [ ! -e "$TMP/bad_out" ] || fail "$1: wrote output for bad input"
}
expect_bad outside 's/start: \[4, 21\]/start: [4, 40]/' "agents[0].start: [4, 40] is outside the map (32 x 32)"
expect_bad obstacle 's/start: \[4, 21\]/start: [30, 3]/' "agents[0].start: on an obstacle"
expect_bad syntax 's/^agents:/agents: [/' "YAML syntax error"
cp -r "$TMP/ten" "$TMP/ten_copy"
"$BIN" bench mapf "$TMP/ten_copy" --out "$TMP/ten_copy/." >/dev/null 2>"$TMP/stderr"; rc=$?
[ $rc = 2 ] && grep -q "instance folder itself" "$TMP/stderr" && cmp -s "$TMP/ten/"*.yaml "$TMP/ten_copy/"*.yaml ||
  fail "--out the instance folder: exit $rc, or an instance was replaced"
"$BIN" bench mapf "$TMP/ten" --method astar >/dev/null 2>&1; rc=$?
[ $rc = 2 ] || fail "unknown method: exit $rc, expected 2"
"$BIN" bench mapf "$TMP/nowhere" >/dev/null 2>"$TMP/stderr"; rc=$?
[ $rc = 2 ] && grep -qF "$TMP/nowhere" "$TMP/stderr" || fail "a missing folder: exit $rc"

[ $fails = 0 ] && echo "mapf: all passed"
exit $((fails > 0))
