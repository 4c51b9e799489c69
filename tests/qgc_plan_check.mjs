// Independent reader of the mission exports, written from QGroundControl's and MAVSDK's import
// rules (not from uavplan's code): a .plan must load in both, a WPL 110 file must parse as QGC
// reads it, and both must say the same mission and follow the CSV trajectory's positions.
//   node qgc_plan_check.mjs DIR UAV_ID...
import fs from 'node:fs';
import path from 'node:path';
import { fileStem } from './file_stem.mjs';

const [dir, ...ids] = process.argv.slice(2);
let failures = 0;
const fail = (file, msg) => { console.error(`qgc_plan_check: ${file}: ${msg}`); failures++; };
const isNum = (v) => typeof v === 'number' && Number.isFinite(v);
const isInt = (v) => Number.isInteger(v);
const latOk = (v) => isNum(v) && v >= -90 && v <= 90;
const lonOk = (v) => isNum(v) && v >= -180 && v <= 180;
// NAV_WAYPOINT, LOITER_UNLIM, LOITER_TIME, LAND, TAKEOFF; RETURN_TO_LAUNCH, DO_CHANGE_SPEED,
// DO_LAND_START have no position.
const NAV_WITH_POSITION = new Set([16, 17, 19, 21, 22]);
const NO_POSITION = new Set([20, 178, 189]);

function checkPlan(file) {
  let j;
  try { j = JSON.parse(fs.readFileSync(file, 'utf8')); } catch (e) { fail(file, `not JSON: ${e.message}`); return null; }
  if (j.fileType !== 'Plan') fail(file, 'fileType is not "Plan"');
  if (j.version !== 1) fail(file, 'version is not 1');
  if (typeof j.groundStation !== 'string') fail(file, 'groundStation missing');
  const m = j.mission;
  if (!m || m.version !== 2) { fail(file, 'mission.version is not 2'); return null; }
  if (![12, 3].includes(m.firmwareType)) fail(file, `firmwareType ${m.firmwareType} is neither PX4 (12) nor ArduPilot (3)`);
  if (!isInt(m.vehicleType)) fail(file, 'vehicleType is not an integer');
  if (!isNum(m.cruiseSpeed) || m.cruiseSpeed <= 0) fail(file, 'cruiseSpeed is not a positive number');
  if (!isNum(m.hoverSpeed) || m.hoverSpeed <= 0) fail(file, 'hoverSpeed is not a positive number');
  const home = m.plannedHomePosition;
  if (!Array.isArray(home) || home.length !== 3 || !latOk(home[0]) || !lonOk(home[1]) || !isNum(home[2]))
    fail(file, 'plannedHomePosition is not [lat, lon, alt]');
  if (!Array.isArray(m.items) || m.items.length === 0) { fail(file, 'mission has no items'); return null; }
  // What each firmware stores: ArduPilot 650 (its SITL: "Only 650 items are supported"), PX4 500
  // (NUM_MISSIONS_SUPPORTED on its NuttX boards).
  const store = m.firmwareType === 3 ? 650 : 500;
  if (m.items.length > store) fail(file, `${m.items.length} mission items, more than the ${store} its firmware stores`);
  m.items.forEach((it, k) => {
    const at = `mission.items[${k}]`;
    if (it.type !== 'SimpleItem') fail(file, `${at}.type is not SimpleItem`);
    for (const key of ['command', 'frame', 'doJumpId']) if (!isInt(it[key])) fail(file, `${at}.${key} is not an integer`);
    if (typeof it.autoContinue !== 'boolean') fail(file, `${at}.autoContinue is not a boolean`);
    if (it.doJumpId !== k + 1) fail(file, `${at}.doJumpId is ${it.doJumpId}, expected ${k + 1}`);
    if (!Array.isArray(it.params) || it.params.length !== 7 || !it.params.every(isNum))
      fail(file, `${at}.params is not exactly 7 numbers`);
    if (NO_POSITION.has(it.command)) {
      // QGroundControl writes these in the mission frame (2) without altitude keys.
      if (it.frame !== 2) fail(file, `${at}: command ${it.command} in frame ${it.frame}, expected 2 (mission)`);
      if ('Altitude' in it) fail(file, `${at}: command ${it.command} has no position but an Altitude`);
      return;
    }
    if (!NAV_WITH_POSITION.has(it.command)) { fail(file, `${at}: command ${it.command} is not one this tool writes`); return; }
    for (const key of ['AMSLAltAboveTerrain', 'Altitude', 'AltitudeMode'])
      if (!isNum(it[key])) fail(file, `${at}.${key} is not a number (QGroundControl rejects null)`);
    // Altitude frames: 3 above home (QGC mode 1), 0 above sea level (2), 10 above the terrain (4).
    const modes = {3: 1, 0: 2, 10: 4};
    if (!(it.frame in modes)) fail(file, `${at}.frame is ${it.frame}, expected 3, 0 or 10`);
    else if (it.AltitudeMode !== modes[it.frame]) fail(file, `${at}.AltitudeMode ${it.AltitudeMode} does not match frame ${it.frame}`);
    if (it.frame !== m.items[0].frame) fail(file, `${at}.frame ${it.frame} differs from the first item's`);
    const home = m.plannedHomePosition[2];
    if (it.frame === 3 && Math.abs(it.AMSLAltAboveTerrain - (home + it.Altitude)) > 2e-4)
      fail(file, `${at}.AMSLAltAboveTerrain is not home plus Altitude`);
    if (it.frame === 0 && Math.abs(it.AMSLAltAboveTerrain - it.Altitude) > 2e-4)
      fail(file, `${at}.AMSLAltAboveTerrain differs from its AMSL Altitude`);
    if (!latOk(it.params[4]) || !lonOk(it.params[5]))
      fail(file, `${at} has no valid latitude/longitude`);
    if (isNum(it.params[6]) && Math.abs(it.params[6] - it.Altitude) > 1e-6)
      fail(file, `${at}.Altitude differs from params[6]`);
  });
  if (m.items[0].command !== 22) fail(file, 'the first item is not a takeoff (22)');
  else if (!(m.items[0].AMSLAltAboveTerrain > m.plannedHomePosition[2]))
    fail(file, `take-off to ${m.items[0].params[6]} m above home: PX4 refuses a take-off that is not above home`);
  checkFixedWingLanding(file, m);
  // Commanded timing (PX4 and ArduPilot fly their own default speed otherwise): a speed item
  // before the first waypoint, airspeed (type 0) for fixed wing, ground speed (1) for multirotors.
  const firstWaypoint = m.items.findIndex((it) => it.command === 16);
  const firstSpeed = m.items.findIndex((it) => it.command === 178);
  if (firstWaypoint >= 0 && (firstSpeed < 0 || firstSpeed > firstWaypoint))
    fail(file, 'no DO_CHANGE_SPEED (178) before the first waypoint: the vehicle would fly its own default speed');
  if (m.vehicleType === 1 && !(m.items[0].params[0] > 0))
    fail(file, `fixed-wing NAV_TAKEOFF minimum pitch ${m.items[0].params[0]}: ArduPlane would climb out at its own few degrees`);
  for (const it of m.items.filter((i) => i.command === 178)) {
    const want = m.vehicleType === 1 ? 0 : 1;
    if (it.params[0] !== want) fail(file, `DO_CHANGE_SPEED type ${it.params[0]}, expected ${want} for vehicleType ${m.vehicleType}`);
    if (!(it.params[1] > 0)) fail(file, `DO_CHANGE_SPEED speed ${it.params[1]} is not positive`);
  }
  if (![20, 21, 16, 17].includes(m.items[m.items.length - 1].command))
    fail(file, 'the mission does not end in land, return, loiter or a waypoint');
  const fence = j.geoFence;
  if (!fence || fence.version !== 2 || !Array.isArray(fence.polygons) || !Array.isArray(fence.circles))
    fail(file, 'geoFence is not {version 2, polygons, circles} (MAVSDK requires it)');
  else {
    fence.polygons.forEach((p, k) => {
      if (p.version !== 1 || typeof p.inclusion !== 'boolean') fail(file, `geoFence.polygons[${k}] lacks version 1 / inclusion`);
      if (!Array.isArray(p.polygon) || p.polygon.length < 3 || !p.polygon.every((v) => v.length === 2 && latOk(v[0]) && lonOk(v[1])))
        fail(file, `geoFence.polygons[${k}].polygon is not >= 3 [lat, lon] vertices`);
    });
    fence.circles.forEach((c, k) => {
      if (c.version !== 1 || typeof c.inclusion !== 'boolean' || !c.circle || !isNum(c.circle.radius) || c.circle.radius <= 0 ||
          !Array.isArray(c.circle.center) || !latOk(c.circle.center[0]) || !lonOk(c.circle.center[1]))
        fail(file, `geoFence.circles[${k}] is not {circle: {center: [lat, lon], radius}, inclusion, version 1}`);
    });
  }
  const rally = j.rallyPoints;
  if (!rally || rally.version !== 2 || !Array.isArray(rally.points) ||
      !rally.points.every((p) => p.length === 3 && latOk(p[0]) && lonOk(p[1]) && isNum(p[2])))
    fail(file, 'rallyPoints is not {version 2, points: [[lat, lon, alt]]} (MAVSDK requires it)');
  return j;
}

// PX4's distance between two positions (its get_distance_to_next_waypoint: a sphere of 6371 km).
function px4DistanceM(lat1, lon1, lat2, lon2) {
  const r = Math.PI / 180, dLat = (lat2 - lat1) * r, dLon = (lon2 - lon1) * r;
  const a = Math.sin(dLat / 2) ** 2 + Math.cos(lat1 * r) * Math.cos(lat2 * r) * Math.sin(dLon / 2) ** 2;
  return 6371000 * 2 * Math.atan2(Math.sqrt(a), Math.sqrt(1 - a));
}

// PX4's fixed-wing landing pattern: DO_LAND_START, then the approach waypoint, then NAV_LAND,
// the glide between them within FW_LND_ANG (5 deg by default), measured as PX4 measures it.
function checkFixedWingLanding(file, m) {
  const n = m.items.length;
  if (m.vehicleType !== 1 || m.items[n - 1].command !== 21) return;
  const start = m.items.findIndex((it) => it.command === 189);
  if (start < 0) { fail(file, 'a fixed-wing landing without DO_LAND_START (189)'); return; }
  const between = m.items.slice(start + 1, n - 1).filter((it) => NAV_WITH_POSITION.has(it.command));
  if (between.length !== 1 || between[0].command !== 16) {
    fail(file, 'DO_LAND_START is not followed by one approach waypoint and then NAV_LAND');
    return;
  }
  const a = between[0].params, l = m.items[n - 1].params;
  const glide = Math.atan2(a[6] - l[6], px4DistanceM(a[4], a[5], l[4], l[5])) * 180 / Math.PI;
  // PX4 accepts up to 0.1 deg more (its check's slack); a glide that needs the slack fails here.
  if (glide > 5.0) fail(file, `the landing glide is ${glide.toFixed(3)} deg, over PX4's FW_LND_ANG 5 deg`);
}

function checkWpl(file, plan) {
  const text = fs.readFileSync(file, 'utf8');
  if (text.includes('\r')) fail(file, 'has CR line ends');
  const lines = text.split('\n');
  if (lines[lines.length - 1] !== '') fail(file, 'does not end with a line end');
  lines.pop();
  if (lines[0] !== 'QGC WPL 110') { fail(file, 'first line is not "QGC WPL 110"'); return; }
  const rows = lines.slice(1).map((l) => l.split('\t'));
  rows.forEach((r, k) => {
    if (r.length !== 12) fail(file, `row ${k}: ${r.length} fields, expected 12 tab-separated`);
    if (Number(r[0]) !== k) fail(file, `row ${k}: index ${r[0]}`);
    if (!r.every((f) => f !== '' && Number.isFinite(Number(f)))) fail(file, `row ${k}: a field is not a number`);
  });
  if (rows.length === 0 || rows[0][1] !== '1') fail(file, 'row 0 (home) is not marked current');
  if (!plan) return;
  const home = plan.mission.plannedHomePosition;
  if (rows[0] && (Math.abs(Number(rows[0][8]) - home[0]) > 1e-9 || Math.abs(Number(rows[0][9]) - home[1]) > 1e-9))
    fail(file, 'home row differs from the .plan home');
  const items = plan.mission.items;
  if (rows.length - 1 !== items.length) { fail(file, `${rows.length - 1} items, the .plan has ${items.length}`); return; }
  items.forEach((it, k) => {
    const r = rows[k + 1];
    if (Number(r[3]) !== it.command || Number(r[2]) !== it.frame) fail(file, `row ${k + 1} differs from the .plan item`);
    for (let p = 0; p < 7; p++)
      if (Math.abs(Number(r[4 + p]) - it.params[p]) > 1e-9) fail(file, `row ${k + 1} param ${p + 1} differs from the .plan`);
  });
}

// The mission's positioned items must lie on the flown trajectory (CSV lat/lon), in order.
function checkAgainstCsv(file, plan, csvFile) {
  const rows = fs.readFileSync(csvFile, 'utf8').trim().split('\n');
  if (rows[0] !== 't,x,y,z,lat,lon,alt') { fail(csvFile, 'header is not t,x,y,z,lat,lon,alt'); return; }
  const pts = rows.slice(1).map((r) => r.split(',').map(Number));
  if (!pts.every((p) => p.length === 7 && p.every(Number.isFinite))) { fail(csvFile, 'a row is not 7 numbers'); return; }
  for (let k = 1; k < pts.length; k++) if (!(pts[k][0] > pts[k - 1][0])) fail(csvFile, `time does not increase at row ${k + 1}`);
  // Every waypoint on the trajectory in order, and the speed commanded for the leg into it the
  // leg's mean speed on the trajectory (within the 10 % of it a speed change is written for);
  // ArduCopter's speeds are horizontal (WPNAV_SPEED), the others' along the leg.
  // The first leg begins where the take-off ends (a runway take-off's taxi and roll come before).
  const at = (it, k0) => {  // the first row from k0 at the item's position and altitude (AMSL)
    for (let k = k0; k < pts.length; k++)
      if (Math.abs(pts[k][4] - it.params[4]) < 1e-7 && Math.abs(pts[k][5] - it.params[5]) < 1e-7 &&
          Math.abs(pts[k][6] - it.AMSLAltAboveTerrain) < 1e-3) return k;
    return -1;
  };
  // A fixed wing's airspeed is equivalent airspeed: the true speed is it over sqrt(rho / rho0)
  // (ISA troposphere) at the altitude of the item before it.
  let from = Math.max(0, at(plan.mission.items[0], 0)), speed = 0;
  let amsl = plan.mission.plannedHomePosition[2];
  const wing = plan.mission.vehicleType === 1;
  const eas = (h) => Math.pow(1 - 2.25577e-5 * Math.min(Math.max(h, -1000), 11000), 0.5 * 4.2559);
  const horizontal = plan.mission.firmwareType === 3 && !wing;
  for (const it of plan.mission.items) {
    if (it.command === 178) speed = it.params[1] / (wing ? eas(amsl) : 1);
    if (!NO_POSITION.has(it.command) && Number.isFinite(it.AMSLAltAboveTerrain)) amsl = it.AMSLAltAboveTerrain;
    if (it.command !== 16) continue;
    const found = at(it, from);
    if (found < 0) { fail(file, `waypoint (${it.params[4]}, ${it.params[5]}) is not on the trajectory after row ${from + 1}`); return; }
    let len = 0, moving = 0;
    for (let k = from + 1; k <= found; k++) {
      const d = Math.hypot(pts[k][1] - pts[k - 1][1], pts[k][2] - pts[k - 1][2], horizontal ? 0 : pts[k][3] - pts[k - 1][3]);
      len += d;
      if (d > 1e-6) moving += pts[k][0] - pts[k - 1][0];
    }
    const flown = moving > 0 ? len / moving : 0;
    if (flown > 0 && Math.abs(speed - flown) > 0.1 * speed + 1e-4)
      fail(file, `the leg into waypoint ${it.doJumpId} is flown at ${flown.toFixed(3)} m/s, the mission commands ${speed.toFixed(3)} m/s (true)`);
    from = found;
  }
  // The landing at the trajectory's end, or where its last run on the ground begins (a fixed
  // wing's roll-out after touch-down).
  const end = plan.mission.items[plan.mission.items.length - 1];
  let ground = pts.length - 1;
  while (ground > 0 && Math.abs(pts[ground - 1][6] - pts[pts.length - 1][6]) < 1e-6) ground--;
  const touch = pts[plan.mission.vehicleType === 1 ? ground : pts.length - 1];
  if (end.command === 21 && (Math.abs(end.params[4] - touch[4]) > 1e-7 || Math.abs(end.params[5] - touch[5]) > 1e-7))
    fail(file, 'the landing is not at the trajectory\'s end (nor where its roll-out begins)');
}

if (!dir || ids.length === 0) { console.error('usage: node qgc_plan_check.mjs DIR UAV_ID...'); process.exit(2); }
for (const id of ids) {
  const stem = fileStem(id);
  const planFile = path.join(dir, `${stem}.plan`);
  const plan = checkPlan(planFile);
  checkWpl(path.join(dir, `${stem}.waypoints`), plan);
  if (plan) checkAgainstCsv(planFile, plan, path.join(dir, `${stem}.csv`));
}
if (failures) process.exit(1);
console.log(`qgc_plan_check: ok (${ids.length} UAVs: .plan, .waypoints, .csv)`);
