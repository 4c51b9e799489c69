#!/usr/bin/env bash
# Golden and bad-input tests of the command line: exit codes, one-line errors naming the file,
# no partial output, byte-identical plans for the same seed.
# Usage: cli_test.sh UAVPLAN_BINARY SOURCE_DIR
set -u
BIN=$1
SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fails=0
pass=0

check() {  # check NAME EXPECTED_EXIT ACTUAL_EXIT
  if [ "$2" = "$3" ]; then pass=$((pass + 1)); else echo "FAIL $1: exit $3, expected $2"; fails=$((fails + 1)); fi
}
expect_bad() {  # expect_bad NAME FILE [PART]: exit 2, one stderr line naming the file (and PART)
  local name=$1 file=$2 part=${3:-}
  rm -rf "$TMP/out"
  "$BIN" plan "$file" -o "$TMP/out" >"$TMP/stdout" 2>"$TMP/stderr"
  check "$name" 2 $?
  if [ "$(wc -l <"$TMP/stderr")" != 1 ] || ! grep -qF "$file" "$TMP/stderr" || ! grep -qF -- "$part" "$TMP/stderr"; then
    echo "FAIL $name: stderr is not one line naming $file${part:+ and '$part'}:"; cat "$TMP/stderr"; fails=$((fails + 1))
  fi
  if [ -e "$TMP/out" ]; then echo "FAIL $name: wrote output for bad input"; fails=$((fails + 1)); fi
}

# The demo plans, verifies, and is byte-identical across runs. The second run has a huge time
# limit, which is no limit (the clock used to overflow into the past): the same bytes.
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/a" >"$TMP/a.stdout" 2>/dev/null; check demo.plan 0 $?
"$BIN" verify "$SRC/scenarios/demo.yaml" "$TMP/a/plan.json" >/dev/null 2>&1; check demo.verify 0 $?
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/b" --time-limit 9.3e9 >/dev/null 2>&1; check time_limit.huge 0 $?
cmp -s "$TMP/a/plan.json" "$TMP/b/plan.json"; check demo.deterministic 0 $?
"$BIN" info "$SRC/scenarios/demo.yaml" >/dev/null 2>&1; check demo.info 0 $?
# The mission types as declared: docs/formats.md's tables are info's own output.
"$BIN" info --missions --markdown >"$TMP/missions.md"; check info.missions 0 $?
sed -n '/<!-- mission-types: begin/,/<!-- mission-types: end/p' "$SRC/docs/formats.md" | sed '1d;$d' >"$TMP/missions.doc"
cmp -s "$TMP/missions.md" "$TMP/missions.doc" && pass=$((pass + 1)) ||
  { echo "FAIL docs/formats.md's mission tables differ from uavplan info --missions --markdown"; fails=$((fails + 1)); }
# The contract's opening example is YAML with the scenario's keys, each UAV key one the reader
# knows (a formatter once ran it together into one line).
sed 's/radius: 0.5, speed: 5/radius: 0.5, zzz: 1, speed: 5/' "$SRC/scenarios/demo.yaml" >"$TMP/zzz.yaml"
/usr/bin/python3 - "$SRC/docs/formats.md" "$BIN" "$TMP/zzz.yaml" <<'PY' && pass=$((pass + 1)) || { echo "FAIL docs.example"; fails=$((fails + 1)); }
import re, subprocess, sys, yaml
text = open(sys.argv[1]).read()
assert text.startswith("# File formats (public contract, version 1)\n"), text[:60]
block = re.search(r"## Scenario \(YAML[^\n]*\n```yaml\n(.*?)\n```", text, re.S).group(1)
doc = yaml.safe_load(block)
assert list(doc) == ["version", "name", "seed", "origin", "world", "uavs", "mission", "planner"], list(doc)
uav = doc["uavs"][0]
assert {"id", "start", "goal", "radius", "speed", "max_turn_deg", "home", "model"} <= set(uav), sorted(uav)
# every key the example lists is one the reader knows: its list for an unknown key
r = subprocess.run([sys.argv[2], "info", sys.argv[3]], capture_output=True, text=True)
known = re.search(r"expected one of: ([^)]*)\)", r.stderr).group(1).replace(" or ", ", ").split(", ")
assert set(uav) <= set(known), (set(uav) - set(known), r.stderr)
PY
"$BIN" info --missions | grep -q "^rendezvous: P4's simultaneous arrival" && pass=$((pass + 1)) ||
  { echo "FAIL info --missions lists no rendezvous"; fails=$((fails + 1)); }
# The planners' parameters as declared: docs/planners.md's tables are info's own output.
"$BIN" info --planners --markdown >"$TMP/planners.md"; check info.planners 0 $?
sed -n '/<!-- planner-params: begin/,/<!-- planner-params: end/p' "$SRC/docs/planners.md" | sed '1d;$d' >"$TMP/planners.doc"
cmp -s "$TMP/planners.md" "$TMP/planners.doc" && pass=$((pass + 1)) ||
  { echo "FAIL docs/planners.md's parameter tables differ from uavplan info --planners --markdown"; fails=$((fails + 1)); }
"$BIN" info >/dev/null 2>&1; check info.nothing 2 $?
"$BIN" info --missions --planners >/dev/null 2>&1; check info.two 2 $?
# A route whose via point has an entry heading: pso_mpc plans it by default, info lists it alone,
# and a planner that would not fly in along the heading is bad input.
cat >"$TMP/entered.yaml" <<'EOF'
version: 1
name: entered
world: {bounds: {min: [0, 0, 0], max: [2000, 2000, 200]}}
uavs: [{id: u1, start: [100, 100, 50], goal: [1900, 1900, 50], radius: 1, speed: 10}]
mission: {type: route, waypoints: [{position: [1000, 600, 60], entry_heading_deg: 90}]}
EOF
"$BIN" info "$TMP/entered.yaml" | grep -q "^planners for this mission: pso_mpc$" && pass=$((pass + 1)) ||
  { echo "FAIL entered.info: $("$BIN" info "$TMP/entered.yaml" | tail -1)"; fails=$((fails + 1)); }
"$BIN" plan "$TMP/entered.yaml" -o "$TMP/entered" >/dev/null 2>&1; check entered.plan 0 $?
printf 'planner: {algorithm: astar}\n' | cat "$TMP/entered.yaml" - >"$TMP/entered_astar.yaml"
expect_bad entered.astar "$TMP/entered_astar.yaml" "does not fly into a via point along its entry_heading_deg"
"$BIN" --help >/dev/null 2>&1; check help 0 $?
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/c" --set nonsense=1 >/dev/null 2>"$TMP/stderr"; check unknown.param 2 $?
grep -q "planner.params.nonsense" "$TMP/stderr" || { echo "FAIL unknown.param message"; fails=$((fails + 1)); }
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/c" --algorithm nope >/dev/null 2>&1; check unknown.algorithm 2 $?
# Limits on the command line: a seed or size that is not what it says is refused, not saturated
# or wrapped.
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/c" --seed 1e23 >/dev/null 2>&1; check seed.exponent 2 $?
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/c" --seed 18446744073709551616 >/dev/null 2>&1; check seed.overflow 2 $?
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/c" --max-memory -1 >/dev/null 2>&1; check max_memory.negative 2 $?
"$BIN" plan "$SRC/scenarios/p4_table3.yaml" -o "$TMP/c" --set max_expansions=1.5 >/dev/null 2>&1; check count.fraction 2 $?
"$BIN" plan "$SRC/scenarios/p4_table3.yaml" -o "$TMP/c" --set max_expansions=1e6 >/dev/null 2>&1; check count.exponent 0 $?
# A plan whose rows start before 0 s (once exported as a speed of 0) is bad input.
mkdir -p "$TMP/neg"
python3 -c 'import json, sys; p = json.load(open(sys.argv[1])); p["uavs"][0]["trajectory"][0][0] = -1e300; json.dump(p, open(sys.argv[2], "w"))' \
  "$TMP/a/plan.json" "$TMP/neg/bad.json"
"$BIN" verify "$SRC/scenarios/demo.yaml" "$TMP/neg/bad.json" >/dev/null 2>"$TMP/stderr"; check plan.negative_time 2 $?
grep -q "from 0 to 1e9" "$TMP/stderr" || { echo "FAIL plan.negative_time message: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
# --timing: per-UAV times only where a UAV was planned on its own (not 0.0 for each of a group).
"$BIN" plan "$SRC/scenarios/p3_group9.yaml" -o "$TMP/timing" --timing >/dev/null 2>&1
if grep -q '\.plan_ms": 0\.0' "$TMP/timing/plan.json"; then echo "FAIL timing: 0.0 per UAV of a group"; fails=$((fails + 1)); else pass=$((pass + 1)); fi
# The table's gap_m is the body's least gap to an obstacle (the centre's distance less the radius,
# as metrics.min_gap_m), not the centre's distance (clear_m was, unsaid).
python3 - "$SRC/scenarios/demo.yaml" "$TMP/a/plan.json" "$TMP/a.stdout" <<'PY' && pass=$((pass + 1)) || fails=$((fails + 1))
import json, sys, yaml
sc, plan, rows = yaml.safe_load(open(sys.argv[1])), json.load(open(sys.argv[2])), open(sys.argv[3]).read().split("\n")
head = rows[0].split()
for u in plan["uavs"]:
    radius = next(x.get("radius", 0.5) for x in sc["uavs"] if x["id"] == u["id"])
    row = next(r.split() for r in rows if r.split()[:1] == [u["id"]])
    want = u["metrics"]["min_clearance_m"] - radius
    if head[-1] != "gap_m" or abs(float(row[-1]) - want) > 1e-3 or abs(u["metrics"]["min_gap_m"] - want) > 1e-9:
        sys.exit(f"FAIL table.gap: {u['id']}: {head[-1]} {row[-1]}, centre {u['metrics']['min_clearance_m']} less radius {radius}")
PY
# A wall across the whole world: astar proves the sides apart on its first grid and says so,
# naming the wall (it used to halve its cells for seconds, then advise a smaller cell_m).
cat >"$TMP/walled.yaml" <<'YAML'
version: 1
name: walled
world:
  bounds: {min: [0, 0, 0], max: [600, 600, 120]}
  obstacles: [{type: box, id: wall, min: [300, 0, 0], max: [301, 600, 120]}]
uavs: [{id: u1, start: [20, 20, 30], goal: [580, 580, 40], radius: 0.5, speed: 5}]
mission: {type: independent}
planner: {algorithm: astar}
YAML
"$BIN" plan "$TMP/walled.yaml" -o "$TMP/walled" >"$TMP/stdout" 2>&1; check walled_off.exit 1 $?
grep -q "no way joins its ends at any cell size.*obstacle wall" "$TMP/stdout" && pass=$((pass + 1)) ||
  { echo "FAIL walled_off.message: $(cat "$TMP/stdout")"; fails=$((fails + 1)); }
# From the ground without min_agl: the flight keeps PX4's take-off height, 2.5 m, above the ground
# (it cruised with its body 5 cm over it), and info says so; min_agl: 0 written flies lower.
cat >"$TMP/delivery.yaml" <<'YAML'
version: 1
name: delivery
world:
  bounds: {min: [0, 0, 0], max: [400, 300, 60]}
  obstacles: [{type: box, id: shed, min: [150, 100, 0], max: [200, 160, 12]}]
uavs:
  - {id: d1, start: [20, 20, 0], goal: [380, 280, 0], radius: 0.5, speed: 6}
  - {id: d2, start: [20, 280, 0], goal: [380, 20, 0], radius: 0.5, speed: 6}
mission: {type: independent, separation: 3}
planner: {algorithm: astar}
YAML
low_agl() { python3 -c 'import json, sys; print(min(u["metrics"]["min_agl_m"] for u in json.load(open(sys.argv[1]))["uavs"]))' "$1"; }
"$BIN" plan "$TMP/delivery.yaml" -o "$TMP/delivery" >/dev/null 2>&1; check default_agl.plan 0 $?
"$BIN" plan "$TMP/delivery.yaml" -o "$TMP/delivery0" --set 'uavs[0].min_agl=0' --set 'uavs[1].min_agl=0' >/dev/null 2>&1
python3 -c 'import sys; sys.exit(not (float(sys.argv[1]) >= 3.0 - 1e-9 and float(sys.argv[2]) < 1.0))' \
  "$(low_agl "$TMP/delivery/plan.json")" "$(low_agl "$TMP/delivery0/plan.json")" && pass=$((pass + 1)) ||
  { echo "FAIL default_agl.height: $(low_agl "$TMP/delivery/plan.json") m, $(low_agl "$TMP/delivery0/plan.json") m with min_agl 0"; fails=$((fails + 1)); }
"$BIN" info "$TMP/delivery.yaml" | grep -q "^min_agl   2.5 m above the ground" && pass=$((pass + 1)) ||
  { echo "FAIL default_agl.info"; fails=$((fails + 1)); }
# One UAV is "1 UAV" (the report said "1 UAVs").
"$BIN" plan "$SRC/scenarios/nyc_block.yaml" -o "$TMP/one" >/dev/null 2>&1
"$BIN" report "$SRC/scenarios/nyc_block.yaml" "$TMP/one/plan.json" -o "$TMP/one/r.html" | grep -q "(1 UAV, plan holds)" &&
  pass=$((pass + 1)) || { echo "FAIL report.one_uav"; fails=$((fails + 1)); }
# max_agl (terrain following): a band 20-45 m over hills, planned and verified with astar; over
# a flat floor, a ceiling; a band without room for the body, or a start above it, is bad input;
# the cell planners, whose map holds columns, say that the band's top is what they cannot fly under.
cat >"$TMP/band.yaml" <<'YAML'
version: 1
name: band
world:
  bounds: {min: [0, 0, 0], max: [600, 400, 150]}
  obstacles: [{type: box, id: barn, min: [250, 150, 0], max: [320, 230, 40]}]
  terrain: {type: grid, origin: [0, 0], cell: 100, heights: [[0, 5, 15, 25, 15, 5], [0, 10, 20, 30, 20, 10], [0, 10, 20, 30, 20, 10], [0, 5, 15, 25, 15, 5]]}
uavs:
  - {id: s1, start: [20, 50, 30], goal: [580, 350, 40], max_turn_deg: 60, max_climb_deg: 30, min_agl: 20, max_agl: 45}
  - {id: s2, start: [20, 350, 30], goal: [580, 50, 40], max_turn_deg: 60, max_climb_deg: 30, min_agl: 20, max_agl: 45}
mission: {type: independent, separation: 10}
planner: {algorithm: astar}
YAML
"$BIN" plan "$TMP/band.yaml" -o "$TMP/band" >/dev/null 2>&1; check max_agl.plan 0 $?
"$BIN" verify "$TMP/band.yaml" "$TMP/band/plan.json" >/dev/null 2>&1; check max_agl.verify 0 $?
"$BIN" info "$TMP/band.yaml" | grep -q "min_agl 20 m, max_agl 45 m" && pass=$((pass + 1)) ||
  { echo "FAIL max_agl.info"; fails=$((fails + 1)); }
python3 - "$TMP/band/plan.json" <<'PY' && pass=$((pass + 1)) || fails=$((fails + 1))
import json, sys
p = json.load(open(sys.argv[1]))
# the band follows the hill: over its crest (30 m) min_agl takes it above 45 m: some row higher than the floor's 45 m
if not max(r[3] for u in p["uavs"] for r in u["trajectory"]) > 45:
    sys.exit("FAIL max_agl.follows: the flight never rises over the hills")
PY
sed 's/max_agl: 45}/max_agl: 45}/; s/\[20, 50, 30\]/[20, 50, 50]/' "$TMP/band.yaml" >"$TMP/band_high.yaml"
expect_bad max_agl.start_above "$TMP/band_high.yaml" "uavs[0].start"
sed 's/min_agl: 20, max_agl: 45}/min_agl: 20, max_agl: 20.5}/' "$TMP/band.yaml" >"$TMP/band_thin.yaml"
expect_bad max_agl.no_room "$TMP/band_thin.yaml" "uavs[0].max_agl"
"$BIN" plan "$TMP/band.yaml" -o "$TMP/band_cells" --algorithm cell_astar >"$TMP/stdout" 2>&1
grep -q "models columns, and obstacle above max_agl" "$TMP/stdout" && pass=$((pass + 1)) ||
  { echo "FAIL max_agl.cell_map: $(grep '^s1:' "$TMP/stdout")"; fails=$((fails + 1)); }
# Airspace from files (world.airspace): a GeoJSON no-fly zone and a QGC fence planned round and
# verified; a flight straight through the zone is a violation naming it; a fence that crosses
# itself, a KML file and a scenario without origin are bad input.
AIR="$SRC/tests/data/airspace"
"$BIN" plan "$AIR/air.yaml" -o "$TMP/air" >/dev/null 2>&1; check airspace.plan 0 $?
"$BIN" verify "$AIR/air.yaml" "$TMP/air/plan.json" >/dev/null 2>&1; check airspace.verify 0 $?
"$BIN" info "$AIR/air.yaml" | grep -q "^obstacles 6  cylinder 1  prism 5" && pass=$((pass + 1)) ||
  { echo "FAIL airspace.info: $("$BIN" info "$AIR/air.yaml" | grep obstacles)"; fails=$((fails + 1)); }
python3 - "$TMP/air/plan.json" "$TMP/air/straight.json" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
p["uavs"][1]["trajectory"] = [[0, 300, 20, 40], [70, 300, 580, 60]]  # through the hospital zone
json.dump(p, open(sys.argv[2], "w"))
PY
"$BIN" verify "$AIR/air.yaml" "$TMP/air/straight.json" >"$TMP/stdout" 2>&1; check airspace.violated 1 $?
grep -q "obstacle zones.geojson zone 0" "$TMP/stdout" && pass=$((pass + 1)) ||
  { echo "FAIL airspace.violation_names_zone: $(head -3 "$TMP/stdout")"; fails=$((fails + 1)); }
mkdir -p "$TMP/airbad" && cp "$AIR"/* "$TMP/airbad/"
python3 - "$TMP/airbad/fence.plan" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
ring = p["geoFence"]["polygons"][0]["polygon"]
ring[1], ring[2] = ring[2], ring[1]  # a bow tie
json.dump(p, open(sys.argv[1], "w"))
PY
bad_zone() {  # bad_zone NAME ZONE_FILE PART: exit 2, one line naming the zone file and PART
  "$BIN" plan "$TMP/airbad/air.yaml" -o "$TMP/airbad/out" >/dev/null 2>"$TMP/stderr"; check "$1" 2 $?
  [ "$(wc -l <"$TMP/stderr")" = 1 ] && grep -qF "$2" "$TMP/stderr" && grep -qF "$3" "$TMP/stderr" && pass=$((pass + 1)) ||
    { echo "FAIL $1 message: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
}
bad_zone airspace.bow_tie "$TMP/airbad/fence.plan" "geoFence.polygons[0]: the zone's boundary crosses itself"
sed -i 's/fence.plan}/zones.kml}/' "$TMP/airbad/air.yaml" && echo '<kml><Document><Placemark>' >"$TMP/airbad/zones.kml"
bad_zone airspace.kml "$TMP/airbad/zones.kml" "GDAL cannot read it as KML"
grep -v '^origin' "$AIR/air.yaml" | sed 's|{file: |{file: '"$AIR"'/|' >"$TMP/air_no_origin.yaml"
expect_bad airspace.no_origin "$TMP/air_no_origin.yaml" "origin"
# A fence through the origin (its corner written to 15 digits) bounds the world at 0, not at
# the projection's -1.06e-09 or -0.
mkdir -p "$TMP/air0" && cp "$AIR"/* "$TMP/air0/" && sed -i 's/min: \[0, 0, 0\]/min: [-50, -50, 0]/' "$TMP/air0/air.yaml"
python3 - "$TMP/air0/fence.plan" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
ring = p["geoFence"]["polygons"][0]["polygon"]
ring[0], ring[1], ring[3] = [47.397699999999986, 8.545599999999993], [47.3977, ring[1][1]], [ring[3][0], 8.5456]
json.dump(p, open(sys.argv[1], "w"))
PY
"$BIN" info "$TMP/air0/air.yaml" | grep -q "^bounds    \[0, 0, 0\] \.\. " && pass=$((pass + 1)) ||
  { echo "FAIL airspace.origin_bound: $("$BIN" info "$TMP/air0/air.yaml" 2>&1 | grep bounds)"; fails=$((fails + 1)); }
# A fence read is the fence written: the .plan export's geoFence holds fence.plan's inclusion
# polygon and exclusion circle corner for corner (and the GeoJSON zone the routes cannot pass over).
"$BIN" export "$AIR/air.yaml" "$TMP/air/plan.json" -o "$TMP/air/exp" --format qgc >/dev/null 2>&1
python3 - "$AIR/fence.plan" "$TMP/air/exp/a1.plan" <<'PY' && pass=$((pass + 1)) || { echo "FAIL airspace.fence_round_trip"; fails=$((fails + 1)); }
import json, sys
read = json.load(open(sys.argv[1]))["geoFence"]
written = json.load(open(sys.argv[2]))["geoFence"]
for kind in ("polygons", "circles"):
    for z in read[kind]:
        assert z in written[kind], (kind, z)  # equal values, corner for corner
assert sum(z["inclusion"] for z in written["polygons"]) == 1, "one inclusion: the fence's, not the bounds"
PY
# Real terrain (world.terrain {file}): the alpine survey over swisstopo's Davos model in CH1903 /
# LV03 is planned, holds its 50-120 m band and the GeoJSON zone, exports above sea level; a
# waypoint pushed above the band or under it is a violation; bad rasters are one-line errors.
ALP="$SRC/scenarios/alpine_survey.yaml"
"$BIN" info "$ALP" | grep -q "CH1903 / LV03 (EPSG:21781)" && pass=$((pass + 1)) ||
  { echo "FAIL dem.info: $("$BIN" info "$ALP" | grep model)"; fails=$((fails + 1)); }
"$BIN" plan "$ALP" -o "$TMP/alp" --format qgc --format wpl --format csv >/dev/null 2>"$TMP/stderr"
check dem.plan 0 $?
grep -q "above mean sea level (MAV_FRAME_GLOBAL" "$TMP/stderr" && pass=$((pass + 1)) ||
  { echo "FAIL dem.amsl_note: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
node "$SRC/tests/qgc_plan_check.mjs" "$TMP/alp" s1 s2 s3 s4 >/dev/null 2>&1; check dem.qgc_files 0 $?
"$BIN" verify "$ALP" "$TMP/alp/plan.json" >/dev/null 2>&1; check dem.verify 0 $?
# P5's mission by small aircraft: their taxi turns on the ground are no reversals (the metric is
# the flight's); in the air they fly none.
"$BIN" plan "$SRC/scenarios/p5_small.yaml" -o "$TMP/p5s" 2>&1 | grep -q ", 0 reversals," && pass=$((pass + 1)) ||
  { echo "FAIL p5_small.reversals: $("$BIN" plan "$SRC/scenarios/p5_small.yaml" -o "$TMP/p5s" 2>&1 | grep reversals)"; fails=$((fails + 1)); }
# A home off the model's ground is refused with the ground's height to ten digits; that height
# entered to six (within a millimetre) is put on the ground, and the flight from it holds.
"$BIN" plan "$ALP" -o "$TMP/alp_home" --set 'uavs[0].home=[-2250, -1450, 0]' >/dev/null 2>"$TMP/stderr"
check dem.home.off_ground 2 $?
grep -q "the ground there, 704.6430664 m" "$TMP/stderr" && pass=$((pass + 1)) ||
  { echo "FAIL dem.home.digits: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
"$BIN" plan "$ALP" -o "$TMP/alp_home" --set 'uavs[0].home=[-2250, -1450, 704.643]' >/dev/null 2>&1
check dem.home.six_digits 0 $?
# Every typo of a file named in one run, each with the key it most likely meant; nothing written.
sed -e 's/radius: 0.5, speed: 5/radius: 0.5, sped: 5/' -e 's/separation: 5/seperation: 5/' \
  "$SRC/scenarios/demo.yaml" >"$TMP/typos.yaml"
"$BIN" plan "$TMP/typos.yaml" -o "$TMP/typos" >/dev/null 2>"$TMP/stderr"; check typos.exit 2 $?
[ "$(grep -c "did you mean 'speed'" "$TMP/stderr")" = 3 ] && grep -q "typos.yaml:38: mission.seperation: unknown key 'seperation' (did you mean 'separation'?)" "$TMP/stderr" &&
  [ ! -e "$TMP/typos" ] && pass=$((pass + 1)) || { echo "FAIL typos.all_named: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
# A wait on the ground is the departure's: depart_s + flight_s = the last movement, arrival_s
# counts the wait (the second UAV leaves 3 s later to keep 10 m from the first).
cat >"$TMP/cross.yaml" <<'EOF'
version: 1
name: cross
world: {bounds: {min: [0, 0, 0], max: [200, 200, 40]}}
uavs:
  - {id: a, start: [10, 100, 0], goal: [190, 100, 0], radius: 0.5, speed: 5}
  - {id: b, start: [100, 10, 0], goal: [100, 190, 0], radius: 0.5, speed: 5}
mission: {type: independent, separation: 10}
planner: {algorithm: astar}
EOF
"$BIN" plan "$TMP/cross.yaml" -o "$TMP/cross" >"$TMP/stdout" 2>&1
grep -q "depart_s  flight_s arrival_s" "$TMP/stdout" && grep -Eq "^b +solved +[0-9.]+ +3.000000 +37.220000 +40.120000 " "$TMP/stdout" &&
  pass=$((pass + 1)) || { echo "FAIL plan.departure: $(cat "$TMP/stdout")"; fails=$((fails + 1)); }
# Valid values that look like a unit or order mistake get a hint on stderr, and still plan: a
# turn limit in radians, a speed in km/h, a world in kilometres, a GeoJSON zone with lat and lon
# swapped (thousands of km away). The bundled scenarios get none.
sed -e 's/max_turn_deg: 60/max_turn_deg: 1.57/' -e 's/speed: 5,/speed: 36,/' "$SRC/scenarios/demo.yaml" >"$TMP/units.yaml"
"$BIN" plan "$TMP/units.yaml" -o "$TMP/units" >/dev/null 2>"$TMP/stderr"; check hints.plan 0 $?
grep -q "units.yaml:33: uavs\[0\].max_turn_deg: hint: a turn limit of 1.57 degrees; if that is radians, write 89.9544" "$TMP/stderr" &&
  grep -q "uavs\[2\].speed: hint: at 36 m/s (129.6 km/h) .* (if that is km/h, write 10)" "$TMP/stderr" &&
  pass=$((pass + 1)) || { echo "FAIL hints.units: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
cat >"$TMP/tiny.yaml" <<'EOF'
version: 1
name: tiny
world: {bounds: {min: [0, 0, 0], max: [2, 2, 1]}}
uavs: [{id: a, start: [0.5, 0.5, 0.5], goal: [1.5, 1.5, 0.5], radius: 0.2, speed: 5}]
EOF
"$BIN" info "$TMP/tiny.yaml" 2>&1 >/dev/null | grep -q "^.*tiny.yaml:4: uavs\[0\].radius: hint: the world is 2 m across, 10 times this UAV's radius" &&
  pass=$((pass + 1)) || { echo "FAIL hints.world_size: $("$BIN" info "$TMP/tiny.yaml" 2>&1)"; fails=$((fails + 1)); }
mkdir -p "$TMP/swapped" && cp "$AIR"/* "$TMP/swapped/"
python3 - "$TMP/swapped/zones.geojson" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
swap = lambda c: [c[1], c[0]] + c[2:] if isinstance(c[0], (int, float)) else [swap(x) for x in c]
for f in p["features"]:
    f["geometry"]["coordinates"] = swap(f["geometry"]["coordinates"])
json.dump(p, open(sys.argv[1], "w"))
PY
"$BIN" info "$TMP/swapped/air.yaml" 2>&1 >/dev/null | grep -q "airspace\[0\].file: hint: zones.geojson zone 0 lies 5653 km outside the world's bounds (lat and lon swapped?" &&
  pass=$((pass + 1)) || { echo "FAIL hints.swapped: $("$BIN" info "$TMP/swapped/air.yaml" 2>&1 >/dev/null)"; fails=$((fails + 1)); }
# An origin with lat and lon swapped puts the elevation model thousands of km away: the error says so.
mkdir -p "$TMP/alp_swapped" && cp -r "$SRC/scenarios/data" "$TMP/alp_swapped/"
sed 's/origin: {lat: 46.8195, lon: 9.8291, alt: 1500}/origin: {lat: 9.8291, lon: 46.8195, alt: 1500}/' \
  "$SRC/scenarios/alpine_survey.yaml" >"$TMP/alp_swapped/alp.yaml"
"$BIN" info "$TMP/alp_swapped/alp.yaml" >/dev/null 2>"$TMP/stderr"; check hints.origin_swapped 2 $?
grep -q "davosdorf.tif: terrain: .* it lies 5376 km from the world: is the scenario's origin right (lat and lon swapped?)" "$TMP/stderr" &&
  pass=$((pass + 1)) || { echo "FAIL hints.origin_swapped: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
for s in "$SRC"/scenarios/*.yaml; do
  "$BIN" info "$s" 2>&1 >/dev/null | grep -q "hint:" && { echo "FAIL hints.bundled: $s"; fails=$((fails + 1)); }
done
# A formation that flies most of its way out of shape (single file through a canyon narrower than
# its shape) is valid, and says so for each UAV; P1's formation keeps its shape and says nothing.
cat >"$TMP/canyon.yaml" <<'EOF'
version: 1
name: canyon
world:
  bounds: {min: [0, 0, 0], max: [600, 200, 0]}
  obstacles:
    - {type: prism, id: north_wall, polygon: [[50, 104], [550, 104], [550, 200], [50, 200]], z_min: 0, z_max: 1}
    - {type: prism, id: south_wall, polygon: [[50, 0], [550, 0], [550, 96], [50, 96]], z_min: 0, z_max: 1}
uavs:
  - {id: lead, start: [20, 100, 0], goal: [580, 100, 0], radius: 0.5, speed: 5, sensor_range: 20}
  - {id: left, start: [14, 106, 0], goal: [574, 106, 0], radius: 0.5, speed: 5, sensor_range: 20}
  - {id: right, start: [14, 94, 0], goal: [574, 94, 0], radius: 0.5, speed: 5, sensor_range: 20}
mission:
  type: formation
  separation: 2
  shape: [[0, 0, 0], [-6, 6, 0], [-6, -6, 0]]
planner: {algorithm: aco_voronoi}
EOF
"$BIN" plan "$TMP/canyon.yaml" -o "$TMP/canyon" >/dev/null 2>"$TMP/stderr"; check formation.canyon 0 $?
[ "$(grep -c "note: [a-z]* kept its slot [0-9]* s of the [0-9]* s in formation ([0-9]* %, 1 break): out of shape for most of the flight" "$TMP/stderr")" = 3 ] &&
  pass=$((pass + 1)) || { echo "FAIL formation.out_of_shape: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
"$BIN" plan "$SRC/scenarios/p1_formation.yaml" -o "$TMP/p1f" 2>&1 >/dev/null | grep -q "out of shape" &&
  { echo "FAIL formation.p1_in_shape"; fails=$((fails + 1)); } || pass=$((pass + 1))
# mission.cruise_agl: a fleet from the ground cruises at least that high between take-off and
# landing (without it, at the 2.5 m default); info says so.
sed 's/mission: {type: independent, separation: 10}/mission: {type: independent, separation: 10, cruise_agl: 30}/' \
  "$TMP/cross.yaml" >"$TMP/cruise.yaml"
"$BIN" info "$TMP/cruise.yaml" | grep -q "^min_agl   30 m above the ground for every UAV while planning (mission.cruise_agl 30 m)" &&
  pass=$((pass + 1)) || { echo "FAIL cruise_agl.info: $("$BIN" info "$TMP/cruise.yaml" | grep min_agl)"; fails=$((fails + 1)); }
"$BIN" plan "$TMP/cruise.yaml" -o "$TMP/cruise" >/dev/null 2>&1; check cruise_agl.plan 0 $?
python3 - "$TMP/cruise/plan.json" "$TMP/cross/plan.json" <<'PY' && pass=$((pass + 1)) || { echo "FAIL cruise_agl.height"; fails=$((fails + 1)); }
import json, sys
high, low = (json.load(open(f)) for f in sys.argv[1:])
assert all(u["metrics"]["min_agl_m"] >= 30 for u in high["uavs"]), [u["metrics"]["min_agl_m"] for u in high["uavs"]]
assert all(u["metrics"]["min_agl_m"] < 5 for u in low["uavs"]), [u["metrics"]["min_agl_m"] for u in low["uavs"]]
PY
# A home whose take-off column comes near something names it: a building, or the terrain rising
# within the body's reach (then what lets it lift off).
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/home_near" --set 'uavs[0].home=[199.8, 230, 8]' >/dev/null 2>"$TMP/stderr"
check home.near_building 2 $?
grep -q "cannot take off: .* comes within 0.2 m of obstacle tower_a beside it" "$TMP/stderr" && pass=$((pass + 1)) ||
  { echo "FAIL home.near_building: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/home_near" --set 'uavs[0].home=[99.8, 50, 0]' >/dev/null 2>"$TMP/stderr"
grep -q "comes within 0.2 m of the terrain beside it (radius plus clearance 1.5 m); the ground rises within the body's reach: a flatter spot or a smaller radius lifts off" "$TMP/stderr" &&
  pass=$((pass + 1)) || { echo "FAIL home.on_a_step: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
# A start inside a building names it.
sed 's/start: \[20, 20, 30\]/start: [230, 230, 30]/' "$SRC/scenarios/demo.yaml" >"$TMP/in_building.yaml"
expect_bad start.in_building "$TMP/in_building.yaml" "uavs[0].start: start is inside obstacle tower_a"
# max_agl is measured from the lowest ground under a UAV: a 5 m pit in a 40 m cell of an
# elevation model lowers the band's top there (min_agl keeps the cell's highest pixel). A level
# flight 30 m above the cell's height is 50 m above the pit: a violation; the plan dips over it.
mkdir -p "$TMP/pit"
python3 - "$TMP/pit" <<'PY'
import sys
d = sys.argv[1]
rows = [" ".join("380" if (r, c) == (99, 100) else "400" for c in range(200)) for r in range(200)]
open(d + "/pit.asc", "w").write("ncols 200\nnrows 200\nxllcorner -500\nyllcorner -500\ncellsize 5\n"
                                "NODATA_value -9999\n" + "\n".join(rows) + "\n")
open(d + "/pit.prj", "w").write(
    'PROJCS["local aeqd",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],'
    'PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Azimuthal_Equidistant"],'
    'PARAMETER["latitude_of_center",47],PARAMETER["longitude_of_center",8],PARAMETER["false_easting",0],'
    'PARAMETER["false_northing",0],UNIT["metre",1]]')
PY
cat >"$TMP/pit/pit.yaml" <<'EOF'
version: 1
name: pit
origin: {lat: 47, lon: 8, alt: 380}
world:
  bounds: {min: [-400, -100, 0], max: [400, 100, 200]}
  terrain: {file: pit.asc, cell: 40}
uavs:
  - {id: a, start: [-300, 2, 50], goal: [300, 2, 50], radius: 1, speed: 10, min_agl: 10, max_agl: 40}
planner: {algorithm: astar}
EOF
"$BIN" plan "$TMP/pit/pit.yaml" -o "$TMP/pit/o" >/dev/null 2>&1; check max_agl.pit_plan 0 $?
python3 - "$TMP/pit/o/plan.json" "$TMP/pit/level.json" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
over = [r[3] for r in p["uavs"][0]["trajectory"] if 0 <= r[1] <= 5]
assert over and max(over) <= 40 - 1 + 1e-6, over  # the body under the band's top over the pit
p["uavs"][0]["trajectory"] = [[0, -300, 2, 50], [60, 300, 2, 50]]
json.dump(p, open(sys.argv[2], "w"))
PY
[ $? = 0 ] && pass=$((pass + 1)) || { echo "FAIL max_agl.pit_dips"; fails=$((fails + 1)); }
"$BIN" verify "$TMP/pit/pit.yaml" "$TMP/pit/level.json" >"$TMP/stdout" 2>&1; check max_agl.pit_level 1 $?
grep -q "high_altitude .*height 50 m above the lowest ground under it, above max_agl 40 m" "$TMP/stdout" &&
  pass=$((pass + 1)) || { echo "FAIL max_agl.pit_message: $(cat "$TMP/stdout")"; fails=$((fails + 1)); }
# Above the terrain is ArduPilot's frame: for PX4 (the default) refused before planning, nothing written.
"$BIN" plan "$ALP" -o "$TMP/alp_px4" --format qgc --altitude terrain >/dev/null 2>"$TMP/stderr"; check dem.terrain_px4 2 $?
[ "$(wc -l <"$TMP/stderr")" = 1 ] && grep -q "PX4 takes no mission item above the terrain" "$TMP/stderr" &&
  [ ! -e "$TMP/alp_px4" ] && pass=$((pass + 1)) || { echo "FAIL dem.terrain_px4 message or output: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
for dz in 200 -90; do
  python3 - "$TMP/alp/plan.json" "$TMP/alp/moved.json" "$dz" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
tr = p["uavs"][2]["trajectory"]
tr[len(tr) // 2][3] += float(sys.argv[3])  # one row out of the band
json.dump(p, open(sys.argv[2], "w"))
PY
  "$BIN" verify "$ALP" "$TMP/alp/moved.json" >"$TMP/stdout" 2>&1; check "dem.band_$dz" 1 $?
  grep -q "s3 .*\(max_agl\|min_agl\|terrain\)" "$TMP/stdout" && pass=$((pass + 1)) ||
    { echo "FAIL dem.band_${dz}_named: $(head -3 "$TMP/stdout")"; fails=$((fails + 1)); }
done
mkdir -p "$TMP/dem" && printf 'ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 500\n1 2\n3 4\n' >"$TMP/dem/flat.asc"
sed -e 's|file: data/davosdorf.tif|file: flat.asc|' -e '/airspace:/d' -e '/alpine_zones/d' "$ALP" >"$TMP/dem/s.yaml"
dem_bad() {  # dem_bad NAME PART: exit 2, one line naming the raster and PART, nothing written
  rm -rf "$TMP/dem/out"
  "$BIN" plan "$TMP/dem/s.yaml" -o "$TMP/dem/out" >/dev/null 2>"$TMP/stderr"; check "$1" 2 $?
  [ "$(wc -l <"$TMP/stderr")" = 1 ] && grep -qF "$TMP/dem/flat.asc: terrain: $2" "$TMP/stderr" && [ ! -e "$TMP/dem/out" ] &&
    pass=$((pass + 1)) || { echo "FAIL $1 message: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
}
dem_bad dem.no_crs "the raster has no coordinate system"
echo "junk" >"$TMP/dem/flat.asc"
dem_bad dem.unreadable "GDAL cannot read it as a raster"
# The bench tables find the bundled scenarios from any folder (beside the binary).
# (exit 0 or 1: whether its timing targets are met depends on the machine; 2 is a missing file)
(cd "$TMP" && "$BIN" bench p2 >"$TMP/stdout" 2>"$TMP/stderr"); rc=$?
[ $rc != 2 ] && grep -q "Table 1" "$TMP/stdout" && pass=$((pass + 1)) ||
  { echo "FAIL bench.any_folder: exit $rc: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
# --algorithm is the planner the mission is checked against (the file's astar cannot plan a group).
"$BIN" plan "$SRC/scenarios/demo.yaml" -o "$TMP/c" --set mission.type=group --algorithm apf >/dev/null 2>"$TMP/stderr"
rc=$?; [ $rc != 2 ] && pass=$((pass + 1)) || { echo "FAIL algorithm.wins: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
"$BIN" frobnicate >/dev/null 2>&1; check unknown.subcommand 2 $?

# P4 scenarios: every route verified (turn <= 60, pitch <= 30, no threat), rendezvous lengths
# within epsilon (the verifier checks the spread).
for sc in p4_table3 p4_rendezvous p3_group9 p3_group9_3d; do
  "$BIN" plan "$SRC/scenarios/$sc.yaml" -o "$TMP/$sc" >/dev/null 2>&1; check "$sc.plan" 0 $?
  "$BIN" verify "$SRC/scenarios/$sc.yaml" "$TMP/$sc/plan.json" >/dev/null 2>&1; check "$sc.verify" 0 $?
done

# P1's local layer: UAVs with sensors fly in the loop around moving obstacles; verified, and the
# same bytes twice. Bad sensing input is exit 2 with one line and nothing written.
p1="$SRC/scenarios/p1_moving.yaml"
"$BIN" plan "$p1" -o "$TMP/p1a" >/dev/null 2>&1; check p1_moving.plan 0 $?
"$BIN" verify "$p1" "$TMP/p1a/plan.json" >/dev/null 2>&1; check p1_moving.verify 0 $?
"$BIN" plan "$p1" -o "$TMP/p1b" >/dev/null 2>&1
cmp -s "$TMP/p1a/plan.json" "$TMP/p1b/plan.json"; check p1_moving.deterministic 0 $?
grep -q "flown in the loop" "$TMP/p1a/plan.json" || { echo "FAIL p1_moving: not flown in the loop"; fails=$((fails + 1)); }
"$BIN" plan "$p1" -o "$TMP/p1c" --set local=rrt >/dev/null 2>&1; check p1_moving.local_rrt 0 $?
mkp1() { sed "$1" "$p1" >"$TMP/$2"; echo "$TMP/$2"; }
expect_bad sensor.zero "$(mkp1 's/sensor_range: 30}/sensor_range: 0}/' s0.yaml)" "uavs[0].sensor_range"
expect_bad sensor.text "$(mkp1 's/sensor_range: 30}/sensor_range: far}/' s1.yaml)" "expected a number"
expect_bad trajectory.one.row "$(mkp1 's/trajectory: \[\[0, 150, 118, 0\], .*\]}/trajectory: [[0, 150, 118, 0]]}/' t1.yaml)" "at least 2 rows"
expect_bad trajectory.times "$(mkp1 's/\[12, 150, 94, 0\]/[0, 150, 94, 0]/' t2.yaml)" "times must increase"
expect_bad trajectory.nan "$(mkp1 's/\[12, 150, 94, 0\]/[12, .nan, 94, 0]/' t3.yaml)" "finite"
expect_bad trajectory.and.velocity "$(mkp1 's/{id: turning, radius: 2, /{id: turning, radius: 2, velocity: [1, 0, 0], /' t4.yaml)" "not both"

# A tampered plan: verify lists violations and exits 1.
awk 'BEGIN{n=0} /"trajectory": \[/ && n==0 {print; getline; sub(/\[0.0,20.0,20.0,30.0\]/, "[0.0,230.0,230.0,30.0]"); n=1} {print}' \
  "$TMP/a/plan.json" >"$TMP/tampered.json"
"$BIN" verify "$SRC/scenarios/demo.yaml" "$TMP/tampered.json" >"$TMP/stdout" 2>&1; check tampered.verify 1 $?
grep -q "u1 start" "$TMP/stdout" && grep -q "u1 obstacle" "$TMP/stdout" || { echo "FAIL tampered: violations not listed"; cat "$TMP/stdout"; fails=$((fails + 1)); }

# An unreachable goal is a clear failure, exit 1, and the plan file says failed.
cat >"$TMP/walled.yaml" <<'YAML'
version: 1
name: walled
world:
  bounds: {min: [0, 0, 0], max: [100, 100, 20]}
  obstacles:
    - {type: box, min: [50, 0, 0], max: [52, 100, 20]}
uavs:
  - {id: u1, start: [10, 50, 10], goal: [90, 50, 10]}
YAML
"$BIN" plan "$TMP/walled.yaml" -o "$TMP/w" >/dev/null 2>&1; check unreachable.exit 1 $?
grep -q '"status": "failed"' "$TMP/w/plan.json" || { echo "FAIL unreachable: plan not marked failed"; fails=$((fails + 1)); }

# Bad input: exit 2, one line naming the file and the place, no output.
good="$SRC/scenarios/demo.yaml"
mk() { sed "$1" "$good" >"$TMP/$2"; echo "$TMP/$2"; }
: >"$TMP/empty.yaml"; expect_bad empty "$TMP/empty.yaml" "empty"
head -c 300 "$BIN" >"$TMP/garbage.yaml"; expect_bad garbage "$TMP/garbage.yaml"
printf 'version: 1\nworld: [1, 2\n' >"$TMP/syntax.yaml"; expect_bad yaml.syntax "$TMP/syntax.yaml" "syntax"
expect_bad version "$(mk 's/^version: 1/version: 3/' version.yaml)" "version"
expect_bad missing.key "$(mk '/^  bounds:/d' missing.yaml)" "missing required key 'bounds'"
expect_bad unknown.key "$(mk 's/^  algorithm: astar/  algoritm: astar/' unknown.yaml)" "planner.algoritm"
expect_bad wrong.type "$(mk 's/separation: 5/separation: five/' type.yaml)" "mission.separation"
expect_bad nan "$(mk 's/radius: 15}/radius: .nan}/' nan.yaml)" "finite"
expect_bad inf "$(mk 's/weight: 1000000/weight: .inf/' inf.yaml)" "finite"
expect_bad negative.radius "$(mk 's/radius: 40,/radius: -40,/' negr.yaml)" "positive"
expect_bad negative.cell "$(mk 's/cell: 100/cell: -100/' negc.yaml)" "positive"
expect_bad start.in.obstacle "$(mk 's/start: \[20, 20, 30\]/start: [230, 230, 30]/' sin.yaml)" "uavs[0].start"
expect_bad goal.outside "$(mk 's/goal: \[580, 580, 40\]/goal: [580, 680, 40]/' gout.yaml)" "outside the world bounds"
# A home: on the ground, for a UAV that starts and ends in the air, of a mission planned UAV by UAV.
home='s/  - {id: u1, start: \[20, 20, 30\]/  - {id: u1, home: [10, 10, 0], start: [20, 20, 30]/'
expect_bad home.in.air "$(mk "${home/\[10, 10, 0\]/[10, 10, 5]}" hair.yaml)" "uavs[0].home"
expect_bad home.group "$(mk "$home; s/type: independent/type: group/" hgroup.yaml)" "independent and route missions"
expect_bad home.ground.start "$(mk "${home/start: \[20, 20, 30\]/start: [20, 20, 0]}" hstart.yaml)" "uavs[0].start"
expect_bad terrain.rows "$(mk 's/- \[0, 2, 4, 4, 2, 0\]/- [0, 2, 4, 4, 2]/' rows.yaml)" "rows must be equal"
expect_bad missing.file "$TMP/does-not-exist.yaml" "cannot open"
# The vehicle's keys (P5): time constants, rate limits, the speed map.
expect_bad model.tau "$(mk 's/start: \[20, 20, 30\]/start: [20, 20, 30], model: {type: autopilot, tau_heading: 0}/' tau.yaml)" "uavs[0].model.tau_heading"
expect_bad model.type "$(mk 's/start: \[20, 20, 30\]/start: [20, 20, 30], model: {type: jet}/' mtype.yaml)" "uavs[0].model.type"
expect_bad turn.rate "$(mk 's/start: \[20, 20, 30\]/start: [20, 20, 30], max_turn_rate_deg_s: 0/' rate.yaml)" "uavs[0].max_turn_rate_deg_s"
expect_bad climb.rate "$(mk 's/start: \[20, 20, 30\]/start: [20, 20, 30], max_climb_rate: -3/' climb.yaml)" "uavs[0].max_climb_rate"
expect_bad speed.map "$(mk 's/radius: 0.5, speed: 5,/radius: 0.5, speed: {min: 9, cruise: 8, max: 10},/' spd.yaml)" "uavs[0].speed.min"
expect_bad speed.max "$(mk 's/radius: 0.5, speed: 5,/radius: 0.5, speed: {cruise: 8, max: 7},/' spdx.yaml)" "uavs[0].speed.max"
printf '{"version": 1, "world": {"bounds": {"min": [0,0,0], "max": [1,1,1]}},}' >"$TMP/bad.json"; expect_bad json "$TMP/bad.json" "JSON"

# Run control: --time-limit bounds the whole command; Ctrl-C ends with exit 130 and nothing
# written; a killed run's temporary file is cleaned up. (--threads: tests/threads_test.sh.)
fifty="$TMP/fifty.yaml"
sed '/^uavs:/,$d' "$good" >"$fifty"
echo "uavs:" >>"$fifty"
for i in $(seq 0 49); do
  echo "  - {id: q$i, start: [$((15 + i % 5 * 8)), $((12 + i * 11)), 30], goal: [$((585 - i % 7 * 6)), $((588 - i * 11)), 40], speed: 5, max_turn_deg: 60, max_climb_deg: 30}" >>"$fifty"
done
printf 'mission: {type: independent, separation: 5}\nplanner: {algorithm: astar}\n' >>"$fifty"
t0=$(date +%s.%N)
"$BIN" plan "$fifty" -o "$TMP/fifty" --time-limit 1 >/dev/null 2>&1; check time_limit.exit 1 $?
t1=$(date +%s.%N)
awk -v a="$t0" -v b="$t1" 'BEGIN { exit !(b - a < 1.6) }' || { echo "FAIL time_limit: took $(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') s for 1 s"; fails=$((fails + 1)); }
grep -q "stopped (time limit" "$TMP/fifty/plan.json" || { echo "FAIL time_limit: no UAV says it was stopped"; fails=$((fails + 1)); }
"$BIN" plan "$fifty" -o "$TMP/interrupted" >/dev/null 2>"$TMP/stderr" &
pid=$!
# Started in the background, the command ignores SIGINT until it installs its handler (bash's
# rule for background jobs): the signal is sent once the handler is there, then planning is under way.
for _ in $(seq 1 300); do
  caught=$(awk '/^SigCgt:/ { print $2 }' "/proc/$pid/status" 2>/dev/null)
  [ -n "$caught" ] && [ $((16#$caught & 2)) -ne 0 ] && break
  sleep 0.02
done
sleep 0.3
kill -INT $pid
wait $pid; check interrupt.exit 130 $?
grep -q "interrupted" "$TMP/stderr" && [ ! -e "$TMP/interrupted/plan.json" ] || { echo "FAIL interrupt: message or output"; fails=$((fails + 1)); }
mkdir -p "$TMP/stale" && : >"$TMP/stale/plan.json.tmp.999999999"
"$BIN" plan "$good" -o "$TMP/stale" >/dev/null 2>&1; check stale.plan 0 $?
[ ! -e "$TMP/stale/plan.json.tmp.999999999" ] || { echo "FAIL stale temporary file kept"; fails=$((fails + 1)); }

# Refused before anything is planned or written: one line on stderr, exit 2, no output.
expect_refused() {  # expect_refused NAME PART ARGS...
  local name=$1 part=$2
  shift 2
  rm -rf "$TMP/refused"
  "$BIN" plan "$@" -o "$TMP/refused" >/dev/null 2>"$TMP/stderr"
  check "$name" 2 $?
  if [ "$(wc -l <"$TMP/stderr")" != 1 ] || ! grep -qF -- "$part" "$TMP/stderr"; then
    echo "FAIL $name: stderr is not one line with '$part':"; cat "$TMP/stderr"; fails=$((fails + 1))
  fi
  [ -e "$TMP/refused" ] && { echo "FAIL $name: wrote output"; fails=$((fails + 1)); }
}
expect_refused seed.negative "--seed" "$good" --seed -1
expect_refused time_limit.negative "--time-limit" "$good" --time-limit -5
expect_refused firmware.without.export "apply to --export" "$good" --firmware ardupilot
sed '/^origin:/d' "$good" >"$TMP/noorigin_plan.yaml"
expect_refused export.needs.origin "no origin" "$TMP/noorigin_plan.yaml" --export qgc
expect_refused tiny.cell "planner.params.cell_m = 0.0001 m" "$good" --set cell_m=0.0001
expect_refused memory.cap "--max-memory" "$good" --set cell_m=0.5 --max-memory 10M
expect_bad slow.uav "$(mk 's/goal: \[580, 580, 40\], radius: 0.5, speed: 5,/goal: [580, 580, 40], radius: 0.5, speed: 1e-6,/' slow.yaml)" "uavs[0].speed"
expect_bad duplicate.key "$(mk 's/seed: 7/seed: 7\nseed: 8/' dup.yaml)" "duplicate key 'seed'"
expect_bad second.document "$(printf '%s\n---\nname: other\n' "$(cat "$good")" >"$TMP/twodocs.yaml"; echo "$TMP/twodocs.yaml")" "second YAML document"
expect_refused set.newline.escaped 'speed=fast\nx' "$good" --set $'uavs[0].speed=fast\nx'
expect_refused set.escape.escaped 'speed=\x1b[31m' "$good" --set $'uavs[0].speed=\e[31m'
expect_refused set.error.names.argument "--set uavs[0].speed=-3" "$good" --set "uavs[0].speed=-3"

# verify: a plan naming a UAV the scenario lacks, and a malformed plan, are bad input.
sed 's/"id": "u3"/"id": "u9"/' "$TMP/a/plan.json" >"$TMP/u9.json"
"$BIN" verify "$good" "$TMP/u9.json" >/dev/null 2>"$TMP/stderr"; check verify.unknown.uav 2 $?
grep -q "u9" "$TMP/stderr" && grep -qF "$TMP/u9.json" "$TMP/stderr" || { echo "FAIL verify.unknown.uav message"; fails=$((fails + 1)); }
echo '{"format": "uavplan-plan"' >"$TMP/trunc.json"
"$BIN" verify "$good" "$TMP/trunc.json" >/dev/null 2>&1; check verify.malformed 2 $?


# P2: the cellular ant colony and its A* baseline plan the city through both task points; verified.
for alg in cellular_aco cell_astar; do
  "$BIN" plan "$SRC/scenarios/p2_city.yaml" -o "$TMP/p2_$alg" --algorithm $alg >/dev/null 2>&1; check p2.$alg.plan 0 $?
  "$BIN" verify "$SRC/scenarios/p2_city.yaml" "$TMP/p2_$alg/plan.json" >/dev/null 2>&1; check p2.$alg.verify 0 $?
done

# A home: the plan takes off there, passes the start and the goal and lands there; verified,
# exported and read back by the firmware rules.
"$BIN" plan "$(mk "$home" home.yaml)" -o "$TMP/home" --export qgc,wpl,csv >/dev/null 2>&1; check home.plan 0 $?
"$BIN" verify "$TMP/home.yaml" "$TMP/home/plan.json" >/dev/null 2>&1; check home.verify 0 $?
node -e 'const t=require(process.argv[1]).uavs[0].trajectory, a=t[0], b=t[t.length-1];
  process.exit(a[1]===10 && a[2]===10 && a[3]===0 && b[1]===10 && b[2]===10 && b[3]===0 ? 0 : 1)' "$TMP/home/plan.json"
check home.trajectory 0 $?
"$BIN" info "$TMP/home.yaml" | grep -q "home (10, 10, 0)" || { echo "FAIL home.info"; fails=$((fails + 1)); }
node "$SRC/tests/qgc_plan_check.mjs" "$TMP/home" u1 u2 u3 >/dev/null; check home.export.check 0 $?

# Not even CSV used to be written when an autopilot could not fly the added legs: without qgc or
# wpl, the plan is written as planned, saying why (a fixed wing in a flat world).
"$BIN" plan "$SRC/scenarios/p1_moving.yaml" -o "$TMP/flat" >/dev/null 2>&1
"$BIN" export "$SRC/scenarios/p1_moving.yaml" "$TMP/flat/plan.json" --format csv --vehicle fixedwing -o "$TMP/flat_csv" \
  >/dev/null 2>"$TMP/stderr"; check export.csv.without.legs 0 $?
grep -q "written as planned, without its added legs" "$TMP/stderr" ||
  { echo "FAIL export.csv.without.legs.note: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }

# Anytime: a colony told to run 3000 iterations under a 5 s limit returns its best route so far
# on every leg (it used to spend the limit on the first leg and fail), and says so.
"$BIN" plan "$SRC/scenarios/p2_city.yaml" -o "$TMP/p2_anytime" --set iterations=3000 --time-limit 5 >"$TMP/stdout" 2>&1
check p2.anytime.plan 0 $?
grep -q "note: the time limit stopped the colony.*best route so far" "$TMP/stdout" ||
  { echo "FAIL p2.anytime.note: $(cat "$TMP/stdout")"; fails=$((fails + 1)); }

# Progress on a terminal: a long plan shows what it is doing and for how long, even while one
# planner runs without reporting (script(1) gives it a terminal).
if command -v script >/dev/null; then
  script -qec "'$BIN' plan '$SRC/scenarios/p2_city.yaml' -o '$TMP/p2_tty' --set iterations=3000 --time-limit 3" \
    /dev/null >"$TMP/tty.txt" 2>&1
  # Any whole second will do: the time limit counts from the start, and a slow build (the
  # sanitizers) spends more of it loading the world before the colony starts.
  grep -Eq "planning: 0/1 UAVs \([1-9][0-9]* s\)" "$TMP/tty.txt" ||
    { echo "FAIL progress.heartbeat: $(tr '\r' '\n' <"$TMP/tty.txt" | head -5)"; fails=$((fails + 1)); }
fi

# P2 on OpenStreetMap buildings (GeoJSON through world.buildings): both planners, verified.
for alg in cellular_aco cell_astar; do
  "$BIN" plan "$SRC/scenarios/nyc_block.yaml" -o "$TMP/nyc_$alg" --algorithm $alg >/dev/null 2>&1; check nyc.$alg.plan 0 $?
  "$BIN" verify "$SRC/scenarios/nyc_block.yaml" "$TMP/nyc_$alg/plan.json" >/dev/null 2>&1; check nyc.$alg.verify 0 $?
done
# The footprints are obstacles to the verifier too: a straight flight at 6 m through the block
# hits the 11.7 m house at x = -43; the same flight at 14 m clears every roof.
mkdir -p "$TMP/nyc_bad/data" && cp "$SRC/scenarios/data/ny.geojson" "$TMP/nyc_bad/data/"
sed 's/goal: \[65, 25, 6\]/goal: [65, 10, 6]/; /waypoints:/d; s/type: route/type: independent/' "$SRC/scenarios/nyc_block.yaml" >"$TMP/nyc_bad/s.yaml"
printf '{"format": "uavplan-plan", "version": 1, "scenario": "nyc_block", "algorithm": "hand", "status": "solved", "uavs": [{"id": "rotor", "status": "solved", "waypoints": [[-65, 10, 6], [65, 10, 6]], "trajectory": [[0, -65, 10, 6], [43.3333, 65, 10, 6]]}]}' >"$TMP/nyc_bad/plan.json"
"$BIN" verify "$TMP/nyc_bad/s.yaml" "$TMP/nyc_bad/plan.json" >"$TMP/stdout" 2>&1; check nyc.straight.rejected 1 $?
grep -q "obstacle t=8.1" "$TMP/stdout" || { echo "FAIL nyc.straight.where: $(cat "$TMP/stdout")"; fails=$((fails + 1)); }
sed -i 's/, 6\]/, 14]/g' "$TMP/nyc_bad/s.yaml" "$TMP/nyc_bad/plan.json"  # over the 11.7 m roofs
"$BIN" verify "$TMP/nyc_bad/s.yaml" "$TMP/nyc_bad/plan.json" >/dev/null 2>&1; check nyc.straight.over 0 $?
sed -i 's#buildings: {file: data/ny.geojson}#buildings: {file: data/missing.geojson}#' "$TMP/nyc_bad/s.yaml"
"$BIN" plan "$TMP/nyc_bad/s.yaml" -o "$TMP/nyc_bad/out" >/dev/null 2>"$TMP/stderr"; check nyc.missing.file 2 $?
if [ "$(wc -l <"$TMP/stderr")" != 1 ] || ! grep -q "s.yaml:[0-9]*: world.buildings.file: cannot read" "$TMP/stderr" || [ -e "$TMP/nyc_bad/out" ]; then
  echo "FAIL nyc.missing.file message: $(cat "$TMP/stderr")"; fails=$((fails + 1))
fi

# export and report: a scenario without an origin cannot be exported (one line, nothing
# written); an unknown format is a usage error; a plan of another scenario is bad input.
sed '/^origin:/d' "$good" >"$TMP/noorigin.yaml"
"$BIN" export "$TMP/noorigin.yaml" "$TMP/a/plan.json" --format qgc -o "$TMP/exp" >/dev/null 2>"$TMP/stderr"
check export.no.origin 2 $?
if [ "$(wc -l <"$TMP/stderr")" != 1 ] || ! grep -q "noorigin.yaml.*origin" "$TMP/stderr"; then
  echo "FAIL export.no.origin message:"; cat "$TMP/stderr"; fails=$((fails + 1)); fi
[ -e "$TMP/exp" ] && { echo "FAIL export.no.origin wrote files"; fails=$((fails + 1)); }
"$BIN" export "$good" "$TMP/a/plan.json" --format shapefile -o "$TMP/exp" >/dev/null 2>&1; check export.bad.format 2 $?
"$BIN" export "$good" "$TMP/u9.json" --format qgc -o "$TMP/exp" >/dev/null 2>&1; check export.unknown.uav 2 $?
"$BIN" report "$good" "$TMP/trunc.json" -o "$TMP/r.html" >/dev/null 2>&1; check report.malformed 2 $?
[ -e "$TMP/r.html" ] && { echo "FAIL report.malformed wrote a file"; fails=$((fails + 1)); }
"$BIN" report "$good" "$TMP/a/plan.json" -o "$TMP/r.html" >/dev/null 2>&1; check report.demo 0 $?
grep -q '<script type="application/json" id="uavplan-data">' "$TMP/r.html" || { echo "FAIL report.demo content"; fails=$((fails + 1)); }

# Planners compared on one file: another planner's parameter is a note, not an error; a mission
# that plans with its own method says which planners it takes.
"$BIN" plan "$good" -o "$TMP/note" --set ants=5 >/dev/null 2>"$TMP/stderr"; check other.planner.param 0 $?
grep -q "note: planner.params.ants is not a parameter of astar (it is one of cellular_aco, aco_voronoi): ignored" "$TMP/stderr" ||
  { echo "FAIL other.planner.param note: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
# P1 formation: bad shapes, goals and re-forming; the bundled scenario plans, verifies, arrives together.
f1="$SRC/scenarios/p1_formation.yaml"
mkf() { sed "$1" "$f1" >"$TMP/$2"; echo "$TMP/$2"; }
expect_bad formation.shape.length "$(mkf 's/shape: \[\[0, 0, 0\], \[-5, 5, 0\], \[-5, -5, 0\]\]/shape: [[0, 0, 0], [-5, 5, 0]]/' f_len.yaml)" "2 slots for 3 UAVs"
expect_bad formation.shape.close "$(mkf 's/\[-5, -5, 0\]\]/[-4, 4, 0]]/' f_close.yaml)" "slots must be at least"
expect_bad formation.goal "$(mkf 's/, goal: \[515, 472, 0\]//' f_goal.yaml)" "missing required key 'goal'"
expect_bad formation.reform "$(mkf 's/reform_after_steps: 5/reform_after_steps: 0/' f_reform.yaml)" "reform_after_steps"
rm -rf "$TMP/f1"
"$BIN" plan "$f1" -o "$TMP/f1" >/dev/null 2>&1; check formation.plan 0 $?
"$BIN" verify "$f1" "$TMP/f1/plan.json" >/dev/null 2>&1; check formation.verify 0 $?
grep -q '"formation": {' "$TMP/f1/plan.json" && grep -q '"eta_s"' "$TMP/f1/plan.json" && grep -q '"breaks": \[$' "$TMP/f1/plan.json" ||
  { echo "FAIL formation.plan: no formation block with breaks"; fails=$((fails + 1)); }
"$BIN" plan "$f1" -o "$TMP/f1rrt" --set local=rrt >/dev/null 2>&1; [ -s "$TMP/f1rrt/plan.json" ] || { echo "FAIL formation.local.rrt: no plan"; fails=$((fails + 1)); }
expect_refused forced.planner "apf" "$SRC/scenarios/p3_group9.yaml" --algorithm astar
expect_bad self.intersecting "$(mk 's/- {type: box, id: tower_a, min: \[200, 200, 0\], max: \[260, 260, 60\]}/- {type: prism, polygon: [[200, 200], [260, 260], [260, 200], [200, 262]], z_min: 0, z_max: 60}/' bowtie.yaml)" "self-intersecting"
mkdir -p "$TMP/adir"
"$BIN" report "$good" "$TMP/a/plan.json" -o "$TMP/adir" >/dev/null 2>"$TMP/stderr"; check report.folder 2 $?
grep -q "is a folder" "$TMP/stderr" || { echo "FAIL report.folder message: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }

# On the ground: take-off and landing legs, clearance and min_agl, a shared landing spot.
cat >"$TMP/ground.yaml" <<'YAML'
version: 1
name: ground
world:
  bounds: {min: [0, 0, 0], max: [300, 200, 60]}
  obstacles:
    - {type: box, min: [120, 40, 0], max: [160, 160, 35]}
  terrain: {type: grid, origin: [0, 0], cell: 50, heights: [[0, 2, 4, 6, 4, 2], [0, 2, 5, 8, 5, 2], [1, 3, 6, 9, 6, 3], [0, 2, 4, 6, 4, 2]]}
uavs:
  - {id: a, start: [20, 30, 0], goal: [270, 170, 2], clearance: 2, min_agl: 10, speed: 6, max_climb_deg: 30}
  - {id: b, start: [20, 90, 0], goal: [270, 170, 2], clearance: 2, min_agl: 10, speed: 6, max_climb_deg: 30}
mission: {type: independent, separation: 5}
planner: {algorithm: astar, params: {cell_m: 4}}
YAML
"$BIN" plan "$TMP/ground.yaml" -o "$TMP/ground" >/dev/null 2>&1; check ground.plan 0 $?
"$BIN" verify "$TMP/ground.yaml" "$TMP/ground/plan.json" >/dev/null 2>&1; check ground.verify 0 $?
node -e '
const p = require(process.argv[1]);
const [a, b] = p.uavs.map(u => u.trajectory);
const ok = a[0][3] === 0 && a[1][1] === a[0][1] && a[1][2] === a[0][2] && a[a.length - 1][3] === 2 &&
  Math.hypot(a[a.length - 1][1] - b[b.length - 1][1], a[a.length - 1][2] - b[b.length - 1][2]) >= 5 &&
  p.uavs.every(u => u.metrics.min_agl_m >= 10 - 1e-6 && u.metrics.max_climb_deg <= 30 + 1e-6);
process.exit(ok ? 0 : 1);' "$TMP/ground/plan.json"; check ground.legs.and.spacing 0 $?
expect_bad ground.below.min_agl "$(sed 's/start: \[20, 90, 0\]/start: [20, 90, 5]/' "$TMP/ground.yaml" >"$TMP/g2.yaml"; echo "$TMP/g2.yaml")" "below min_agl"


# Exports leave only what holds: a tampered plan is refused (exit 1, nothing written) unless
# --force, which writes the UAVs that hold and names the others; a re-plan or re-export removes
# the files of the last export, never other files; every --end is flown and verified.
node -e '
const fs = require("fs"); const p = JSON.parse(fs.readFileSync(process.argv[1]));
p.uavs[1].trajectory[2] = [p.uavs[1].trajectory[2][0], 230, 230, 30];  // inside tower_a
fs.writeFileSync(process.argv[2], JSON.stringify(p));' "$TMP/a/plan.json" "$TMP/tampered.json"
"$BIN" export "$good" "$TMP/tampered.json" --format qgc -o "$TMP/tx" >/dev/null 2>"$TMP/stderr"; check export.tampered 1 $?
grep -q "export refused: 1 of 3 UAVs does not hold; nothing written" "$TMP/stderr" && grep -q "u2: does not hold" "$TMP/stderr" ||
  { echo "FAIL export.tampered message: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
[ -e "$TMP/tx" ] && { echo "FAIL export.tampered wrote files"; fails=$((fails + 1)); }
# plan --export is all or nothing too: a plan whose export is refused (here, stopped before any
# UAV was planned) writes no plan.json either, and says so.
"$BIN" plan "$good" -o "$TMP/px" --export qgc --time-limit 0.001 >"$TMP/stdout" 2>"$TMP/stderr"; check plan.export.refused 1 $?
[ ! -e "$TMP/px" ] && grep -q "export refused" "$TMP/stderr" && grep -q "nothing written (the export was refused)" "$TMP/stdout" ||
  { echo "FAIL plan.export.refused: $(ls "$TMP/px" 2>&1) $(cat "$TMP/stderr" "$TMP/stdout")"; fails=$((fails + 1)); }
"$BIN" export "$good" "$TMP/tampered.json" --format qgc --force -o "$TMP/tx" >/dev/null 2>"$TMP/stderr"; check export.force 0 $?
[ -e "$TMP/tx/u1.plan" ] && [ -e "$TMP/tx/u3.plan" ] && [ ! -e "$TMP/tx/u2.plan" ] && grep -q "left out of the export: u2" "$TMP/stderr" ||
  { echo "FAIL export.force files: $(ls "$TMP/tx") $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
echo keep >"$TMP/tx/notes.txt"
"$BIN" export "$good" "$TMP/a/plan.json" --format csv -o "$TMP/tx" >/dev/null 2>&1; check export.again 0 $?
[ ! -e "$TMP/tx/u1.plan" ] && [ -e "$TMP/tx/u2.csv" ] && [ -e "$TMP/tx/notes.txt" ] ||
  { echo "FAIL export.stale: $(ls "$TMP/tx")"; fails=$((fails + 1)); }
# Formats exported one at a time from the same plan add up; another plan's export removes them
# and says so.
"$BIN" export "$good" "$TMP/a/plan.json" --format qgc -o "$TMP/ty" >/dev/null 2>&1; check export.one.qgc 0 $?
"$BIN" export "$good" "$TMP/a/plan.json" --format csv -o "$TMP/ty" >"$TMP/stdout" 2>&1; check export.one.csv 0 $?
[ -e "$TMP/ty/u1.plan" ] && [ -e "$TMP/ty/u1.csv" ] && grep -q "kept $TMP/ty/u1.plan (the same plan's)" "$TMP/stdout" ||
  { echo "FAIL export.formats.add.up: $(ls "$TMP/ty") $(cat "$TMP/stdout")"; fails=$((fails + 1)); }
"$BIN" export "$good" "$TMP/tampered.json" --format csv --force -o "$TMP/ty" >/dev/null 2>"$TMP/stderr"; check export.other.plan 0 $?
[ ! -e "$TMP/ty/u1.plan" ] && grep -q "note: removed $TMP/ty/u1.plan" "$TMP/stderr" ||
  { echo "FAIL export.other.plan: $(ls "$TMP/ty") $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
"$BIN" plan "$good" -o "$TMP/tx" >/dev/null 2>&1; check export.replan 0 $?
[ ! -e "$TMP/tx/u2.csv" ] && [ -e "$TMP/tx/notes.txt" ] || { echo "FAIL export.replan stale: $(ls "$TMP/tx")"; fails=$((fails + 1)); }
for end in land loiter none; do
  "$BIN" export "$good" "$TMP/a/plan.json" --format qgc,wpl,csv --end "$end" -o "$TMP/end_$end" >/dev/null 2>&1; check "export.end.$end" 0 $?
  node "$SRC/tests/qgc_plan_check.mjs" "$TMP/end_$end" u1 u2 u3 >/dev/null || { echo "FAIL export.end.$end check"; fails=$((fails + 1)); }
done
node -e 'const p = JSON.parse(require("fs").readFileSync(process.argv[1])); const it = p.mission.items; process.exit(it[it.length - 1].command === 17 ? 0 : 1)' \
  "$TMP/end_loiter/u1.plan"; check export.end.loiter.item 0 $?
"$BIN" export "$good" "$TMP/a/plan.json" --format qgc --end rtl -o "$TMP/rtl" >/dev/null 2>"$TMP/stderr"; check export.rtl.blocked 1 $?
grep -q "rtl" "$TMP/stderr" || { echo "FAIL export.rtl message: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
# A fixed wing in open country: climb-out, glide and landing pattern; and from the ground.
cat >"$TMP/open.yaml" <<'YAML'
version: 1
name: open
origin: {lat: -33.95, lon: 151.18, alt: 6}
world:
  bounds: {min: [-800, -800, 0], max: [1800, 800, 150]}
  obstacles:
    - {type: cylinder, id: mast, center: [500, 0], radius: 30, z_min: 0, z_max: 150}
uavs:
  - {id: fw1, start: [0, -40, 60], heading_deg: 0, goal: [1000, -40, 60], speed: 14, max_turn_deg: 30, max_climb_deg: 15}
  - {id: fw2, start: [0, 40, 60], heading_deg: 0, goal: [1000, 40, 60], speed: 14, max_turn_deg: 30, max_climb_deg: 15}
mission: {type: independent, separation: 20}
planner: {algorithm: astar, params: {cell_m: 10}}
YAML
"$BIN" plan "$TMP/open.yaml" -o "$TMP/open" --export qgc,wpl,csv --vehicle fixedwing --fence all >/dev/null 2>"$TMP/stderr"; check export.fixedwing 0 $?
node "$SRC/tests/qgc_plan_check.mjs" "$TMP/open" fw1 fw2 >/dev/null || { echo "FAIL export.fixedwing check"; fails=$((fails + 1)); }
node -e 'const p = JSON.parse(require("fs").readFileSync(process.argv[1])); const c = p.mission.items.map(i => i.command);
process.exit(p.mission.vehicleType === 1 && c.includes(189) && c[c.length - 1] === 21 && p.geoFence.circles.length === 1 ? 0 : 1)' \
  "$TMP/open/fw1.plan"; check export.fixedwing.pattern 0 $?
sed 's/^name: ground/name: ground\norigin: {lat: 52.5, lon: 13.4, alt: 34}/' "$TMP/ground.yaml" >"$TMP/ground_geo.yaml"
"$BIN" plan "$TMP/ground_geo.yaml" -o "$TMP/ground_geo" --export qgc,wpl,csv >/dev/null 2>&1; check export.ground 0 $?
# Flown 3 m up, its take-offs climb a few metres: PX4 up to v1.14 refuses that, and the export
# says what to set.
sed 's/min_agl: 10/min_agl: 3/' "$TMP/ground_geo.yaml" >"$TMP/ground_low.yaml"
"$BIN" plan "$TMP/ground_low.yaml" -o "$TMP/ground_low" --export qgc >/dev/null 2>"$TMP/stderr"
grep -q "PX4 up to v1.14 refuses a take-off below NAV_ACC_RAD + 1 m" "$TMP/stderr" && pass=$((pass + 1)) ||
  { echo "FAIL export.ground.px4_takeoff: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }
node "$SRC/tests/qgc_plan_check.mjs" "$TMP/ground_geo" a b >/dev/null || { echo "FAIL export.ground check"; fails=$((fails + 1)); }
"$BIN" plan "$TMP/ground_geo.yaml" -o "$TMP/ground_fw" --export qgc --vehicle fixedwing >/dev/null 2>"$TMP/stderr"; check export.ground.fixedwing 1 $?
grep -q "cannot fly its planned vertical take-off" "$TMP/stderr" || { echo "FAIL export.ground.fixedwing message: $(cat "$TMP/stderr")"; fails=$((fails + 1)); }

# Failures name the UAV, the leg and why, and suggest the setting that fixes them: a climb limit
# of 5 degrees over a wall, on a cell map whose levels are too tall to climb at all; the
# suggested level_m then solves it.
cat >"$TMP/climb.yaml" <<'YAML'
version: 1
name: climb
world:
  bounds: {min: [0, 0, 0], max: [600, 200, 120]}
  obstacles:
    - {type: box, min: [150, 0, 0], max: [180, 200, 80]}
uavs:
  - {id: a, start: [20, 100, 10], goal: [580, 100, 10], speed: 5, max_climb_deg: 5, max_turn_deg: 45}
mission: {type: independent}
planner: {algorithm: cellular_aco, params: {cell_m: 10}}
YAML
"$BIN" plan "$TMP/climb.yaml" -o "$TMP/climb" >"$TMP/stdout" 2>&1; check climb.cells.fails 1 $?
level=$(sed -n 's/^a: leg 1 (start to goal): no route on the cell map; .*climb limit of 5.0 deg.*level_m <= \([0-9.]*\)$/\1/p' "$TMP/stdout" | head -1)
if [ -z "$level" ]; then echo "FAIL climb.cells.hint: $(cat "$TMP/stdout")"; fails=$((fails + 1)); else
  "$BIN" plan "$TMP/climb.yaml" -o "$TMP/climb" --set "level_m=$level" >/dev/null 2>&1; check climb.cells.hint.solves 0 $?
  "$BIN" verify "$TMP/climb.yaml" "$TMP/climb/plan.json" >/dev/null 2>&1; check climb.cells.hint.verifies 0 $?
fi
# The lattice's step is derived long enough to climb at 5 deg (11.5 cells); given shorter, no move
# can change height, and the hint names the step that can.
"$BIN" plan "$TMP/climb.yaml" -o "$TMP/climb" --algorithm directional_astar --set step_cells=2.5 >"$TMP/stdout" 2>&1
check climb.lattice.fails 1 $?
grep -q "a: leg 1 (start to goal): no route within the turn and climb limits.*planner.params.step_cells >= 11.5" "$TMP/stdout" ||
  { echo "FAIL climb.lattice.hint: $(cat "$TMP/stdout")"; fails=$((fails + 1)); }
"$BIN" plan "$TMP/climb.yaml" -o "$TMP/climb" --algorithm rrt --set max_nodes=50 >"$TMP/stdout" 2>&1; check climb.rrt.fails 1 $?
grep -q "a: rrt: leg 1 (start to goal) from .*raise planner.params.max_nodes (now 50)" "$TMP/stdout" ||
  { echo "FAIL climb.rrt.hint: $(cat "$TMP/stdout")"; fails=$((fails + 1)); }

echo "$pass passed, $fails failed"
[ "$fails" = 0 ]
