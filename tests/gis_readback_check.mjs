// Reads the GeoJSON and KML exports back with GDAL's ogr2ogr (an independent reader) and checks
// them against the CSV trajectories: one LineString per UAV in lon, lat, alt order (RFC 7946),
// the same positions, WGS 84, obstacles as closed counter-clockwise polygons.
//   node gis_readback_check.mjs DIR OBSTACLE_COUNT UAV_ID...
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileStem } from './file_stem.mjs';

const [dir, obstacleCountArg, ...ids] = process.argv.slice(2);
let failures = 0;
const fail = (msg) => { console.error(`gis_readback_check: ${msg}`); failures++; };
const ogr = (...args) => execFileSync('ogr2ogr', args, { encoding: 'utf8', maxBuffer: 64 << 20 });

// ogr2ogr CSV with WKT geometry (RFC 4180: a quote inside a quoted field is doubled); returns
// [{WKT, ...fields}].
function readCsv(text) {
  const lines = text.trim().split('\n');
  const split = (l) => {
    const out = []; let cur = ''; let q = false;
    for (let k = 0; k < l.length; k++) {
      const ch = l[k];
      if (q && ch === '"' && l[k + 1] === '"') { cur += '"'; k++; }
      else if (ch === '"') q = !q;
      else if (ch === ',' && !q) { out.push(cur); cur = ''; }
      else cur += ch;
    }
    out.push(cur);
    return out;
  };
  const head = split(lines[0]);
  return lines.slice(1).map((l) => Object.fromEntries(split(l).map((v, k) => [head[k], v])));
}
function wktPoints(wkt) {
  const inner = wkt.slice(wkt.indexOf('(')).replace(/[()]/g, '');
  return inner.split(',').map((p) => p.trim().split(/\s+/).map(Number));
}
function trajectory(id) {
  return fs.readFileSync(path.join(dir, `${fileStem(id)}.csv`), 'utf8').trim().split('\n').slice(1).map((r) => r.split(',').map(Number));
}
function sameRoute(label, pts, traj) {
  // Every exported vertex (lon, lat, alt) is a trajectory row's (lon, lat, alt); ends match.
  const keyed = traj.map((r) => [r[5], r[4], r[6]]);
  const near = (a, b) => Math.abs(a[0] - b[0]) < 1e-7 && Math.abs(a[1] - b[1]) < 1e-7 && Math.abs(a[2] - b[2]) < 1e-3;
  if (!near(pts[0], keyed[0])) fail(`${label}: first vertex ${pts[0]} is not the trajectory's start ${keyed[0]} (lon, lat, alt)`);
  if (!near(pts[pts.length - 1], keyed[keyed.length - 1])) fail(`${label}: last vertex is not the trajectory's end`);
  let k = 0;
  for (const p of pts) {
    while (k < keyed.length && !near(p, keyed[k])) k++;
    if (k === keyed.length) { fail(`${label}: vertex ${p} is not on the trajectory in order`); return; }
  }
}

if (!dir || ids.length === 0) { console.error('usage: node gis_readback_check.mjs DIR OBSTACLE_COUNT UAV_ID...'); process.exit(2); }
const obstacleCount = Number(obstacleCountArg);

// GeoJSON
const gj = path.join(dir, 'plan.geojson');
const info = execFileSync('ogrinfo', ['-ro', '-al', '-so', gj], { encoding: 'utf8' });
if (!/using driver `GeoJSON' successful/.test(info)) fail('GDAL did not open plan.geojson with its GeoJSON driver');
if (!/WGS 84/.test(info)) fail('plan.geojson is not read as WGS 84');
const routes = readCsv(ogr('-f', 'CSV', '/vsistdout/', gj, '-where', "kind = 'route'", '-lco', 'GEOMETRY=AS_WKT'));
if (routes.length !== ids.length) fail(`plan.geojson: ${routes.length} routes, expected ${ids.length}`);
for (const id of ids) {
  const r = routes.find((x) => x.uav === id);
  if (!r) { fail(`plan.geojson: no route for ${id}`); continue; }
  if (!r.WKT.startsWith('LINESTRING Z')) fail(`plan.geojson: ${id} is ${r.WKT.slice(0, 20)}, not a 3-D LineString`);
  sameRoute(`plan.geojson ${id}`, wktPoints(r.WKT), trajectory(id));
}
const obstacles = readCsv(ogr('-f', 'CSV', '/vsistdout/', gj, '-where', "kind = 'obstacle'", '-lco', 'GEOMETRY=AS_WKT'));
if (obstacles.length !== obstacleCount) fail(`plan.geojson: ${obstacles.length} obstacles, expected ${obstacleCount}`);
for (const o of obstacles) {
  if (!o.WKT.startsWith('POLYGON')) { fail(`plan.geojson: obstacle ${o.index} is not a Polygon`); continue; }
  const ring = wktPoints(o.WKT);
  const first = ring[0], last = ring[ring.length - 1];
  if (first[0] !== last[0] || first[1] !== last[1]) fail(`plan.geojson: obstacle ${o.index} ring is not closed`);
  let area2 = 0;
  for (let k = 0; k + 1 < ring.length; k++) area2 += ring[k][0] * ring[k + 1][1] - ring[k + 1][0] * ring[k][1];
  if (!(area2 > 0)) fail(`plan.geojson: obstacle ${o.index} exterior ring is not counter-clockwise (RFC 7946)`);
}

// KML
const kml = path.join(dir, 'plan.kml');
const kroutes = readCsv(ogr('-f', 'CSV', '/vsistdout/', kml, 'routes', '-lco', 'GEOMETRY=AS_WKT'));
if (kroutes.length !== ids.length) fail(`plan.kml: ${kroutes.length} routes, expected ${ids.length}`);
for (const id of ids) {
  const r = kroutes.find((x) => x.Name === id);
  if (!r) { fail(`plan.kml: no route named ${id}`); continue; }
  if (!r.WKT.startsWith('LINESTRING Z')) fail(`plan.kml: ${id} is not a 3-D LineString`);
  sameRoute(`plan.kml ${id}`, wktPoints(r.WKT), trajectory(id));
}
if (!/<altitudeMode>absolute<\/altitudeMode>/.test(fs.readFileSync(kml, 'utf8'))) fail('plan.kml: routes lack altitudeMode');
const kobst = readCsv(ogr('-f', 'CSV', '/vsistdout/', kml, 'obstacles', '-lco', 'GEOMETRY=AS_WKT'));
if (kobst.length !== obstacleCount) fail(`plan.kml: ${kobst.length} obstacles, expected ${obstacleCount}`);

if (failures) process.exit(1);
console.log(`gis_readback_check: ok (${ids.length} routes, ${obstacleCount} obstacles, GeoJSON and KML)`);
