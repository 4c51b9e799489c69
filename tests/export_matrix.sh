#!/usr/bin/env bash
# Every bundled scenario planned once and exported for each firmware and vehicle, every file
# written read back by the checker of QGroundControl's, MAVSDK's and the firmwares' rules
# (qgc_plan_check.mjs). Prints the table scenario x firmware x vehicle with its verdicts. Fails
# when a written file breaks a rule, or when a solved plan does not export with its default
# vehicle (a plan `plan` calls solved exports). A scenario without an origin is placed at
# 47.4 N 8.5 E, 400 m (a copy of it; none of those reads other files).
# Usage: export_matrix.sh UAVPLAN_BINARY SOURCE_DIR
set -uo pipefail
BIN=$1
SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fails=0
printf '%-16s %-8s %-9s %-11s %s\n' scenario status firmware vehicle verdict
for scen in "$SRC"/scenarios/*.yaml; do
  name=$(basename "$scen" .yaml)
  file=$scen
  if ! grep -q '^origin:' "$scen"; then
    file=$TMP/$name.yaml
    { cat "$scen"; echo 'origin: {lat: 47.4, lon: 8.5, alt: 400}'; } >"$file"
  fi
  "$BIN" plan "$file" -o "$TMP/$name" >/dev/null 2>&1
  status=$(node -e 'console.log(require(process.argv[1]).status)' "$TMP/$name/plan.json" 2>/dev/null || echo none)
  ids=$(node -e 'const p=require(process.argv[1]); console.log(p.uavs.filter(u=>u.status==="solved").map(u=>u.id).join(" "))' \
    "$TMP/$name/plan.json" 2>/dev/null)
  for fw in px4 ardupilot; do
    for vehicle in default multirotor fixedwing; do
      out=$TMP/$name-$fw-$vehicle
      args=(--format qgc,wpl,csv --firmware "$fw" -o "$out")
      [ "$vehicle" = default ] || args+=(--vehicle "$vehicle")
      if "$BIN" export "$file" "$TMP/$name/plan.json" "${args[@]}" >"$out.log" 2>&1; then
        # shellcheck disable=SC2086
        if node "$SRC/tests/qgc_plan_check.mjs" "$out" $ids >"$out.check" 2>&1; then
          verdict=ok
        else
          verdict="FAIL: $(head -1 "$out.check")"
          fails=$((fails + 1))
        fi
      else
        why=$(grep -v '^note' "$out.log" | sed -n 's/^  //p' | head -1)
        [ -n "$why" ] || why=$(grep -v '^note' "$out.log" | head -1)
        verdict="refused: ${why:0:90}"
        if [ "$vehicle" = default ] && [ "$status" = solved ]; then
          verdict="FAIL (a solved plan must export) $verdict"
          fails=$((fails + 1))
        fi
      fi
      printf '%-16s %-8s %-9s %-11s %s\n' "$name" "$status" "$fw" "$vehicle" "$verdict"
    done
  done
done
[ "$fails" -eq 0 ] || { echo "export_matrix: $fails failed"; exit 1; }
echo "export_matrix: ok"
