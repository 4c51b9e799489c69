#!/usr/bin/env bash
# uavplan batch through the command line: the same bytes whatever --jobs, --isolate or MPI;
# a batch killed (SIGKILL) or interrupted (SIGINT) part way resumes with no run lost or done
# twice; bad sweeps are exit 2, one line naming the key, nothing written.
set -u
UAVPLAN=$1
ROOT=$(cd "$2" && pwd)
MODE=${3:-all}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cat > "$T/sweep.yaml" <<YAML
name: cli-test
scenarios: [$ROOT/scenarios/demo.yaml, "$ROOT/scenarios/p4_table*.yaml"]
planners: [astar, {name: rrt, params: {goal_bias: [0.05, 0.2]}}]
seeds: 3
YAML

runs() { tail -n +2 "$1/results.csv" | wc -l; }
journal_runs() { cat "$1"/journal/*.jsonl | grep -c '"run"'; }

if [ "$MODE" = mpi ]; then
  "$UAVPLAN" batch "$T/sweep.yaml" -o "$T/one" --jobs 1 >/dev/null || fail "batch --jobs 1"
  mpirun --allow-run-as-root --oversubscribe -np 2 "$UAVPLAN" batch "$T/sweep.yaml" -o "$T/mpi" --jobs 1 --mpi \
    >"$T/mpi.out" 2>&1 || { cat "$T/mpi.out"; fail "mpirun -np 2 batch --mpi"; }
  cmp "$T/one/results.csv" "$T/mpi/results.csv" || fail "MPI results differ from one process"
  diff -r "$T/one/runs" "$T/mpi/runs" >/dev/null || fail "MPI plans differ from one process"
  ls "$T/mpi/journal/rank-1.jsonl" >/dev/null || fail "rank 1 ran nothing"
  grep -q "2 ranks" "$T/mpi.out" || fail "the summary does not count the ranks"
  echo "batch mpi: ok"
  exit 0
fi

# --dry-run: the count, nothing written.
out=$("$UAVPLAN" batch "$T/sweep.yaml" -o "$T/dry" --dry-run) || fail "dry run"
[ "$out" = "18 runs: 2 scenarios x 3 planner settings x 1 parameter settings x 3 seeds" ] || fail "dry run said: $out"
[ ! -e "$T/dry" ] || fail "dry run wrote $T/dry"

# A dry run of a sweep of 1e8 runs counts them without listing them (that took 37 GB).
printf 'scenarios: [%s]\nplanners: [astar]\nseeds: 10000\nparams: {"uavs[0].speed": [%s], "uavs[1].speed": [%s]}\n' \
  "$ROOT/scenarios/demo.yaml" "$(seq -s, 1 100)" "$(seq -s, 1 100)" > "$T/huge.yaml"
out=$(timeout 60 "$UAVPLAN" batch "$T/huge.yaml" -o "$T/huge" --dry-run) || fail "dry run of 1e8 runs"
[ "${out%% *}" = 100000000 ] || fail "dry run of 1e8 runs said: $out"

# A glob beside the sweep does not take the sweep file for a scenario.
mkdir -p "$T/g" && cp "$ROOT/scenarios/demo.yaml" "$T/g/" && printf 'scenarios: ["*.yaml"]\n' > "$T/g/sweep.yaml"
out=$("$UAVPLAN" batch "$T/g/sweep.yaml" -o "$T/g/out" --dry-run) || fail "glob beside the sweep"
[ "$out" = "1 runs: 1 scenarios x 1 planner settings x 1 parameter settings x 1 seeds" ] || fail "glob beside the sweep: $out"

# The same bytes whatever the number of jobs, and isolated in processes.
"$UAVPLAN" batch "$T/sweep.yaml" -o "$T/j1" --jobs 1 >"$T/j1.out" || fail "batch --jobs 1"
"$UAVPLAN" batch "$T/sweep.yaml" -o "$T/j2" --jobs 2 >/dev/null || fail "batch --jobs 2"
"$UAVPLAN" batch "$T/sweep.yaml" -o "$T/iso" --jobs 2 --isolate >/dev/null || fail "batch --isolate"
[ "$(runs "$T/j1")" = 18 ] || fail "results.csv has $(runs "$T/j1") rows, not 18"
cmp "$T/j1/results.csv" "$T/j2/results.csv" || fail "results.csv differs between --jobs 1 and 2"
cmp "$T/j1/results.csv" "$T/iso/results.csv" || fail "results.csv differs with --isolate"
diff -r "$T/j1/runs" "$T/j2/runs" >/dev/null || fail "plans differ between --jobs 1 and 2"
[ "$(ls "$T/j1/runs" | wc -l)" = 18 ] || fail "not one plan per run"
# Every solved row's plan verifies through the CLI, and its length is the plan's.
row=$(grep ',solved,1,' "$T/j1/results.csv" | head -1)
sc=$(echo "$row" | cut -d, -f2); plan=$(echo "$row" | cut -d, -f15)
"$UAVPLAN" verify "$sc" "$T/j1/$plan" >/dev/null || fail "a solved run's plan does not verify"
grep -q "^astar  *-  *demo.yaml  *3  *3  *3 " "$T/j1.out" || { cat "$T/j1.out"; fail "summary row for astar on demo"; }
# One row per parameter setting (the two goal biases were one row, their runs merged).
for b in 0.05 0.2; do
  grep -q "^rrt  *goal_bias=$b  *demo.yaml  *3 " "$T/j1.out" || { cat "$T/j1.out"; fail "no summary row for rrt goal_bias=$b"; }
done
head -1 "$T/j1/timings.csv" | grep -q "^run,plan_ms,wall_ms$" || fail "timings.csv header"

# --isolate: a run whose process dies (here: SIGKILL, which no sanitizer runtime intercepts) is a
# row, the batch goes on.
cat > "$T/crash.yaml" <<YAML
scenarios: [$ROOT/scenarios/demo.yaml]
planners: [astar]
seeds: 3
YAML
"$UAVPLAN" batch "$T/crash.yaml" -o "$T/crash" --jobs 1 --isolate >/dev/null 2>&1 &
pid=$!
killed=0
for _ in $(seq 1 600); do
  child=$(pgrep -P $pid -f "plan $ROOT/scenarios/demo.yaml" | head -1)
  if [ -n "$child" ]; then kill -KILL "$child"; killed=1; break; fi
  sleep 0.01
done
wait $pid || fail "the isolated batch did not finish after a run's process died"
[ $killed = 1 ] || fail "no run's process was seen to kill"
[ "$(runs "$T/crash")" = 3 ] || fail "the isolated batch has $(runs "$T/crash") rows, not 3"
grep -q ',crashed,0,.*,none,.*signal 9' "$T/crash/results.csv" || { cat "$T/crash/results.csv"; fail "the dead run is not a crashed row"; }
[ "$(grep -c ',solved,1,' "$T/crash/results.csv")" = 2 ] || fail "the other runs were not solved"

# Bad sweeps: exit 2, one line naming the sweep's key, nothing written.
bad() {  # name, yaml, expected text
  printf '%s\n' "$2" > "$T/bad.yaml"
  "$UAVPLAN" batch "$T/bad.yaml" -o "$T/bad_out" >"$T/bad.stdout" 2>"$T/bad.stderr"
  rc=$?
  [ $rc = 2 ] || fail "$1: exit $rc, not 2"
  [ "$(wc -l < "$T/bad.stderr")" = 1 ] || { cat "$T/bad.stderr"; fail "$1: not one line"; }
  grep -q -- "$3" "$T/bad.stderr" || { cat "$T/bad.stderr"; fail "$1: does not say '$3'"; }
  [ ! -e "$T/bad_out" ] || fail "$1: wrote the output folder"
}
bad "unknown planner" "scenarios: [$ROOT/scenarios/demo.yaml]
planners: [astar, nosuch]" "planners\[1\]: unknown planner 'nosuch'"
bad "unknown parameter" "scenarios: [$ROOT/scenarios/demo.yaml]
planners: [astar]
params: {no_such_param: [1, 2]}" "params.no_such_param"
bad "bad parameter value" "scenarios: [$ROOT/scenarios/demo.yaml]
planners: [{name: rrt, params: {goal_bias: [0.1, banana]}}]" "planners\[0\].params.goal_bias"
bad "missing scenario" "scenarios: [$ROOT/scenarios/demo.yaml, nowhere.yaml]" "scenarios\[1\]: no such scenario file"
bad "glob matching nothing" "scenarios: [\"$T/*.nothing\"]" "scenarios\[0\]: .* matches no file"
bad "empty scenarios" "scenarios: []" "scenarios"
bad "empty seeds" "scenarios: [$ROOT/scenarios/demo.yaml]
seeds: []" "seeds"
bad "unknown key" "scenarios: [$ROOT/scenarios/demo.yaml]
planer: [astar]" "planer: unknown key"
bad "scenario key" "scenarios: [$ROOT/scenarios/demo.yaml]
params: {\"uavs[0].speed\": [-3]}" "params.uavs\[0\].speed"

# A batch in a folder that holds one already is refused without --resume.
"$UAVPLAN" batch "$T/sweep.yaml" -o "$T/j1" >/dev/null 2>"$T/again.err"; rc=$?
[ $rc = 2 ] && grep -q -- "--resume" "$T/again.err" || fail "a second batch into the same folder was not refused"

# Killed (SIGKILL) part way, then resumed: no run lost, none done twice, the same results.
# Twelve runs of the demo: enough for the kill to land part way in release (about 0.5 s a run).
L=12
cat > "$T/long.yaml" <<YAML
scenarios: [$ROOT/scenarios/demo.yaml]
planners: [astar]
seeds: $L
YAML
"$UAVPLAN" batch "$T/long.yaml" -o "$T/full" --jobs 2 >/dev/null || fail "full batch"
"$UAVPLAN" batch "$T/long.yaml" -o "$T/killed" --jobs 2 >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 400); do
  [ -d "$T/killed/journal" ] && [ "$(cat "$T/killed"/journal/*.jsonl 2>/dev/null | wc -l)" -ge 3 ] && break
  sleep 0.05
done
kill -9 $pid; wait $pid 2>/dev/null
done_before=$(cat "$T/killed"/journal/*.jsonl | wc -l)
[ "$done_before" -ge 3 ] && [ "$done_before" -lt $L ] || fail "the kill came at $done_before of $L runs"
# A line cut short by the kill is dropped and its run done again.
printf '{"run": %d, "scenario": "cut sh' $((L - 1)) >> "$T/killed/journal/rank-0.jsonl"
"$UAVPLAN" batch "$T/long.yaml" -o "$T/killed" --jobs 2 --resume >"$T/resume.out" || fail "resume"
grep -q "$L of $L runs done ($((L - done_before)) this time" "$T/resume.out" || { cat "$T/resume.out"; fail "resume did not do just the rest"; }
[ "$(journal_runs "$T/killed")" = $L ] || fail "the journal holds $(journal_runs "$T/killed") runs, not $L"
[ "$(grep -o '"run": *[0-9]*' "$T"/killed/journal/*.jsonl | sort -u | wc -l)" = $L ] || fail "a run was done twice"
cmp "$T/full/results.csv" "$T/killed/results.csv" || fail "resumed results differ from an uninterrupted batch"

# Ctrl-C: the runs under way finish, exit 130, --resume does the rest.
"$UAVPLAN" batch "$T/long.yaml" -o "$T/int" --jobs 1 >/dev/null 2>"$T/int.err" &
pid=$!
for _ in $(seq 1 400); do
  [ "$(cat "$T/int"/journal/*.jsonl 2>/dev/null | wc -l)" -ge 2 ] && break
  sleep 0.05
done
kill -INT $pid; wait $pid; rc=$?
[ $rc = 130 ] || fail "interrupted batch: exit $rc, not 130"
grep -q -- "--resume continues" "$T/int.err" || fail "interrupted batch does not say how to go on"
n=$(runs "$T/int")
[ "$n" -lt $L ] && [ "$n" = "$(journal_runs "$T/int")" ] || fail "interrupted batch: $n rows"
"$UAVPLAN" batch "$T/long.yaml" -o "$T/int" --resume >/dev/null || fail "resume after Ctrl-C"
cmp "$T/full/results.csv" "$T/int/results.csv" || fail "results after Ctrl-C and resume differ"
# A resume with another sweep is refused.
sed -i "s/seeds: $L/seeds: [5, 6]/" "$T/long.yaml"
"$UAVPLAN" batch "$T/long.yaml" -o "$T/int" --resume >/dev/null 2>"$T/other.err"; rc=$?
[ $rc = 2 ] && grep -q "another sweep" "$T/other.err" || fail "resume with another sweep was not refused"
# A resume after a scenario file was edited is refused: two versions never mix in one results.csv.
cp "$ROOT/scenarios/demo.yaml" "$T/edit.yaml"
printf 'scenarios: [%s]\nplanners: [astar]\nseeds: 4\n' "$T/edit.yaml" > "$T/edit_sweep.yaml"
"$UAVPLAN" batch "$T/edit_sweep.yaml" -o "$T/edit" --jobs 1 >/dev/null || fail "batch before the edit"
sed -i 's/^name: demo/name: demo2/' "$T/edit.yaml"
"$UAVPLAN" batch "$T/edit_sweep.yaml" -o "$T/edit" --resume >/dev/null 2>"$T/edit.err"; rc=$?
[ $rc = 2 ] && grep -q "changed" "$T/edit.err" || { cat "$T/edit.err"; fail "resume after a scenario edit was not refused"; }

# A tiny time limit is passed to isolated runs exactly (1e-7, not "0.000000"): the same rows.
printf 'scenarios: [%s]\nplanners: [astar]\nseeds: 2\ntime_limit_s: 1e-7\n' "$ROOT/scenarios/demo.yaml" > "$T/tiny.yaml"
"$UAVPLAN" batch "$T/tiny.yaml" -o "$T/tiny_in" --jobs 1 >/dev/null 2>&1
"$UAVPLAN" batch "$T/tiny.yaml" -o "$T/tiny_iso" --jobs 1 --isolate >/dev/null 2>&1
cmp "$T/tiny_in/results.csv" "$T/tiny_iso/results.csv" || fail "a 1e-7 s limit gives other rows with --isolate"
grep -q ',timeout,.*,stopped,' "$T/tiny_in/results.csv" || fail "a run stopped by its limit is not a timeout row"

# Ctrl-C reaches isolated runs (their own process group), and a killed batch leaves no orphans.
printf 'scenarios: [%s]\nplanners: [{name: cellular_aco, params: {iterations: [100000]}}]\nseeds: 2\n' \
  "$ROOT/scenarios/p2_city.yaml" > "$T/slow.yaml"
slow_batch() {  # slow_batch OUT: starts the batch in the background; sets pid and child (its run)
  "$UAVPLAN" batch "$T/slow.yaml" -o "$1" --jobs 1 --isolate >/dev/null 2>&1 &
  pid=$!
  child=""
  for _ in $(seq 1 500); do
    child=$(pgrep -P $pid -f "p2_city.yaml" | head -1); [ -n "$child" ] && break; sleep 0.01
  done
  [ -n "$child" ] || fail "no isolated run was seen"
}
gone() {  # gone PID: true once the process has ended (within 5 s)
  for _ in $(seq 1 100); do kill -0 "$1" 2>/dev/null || return 0; sleep 0.05; done
  return 1
}
slow_batch "$T/slow_int"
sleep 0.5
kill -INT $pid
gone "$child" || fail "an isolated run went on after Ctrl-C"
wait $pid; rc=$?
[ $rc = 130 ] || fail "interrupted isolated batch: exit $rc, not 130"
slow_batch "$T/slow_kill"
kill -KILL $pid; wait $pid 2>/dev/null
gone "$child" || { kill -KILL "$child"; fail "a killed batch left its run running"; }
echo "batch: ok"
