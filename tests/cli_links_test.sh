#!/usr/bin/env bash
# The shipped program links neither OMPL nor MPI (they are its companions': uavplan-bench,
# uavplan-mpi); alone, without them beside it, `bench` and `batch --mpi` say which program to
# build, exit 2.
# Usage: cli_links_test.sh UAVPLAN_BINARY
set -u
BIN=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fails=0
if ldd "$BIN" | grep -iE 'ompl|mpi'; then echo "FAIL links OMPL or MPI"; fails=$((fails + 1)); fi
cp "$BIN" "$TMP/uavplan"
"$TMP/uavplan" bench world >/dev/null 2>"$TMP/err"
rc=$?
if [ "$rc" != 2 ] || ! grep -q "uavplan-bench" "$TMP/err"; then echo "FAIL bench alone: exit $rc: $(cat "$TMP/err")"; fails=$((fails + 1)); fi
printf 'runs: [{scenario: x.yaml}]\n' >"$TMP/sweep.yaml"
"$TMP/uavplan" batch "$TMP/sweep.yaml" -o "$TMP/out" --mpi >/dev/null 2>"$TMP/err"
rc=$?
if [ "$rc" != 2 ] || ! grep -q "uavplan-mpi" "$TMP/err"; then echo "FAIL batch --mpi alone: exit $rc: $(cat "$TMP/err")"; fails=$((fails + 1)); fi
echo "$((3 - fails)) passed, $fails failed"
[ "$fails" = 0 ]
