// The report viewer: reads the plan data the uavplan binary inlined in the page and draws the
// 3-D view (three.js), the charts (uPlot), the metrics table and the verification.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { Line2 } from 'three/addons/lines/Line2.js';
import { LineGeometry } from 'three/addons/lines/LineGeometry.js';
import { LineMaterial } from 'three/addons/lines/LineMaterial.js';
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import './report.css';

const data = JSON.parse(document.getElementById('uavplan-data').textContent);

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'style') for (const [name, value] of Object.entries(v)) e.style.setProperty(name, value);
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c instanceof Node ? c : document.createTextNode(String(c)));
  return e;
}

const fmt = (v, d = 3) => (Number.isInteger(v) ? String(v) : v.toFixed(d));
// A metric cell says why a value is missing instead of showing a dash.
function metricText(u, key) {
  if (key === 'kept_off_m') return `${fmt(u.radius + (u.clearance || 0))} = ${u.radius} + ${u.clearance || 0}`;
  const v = u.metrics[key];
  if (typeof v === 'number') return fmt(v);
  if (u.trajectory.length < 2) return `not flown (${u.status})`;
  if (key === 'min_clearance_m') return 'no obstacle';
  if (key === 'min_agl_m') return 'flat world';
  if (key === 'arrival_s') return 'never at its goal to stay';
  return 'not computed';
}
const terrainBrown = '#8c7b5e';

// ---- page layout ----
const app = document.getElementById('app');
const holds = data.violations.length === 0;
app.append(
  el('header', {},
    el('h1', {}, data.name || 'plan'),
    el('span', { class: `badge ${data.status}` }, data.status),
    el('span', { class: `badge ${holds ? 'holds' : 'violations'}` },
      holds ? 'verified: plan holds' : `verified: ${data.violations.length} violation(s)`),
    el('span', { class: 'muted' }, `${data.mission} mission, algorithm ${data.algorithm}, seed ${data.seed}, ${data.uavs.length} UAV(s)`)),
);
const main = el('main');
app.append(main);
const left = el('section');
const right = el('section');
main.append(left, right);

const view = el('div', { id: 'view' });
const slider = el('input', { type: 'range', min: '0', max: String(data.t_end_s || 0), step: 'any', value: '0', id: 'time' });
const timeLabel = el('span', { class: 'muted', id: 'time-label' }, 't = 0 s');
const statesLabel = el('span', { class: 'muted', id: 'uav-states' }, '');
const play = el('button', { type: 'button', id: 'play' }, 'Play');
const routesToggle = el('input', { type: 'checkbox', checked: '', id: 'routes' });
left.append(view,
  el('div', { class: 'controls' }, play, slider, timeLabel, statesLabel,
    el('label', {}, routesToggle, ' routes')));
const legend = el('div', { class: 'legend', id: 'legend' });
for (const u of data.uavs) legend.append(el('span', { class: 'uav', style: { '--c': u.colour } }, `${u.id} (${u.status})`));
const kinds = new Set(data.obstacles.map((o) => o.kind || 'obstacle'));
if (kinds.has('obstacle')) legend.append(el('span', { class: 'key', style: { '--c': '#a4abb5' } }, 'obstacle'));
if (kinds.has('airspace')) legend.append(el('span', { class: 'key', style: { '--c': '#dc2626' } }, 'no-fly zone (airspace file), named'));
if (kinds.has('fence')) legend.append(el('span', { class: 'key', style: { '--c': '#d97706' } }, 'outside the geofence'));
if (data.terrain) legend.append(el('span', { class: 'key', style: { '--c': terrainBrown } }, 'terrain'));
if (data.threats.length)
  legend.append(el('span', { class: 'key ring', style: { '--c': '#c2410c' } }, 'radar: threat cost = 1, 0.1, 0.01 x distance'));
if (data.moving.length) legend.append(el('span', { class: 'key dashed', style: { '--c': '#6b7280' } }, 'moving obstacle and its track'));
legend.append(el('span', { class: 'key', style: { '--c': '#1d232b' } }, 'start (cube) and goal (ring) in the UAV\'s colour'));
if ((data.via_points || []).length) legend.append(el('span', { class: 'key', style: { '--c': '#6d28d9' } }, 'via point V1, V2, ... (in order)'));
if ((data.task_points || []).length)
  legend.append(el('span', { class: 'key ring', style: { '--c': '#0f766e' } }, 'task point T1, T2, ... and the radius it is reached within'));
if (data.airfield) legend.append(el('span', { class: 'key', style: { '--c': '#374151' } }, 'runway (from its threshold)'));
left.append(legend);

// ---- 3-D view (z up, the scenario's frame) ----
const bmin = new THREE.Vector3(...data.bounds.min);
const bmax = new THREE.Vector3(...data.bounds.max);
const size = new THREE.Vector3().subVectors(bmax, bmin);
const diag = size.length() || 1;
const centre = new THREE.Vector3().addVectors(bmin, bmax).multiplyScalar(0.5);

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setClearColor(0xf4f6f8);
view.append(renderer.domElement);
// North arrow and scale bar over the view, updated every frame from the camera.
const north = el('div', { class: 'overlay north', id: 'north', title: 'north (+y)' });
north.innerHTML = '<svg viewBox="-20 -24 40 48" width="40" height="48"><polygon points="0,-18 8,6 0,1 -8,6" fill="#1d232b"/>' +
  '<text x="0" y="20" text-anchor="middle" font-size="11" font-weight="700" fill="#1d232b">N</text></svg>';
const scaleBar = el('div', { class: 'overlay scalebar', id: 'scalebar' }, el('div', { class: 'bar' }), el('span', {}, ''));
view.append(north, scaleBar);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(45, 1, diag / 1000, diag * 20);
camera.up.set(0, 0, 1);
camera.position.set(centre.x - 0.55 * size.x, centre.y - 1.0 * size.y - 0.2 * diag, centre.z + 0.7 * diag);
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.copy(centre);
controls.update();
scene.add(new THREE.HemisphereLight(0xffffff, 0x8d8d8d, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(-0.4, -0.6, 1).multiplyScalar(diag);
scene.add(sun);

const boundsBox = new THREE.LineSegments(
  new THREE.EdgesGeometry(new THREE.BoxGeometry(size.x, size.y, size.z)),
  new THREE.LineBasicMaterial({ color: 0x9aa5b1 }));
boundsBox.position.copy(centre);
scene.add(boundsBox);

// Axes in metres along the bounds' edges: x (east) along the south edge, y (north) along the
// west edge, z up the north-west corner; labels are sprites that always face the camera.
function niceStep(span, count) {
  const raw = span / Math.max(1, count);
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * p).find((v) => v >= raw) || raw;
}
const fmtM = (v) => `${Number.isInteger(v) ? v : v.toFixed(1)} m`;
function label(text, position, scale) {
  const c = document.createElement('canvas');
  c.width = 512; c.height = 128;
  const g = c.getContext('2d');
  g.font = '600 64px system-ui, "DejaVu Sans", sans-serif';
  g.fillStyle = '#3b4450';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, 256, 64);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(c), depthTest: false, transparent: true }));
  sprite.scale.set(scale * 4, scale, 1);
  sprite.position.copy(position);
  sprite.renderOrder = 2;
  sprite.userData.text = text;
  scene.add(sprite);
  return sprite;
}
const axisLabels = [];
const zLabels = [];  // heights of the z labels, for the test of their spacing
let zLabelHeight = 0;
{
  const tick = diag * 0.012, textSize = diag * 0.03, ticks = [];
  const along = (axis, from, to, at) => {
    const step = niceStep(to - from, 5);
    for (let v = Math.ceil(from / step) * step; v <= to + 1e-9; v += step) at(v, step);
  };
  along('x', bmin.x, bmax.x, (v) => {
    ticks.push(v, bmin.y, bmin.z, v, bmin.y - tick, bmin.z);
    axisLabels.push(label(fmtM(v), new THREE.Vector3(v, bmin.y - 3 * tick, bmin.z), textSize));
  });
  along('y', bmin.y, bmax.y, (v) => {
    ticks.push(bmin.x, v, bmin.z, bmin.x - tick, v, bmin.z);
    axisLabels.push(label(fmtM(v), new THREE.Vector3(bmin.x - 4 * tick, v, bmin.z), textSize));
  });
  // z: as many labels as fit one above the other, none where the height is a sliver of the
  // diagonal (a long mission's: the altitude chart gives its heights; a label there would sit on
  // the y axis's).
  const zFit = Math.floor(size.z / (1.5 * textSize));
  zLabelHeight = textSize;
  if (size.z > 0 && zFit >= 1) {
    const zStep = Math.max(niceStep(size.z, Math.min(5, zFit)), 1.5 * textSize);
    for (let v = Math.ceil(bmin.z / zStep) * zStep; v <= bmax.z + 1e-9; v += zStep) {
      if (v === bmin.z) continue;  // the y axis labels the corner
      ticks.push(bmin.x, bmax.y, v, bmin.x - tick, bmax.y, v);
      zLabels.push(v);
      axisLabels.push(label(fmtM(v), new THREE.Vector3(bmin.x - 5 * tick, bmax.y, v), textSize));
    }
  }
  axisLabels.push(label('x, east', new THREE.Vector3(centre.x, bmin.y - 7 * tick, bmin.z), textSize * 1.1));
  axisLabels.push(label('y, north', new THREE.Vector3(bmin.x - 9 * tick, centre.y, bmin.z), textSize * 1.1));
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(ticks, 3));
  scene.add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x59626d })));
}

if (data.terrain) {
  // Each cell is a flat column (the world's model): its top, and the walls down to its lower
  // neighbours and to the floor at the edges, so no gap shows between cells of other heights.
  const t = data.terrain;
  const positions = [];
  const colours = [];
  const hmax = t.heights.reduce((m, h) => Math.max(m, h - bmin.z), 1e-9);  // no spread: 250 k cells overflow the stack
  const lo = new THREE.Color(0xc9bfa6);
  const hi = new THREE.Color(terrainBrown);
  const wall = new THREE.Color(0x9c8b6c);
  const floor = bmin.z;
  const height = (i, j) => (i < 0 || j < 0 || i >= t.nx || j >= t.ny ? floor : Math.max(floor, t.heights[j * t.nx + i]));
  const quad = (a, b, c, d, col) => {
    positions.push(...a, ...b, ...c, ...a, ...c, ...d);
    for (let k = 0; k < 6; k++) colours.push(col.r, col.g, col.b);
  };
  for (let j = 0; j < t.ny; j++) {
    for (let i = 0; i < t.nx; i++) {
      const h = height(i, j);
      const x0 = t.origin[0] + i * t.cell, y0 = t.origin[1] + j * t.cell;
      const x1 = x0 + t.cell, y1 = y0 + t.cell;
      quad([x0, y0, h], [x1, y0, h], [x1, y1, h], [x0, y1, h], lo.clone().lerp(hi, Math.max(0, h - floor) / hmax));
      const e = height(i + 1, j), w = height(i - 1, j), n = height(i, j + 1), s = height(i, j - 1);
      if (e < h) quad([x1, y0, e], [x1, y1, e], [x1, y1, h], [x1, y0, h], wall);
      if (w < h) quad([x0, y1, w], [x0, y0, w], [x0, y0, h], [x0, y1, h], wall);
      if (n < h) quad([x1, y1, n], [x0, y1, n], [x0, y1, h], [x1, y1, h], wall);
      if (s < h) quad([x0, y0, s], [x1, y0, s], [x1, y0, h], [x0, y0, h], wall);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
  g.computeVertexNormals();
  scene.add(new THREE.Mesh(g, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide })));
  // The floor beyond the grid.
  const ground = new THREE.Mesh(new THREE.PlaneGeometry(size.x, size.y),
    new THREE.MeshLambertMaterial({ color: 0xe2e0d8, side: THREE.DoubleSide }));
  ground.position.set(centre.x, centre.y, bmin.z - 1e-3 * diag);
  scene.add(ground);
} else {
  const ground = new THREE.Mesh(new THREE.PlaneGeometry(size.x, size.y),
    new THREE.MeshLambertMaterial({ color: 0xe2e0d8, side: THREE.DoubleSide }));
  ground.position.set(centre.x, centre.y, bmin.z);
  scene.add(ground);
}

// Obstacles grey; airspace translucent: no-fly zones red, the world outside the fence amber.
const solidLook = {
  obstacle: [new THREE.MeshLambertMaterial({ color: 0xa4abb5, transparent: true, opacity: 0.85 }),
    new THREE.LineBasicMaterial({ color: 0x59626d })],
  airspace: [new THREE.MeshLambertMaterial({ color: 0xdc2626, transparent: true, opacity: 0.25, depthWrite: false }),
    new THREE.LineBasicMaterial({ color: 0xb91c1c })],
  fence: [new THREE.MeshLambertMaterial({ color: 0xd97706, transparent: true, opacity: 0.15, depthWrite: false }),
    new THREE.LineBasicMaterial({ color: 0xb45309 })],
};
const zones = { airspace: 0, fence: 0, named: 0 };
let solidKind = 'obstacle';
function addSolid(geometry, position) {
  const [material, edges] = solidLook[solidKind] || solidLook.obstacle;
  const m = new THREE.Mesh(geometry, material);
  m.position.copy(position);
  scene.add(m);
  const e = new THREE.LineSegments(new THREE.EdgesGeometry(geometry, 30), edges);
  e.position.copy(position);
  scene.add(e);
}
// A zone's name over its top, at its middle.
function zoneLabel(o) {
  const c = o.center || (o.min && o.max ? o.min.map((v, k) => 0.5 * (v + o.max[k])) : null) ||
    o.polygon.reduce((a, [x, y]) => [a[0] + x / o.polygon.length, a[1] + y / o.polygon.length], [0, 0]);
  const top = o.z_max ?? (o.max ? o.max[2] : (o.center ? o.center[2] + o.radius : bmax.z));
  label(o.id, new THREE.Vector3(c[0], c[1], Math.min(top, bmax.z)), diag * 0.02);
  zones.named++;
}
for (const o of data.obstacles) {
  solidKind = o.kind || 'obstacle';
  if (solidKind in zones) zones[solidKind]++;
  if (solidKind === 'airspace' && o.id) zoneLabel(o);
  if (o.shape === 'box') {
    const a = new THREE.Vector3(...o.min), b = new THREE.Vector3(...o.max);
    addSolid(new THREE.BoxGeometry(b.x - a.x, b.y - a.y, b.z - a.z), a.clone().add(b).multiplyScalar(0.5));
  } else if (o.shape === 'cylinder') {
    const g = new THREE.CylinderGeometry(o.radius, o.radius, o.z_max - o.z_min, 48);
    g.rotateX(Math.PI / 2);
    addSolid(g, new THREE.Vector3(o.center[0], o.center[1], 0.5 * (o.z_min + o.z_max)));
  } else if (o.shape === 'sphere') {
    addSolid(new THREE.SphereGeometry(o.radius, 32, 16), new THREE.Vector3(...o.center));
  } else if (o.shape === 'prism') {
    const shape = new THREE.Shape(o.polygon.map(([x, y]) => new THREE.Vector2(x, y)));
    const g = new THREE.ExtrudeGeometry(shape, { depth: o.z_max - o.z_min, bevelEnabled: false });
    addSolid(g, new THREE.Vector3(0, 0, o.z_min));
  }
}
const marker = diag * 0.006;
const shellMaterials = [0.22, 0.12, 0.06].map((opacity) =>
  new THREE.MeshBasicMaterial({ color: 0xc2410c, transparent: true, opacity, depthWrite: false, side: THREE.DoubleSide }));
let shellCount = 0;
for (const r of data.threats) {
  const m = new THREE.Mesh(new THREE.OctahedronGeometry(marker * 1.5),
    new THREE.MeshLambertMaterial({ color: 0x7a4a00 }));
  m.position.set(...r.position);
  scene.add(m);
  r.shells_m.forEach((radius, k) => {
    if (!(radius > 0) || radius > 2 * diag) return;
    const shell = new THREE.Mesh(new THREE.SphereGeometry(radius, 40, 20), shellMaterials[k]);
    shell.position.set(...r.position);
    scene.add(shell);
    // The shell's equator, drawn so its reach reads from above too.
    const circle = Array.from({ length: 97 }, (_, a) =>
      new THREE.Vector3(radius * Math.cos(Math.PI * a / 48), radius * Math.sin(Math.PI * a / 48), 0));
    const ring = new THREE.Line(new THREE.BufferGeometry().setFromPoints(circle), new THREE.LineBasicMaterial({ color: 0xc2410c }));
    ring.position.set(...r.position);
    scene.add(ring);
    shellCount++;
  });
}
// The mission's places: via points in order, task points with their radius, the runway; each
// UAV's start (a cube) and goal (a ring) in its colour, drawn for failed UAVs too (with the
// routes: the routes toggle shows and hides the UAVs' layer).
function placeLabel(text, position) { label(text, position, diag * 0.02); }
const drawn = { starts: 0, goals: 0, viaPoints: 0, taskPoints: 0, runway: false };
const routeGroup = new THREE.Group();
scene.add(routeGroup);
(data.via_points || []).forEach((p, k) => {
  const m = new THREE.Mesh(new THREE.OctahedronGeometry(marker * 1.6), new THREE.MeshLambertMaterial({ color: 0x6d28d9 }));
  m.position.set(...p);
  scene.add(m);
  placeLabel(`V${k + 1}`, new THREE.Vector3(p[0], p[1], p[2] + 4 * marker));
  drawn.viaPoints++;
});
(data.task_points || []).forEach((tp, k) => {
  const [x, y, z] = tp.position;
  const ring = Array.from({ length: 97 }, (_, a) =>
    new THREE.Vector3(x + tp.radius_m * Math.cos(Math.PI * a / 48), y + tp.radius_m * Math.sin(Math.PI * a / 48), z));
  scene.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(ring), new THREE.LineBasicMaterial({ color: 0x0f766e })));
  const m = new THREE.Mesh(new THREE.OctahedronGeometry(marker * 1.6), new THREE.MeshLambertMaterial({ color: 0x0f766e }));
  m.position.set(x, y, z);
  scene.add(m);
  placeLabel(`T${k + 1}`, new THREE.Vector3(x, y, z + 4 * marker));
  drawn.taskPoints++;
});
if (data.airfield) {
  const a = data.airfield, h = a.runway_heading_deg * Math.PI / 180;
  const width = Math.max(60, 2 * marker);  // the contract's runway: 30 m either side of the centreline
  const strip = new THREE.Mesh(new THREE.BoxGeometry(a.runway_length_m, width, Math.max(1, marker * 0.2)),
    new THREE.MeshLambertMaterial({ color: 0x374151 }));
  strip.rotation.z = h;
  strip.position.set(a.position[0] + 0.5 * a.runway_length_m * Math.cos(h), a.position[1] + 0.5 * a.runway_length_m * Math.sin(h),
    a.position[2]);
  scene.add(strip);
  placeLabel('runway', new THREE.Vector3(a.position[0], a.position[1], a.position[2] + 4 * marker));
  drawn.runway = true;
}
for (const u of data.uavs) {
  const colour = new THREE.Color(u.colour);
  const body = Math.max(u.radius, marker) * 2.2;
  if (u.start) {
    const cube = new THREE.Mesh(new THREE.BoxGeometry(body, body, body), new THREE.MeshLambertMaterial({ color: colour }));
    cube.position.set(...u.start);
    routeGroup.add(cube);
    drawn.starts++;
  }
  if (u.goal) {
    const ring = new THREE.Mesh(new THREE.TorusGeometry(body, body * 0.18, 8, 32), new THREE.MeshBasicMaterial({ color: colour }));
    ring.position.set(...u.goal);
    routeGroup.add(ring);
    drawn.goals++;
  }
}

function movingAt(m, t) {
  return m.trajectory ? positionAt(m.trajectory, t) : [0, 1, 2].map((k) => m.position[k] + t * m.velocity[k]);
}
const trackMaterial = new THREE.LineDashedMaterial({ color: 0x6b7280, dashSize: diag * 0.01, gapSize: diag * 0.006 });
const movers = data.moving.map((m) => {
  const mesh = new THREE.Mesh(new THREE.SphereGeometry(Math.max(m.radius, marker), 24, 12),
    new THREE.MeshLambertMaterial({ color: 0x6b7280, transparent: true, opacity: 0.6 }));
  scene.add(mesh);
  // Its track over the plan's time span: the trajectory's rows, or the straight constant-velocity line.
  const span = data.t_end_s || 0;
  const pts = m.trajectory ? m.trajectory.filter(([t]) => t <= span).map(([, x, y, z]) => new THREE.Vector3(x, y, z)) : [];
  if (!m.trajectory || pts.length === 0 || m.trajectory[0][0] > 0) pts.unshift(new THREE.Vector3(...movingAt(m, 0)));
  pts.push(new THREE.Vector3(...movingAt(m, span)));
  const track = new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts), trackMaterial);
  track.computeLineDistances();
  scene.add(track);
  return { m, mesh };
});

// The rows of a trajectory that a drawn line needs: Douglas-Peucker within `tol` metres (a long
// mission's rows every second are mostly straight runs; drawing all of them stalls the page).
function simplified(traj, tol) {
  if (traj.length <= 2) return traj;
  const keep = new Uint8Array(traj.length);
  keep[0] = keep[traj.length - 1] = 1;
  const stack = [[0, traj.length - 1]];
  while (stack.length) {
    const [a, b] = stack.pop();
    const [, ax, ay, az] = traj[a], [, bx, by, bz] = traj[b];
    const dx = bx - ax, dy = by - ay, dz = bz - az, len2 = dx * dx + dy * dy + dz * dz;
    let worst = -1, at = -1;
    for (let i = a + 1; i < b; ++i) {
      const [, x, y, z] = traj[i];
      const s = len2 > 0 ? Math.min(1, Math.max(0, ((x - ax) * dx + (y - ay) * dy + (z - az) * dz) / len2)) : 0;
      const ex = x - ax - s * dx, ey = y - ay - s * dy, ez = z - az - s * dz, d = ex * ex + ey * ey + ez * ez;
      if (d > worst) { worst = d; at = i; }
    }
    if (at >= 0 && worst > tol * tol) { keep[at] = 1; stack.push([a, at], [at, b]); }
  }
  return traj.filter((_, i) => keep[i]);
}

// Routes as screen-space wide lines, and one marker per UAV that the time slider moves.
const lineMaterials = [];
const uavMarkers = [];
for (const u of data.uavs) {
  if (u.trajectory.length < 2) continue;
  const pts = [];
  for (const [, x, y, z] of simplified(u.trajectory, diag * 1e-4)) pts.push(x, y, z);
  const g = new LineGeometry();
  g.setPositions(pts);
  const mat = new LineMaterial({ color: new THREE.Color(u.colour), linewidth: 3, worldUnits: false });
  lineMaterials.push(mat);
  routeGroup.add(new Line2(g, mat));
  const dot = new THREE.Mesh(new THREE.SphereGeometry(Math.max(u.radius, marker), 20, 10),
    new THREE.MeshBasicMaterial({ color: new THREE.Color(u.colour) }));
  routeGroup.add(dot);
  uavMarkers.push({ u, dot });
}

// A flight of the plan (uavplan fly), when given: each UAV's flown track dashed in its colour.
const colourById = Object.fromEntries(data.uavs.map((u) => [u.id, u.colour]));
let flownTracks = 0;
for (const f of data.flown || []) {
  if (f.trajectory.length < 2 || !(f.id in colourById)) continue;
  const pts = [];
  for (const [, x, y, z] of simplified(f.trajectory, diag * 1e-4)) pts.push(x, y, z);
  const g = new LineGeometry();
  g.setPositions(pts);
  const mat = new LineMaterial({ color: new THREE.Color(colourById[f.id]), linewidth: 2, worldUnits: false,
    dashed: true, dashSize: diag * 0.01, gapSize: diag * 0.006 });
  lineMaterials.push(mat);
  const line = new Line2(g, mat);
  line.computeLineDistances();
  routeGroup.add(line);
  flownTracks++;
}
if (flownTracks > 0) legend.append(el('span', { class: 'key dashed', style: { '--c': '#6b7280' } }, 'flown (in the UAV\'s colour)'));

function positionAt(traj, t) {
  if (t <= traj[0][0]) return traj[0].slice(1);
  const last = traj[traj.length - 1];
  if (t >= last[0]) return last.slice(1);
  let lo = 0, hi = traj.length - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (traj[mid][0] <= t) lo = mid; else hi = mid;
  }
  const a = traj[lo], b = traj[hi];
  const s = (t - a[0]) / (b[0] - a[0] || 1);
  return [1, 2, 3].map((k) => a[k] + s * (b[k] - a[k]));
}

// A UAV's state at t: arrived once it is at its goal to stay (its arrival_s), waiting where it
// holds still before that (before its departure, or for the others), else flying.
function stateAt(u, t) {
  if (typeof u.arrival_s === 'number' && t >= u.arrival_s) return 'arrived';
  const traj = u.trajectory;
  if (traj.length < 2 || t >= traj[traj.length - 1][0]) return traj.length < 2 ? 'not flown' : 'arrived';
  const a = positionAt(traj, t), b = positionAt(traj, Math.min(t + 1e-3, traj[traj.length - 1][0]));
  return Math.hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) > 1e-9 ? 'flying' : 'waiting';
}
function statesText(t) {
  const n = { flying: 0, waiting: 0, arrived: 0 };
  for (const u of data.uavs) if (u.trajectory.length >= 2) n[stateAt(u, t)] += 1;
  return Object.entries(n).filter(([, k]) => k > 0).map(([s, k]) => `${k} ${s}`).join(', ');
}

// A phased mission's phase at time t (the last one holds to the end).
const phases = data.phases || [];
function phaseAt(t) {
  return phases.find((p) => t >= p.start_s && t <= p.end_s) || null;
}

let currentTime = 0;
function setTime(t) {
  currentTime = Math.min(Math.max(0, t), data.t_end_s || 0);
  slider.value = String(currentTime);
  const phase = phaseAt(currentTime);
  timeLabel.textContent = `t = ${currentTime.toFixed(1)} s${phase ? ` \u00b7 ${phase.name}` : ''}`;
  statesLabel.textContent = statesText(currentTime);
  for (const { u, dot } of uavMarkers) dot.position.set(...positionAt(u.trajectory, currentTime));
  for (const { m, mesh } of movers) mesh.position.set(...movingAt(m, currentTime));
  for (const c of charts) c.setCursor({ left: c.valToPos(currentTime, 'x'), top: 10 }, false);
}

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h, true);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
  for (const m of lineMaterials) m.resolution.set(w, h);
  for (const c of [...charts, ...profileCharts]) c.setSize({ width: chartWidth(), height: c.height });
}

let playing = false;
let lastFrame = 0;
play.addEventListener('click', () => {
  playing = !playing;
  play.textContent = playing ? 'Pause' : 'Play';
  if (playing && currentTime >= (data.t_end_s || 0)) setTime(0);
  lastFrame = performance.now();
});
slider.addEventListener('input', () => setTime(parseFloat(slider.value)));
routesToggle.addEventListener('change', () => { routeGroup.visible = routesToggle.checked; });

// ---- charts ----
const charts = [];
const chartWidth = () => Math.max(280, Math.floor(right.clientWidth || 400));
right.append(el('h2', {}, 'Altitude, speed and separation over time'));
const series = data.series;
const colourOf = Object.fromEntries(data.uavs.map((u) => [u.id, u.colour]));
// Phases as coloured bands behind the series, each named at its top left.
const phaseColours = ['rgba(59,130,246,0.10)', 'rgba(16,185,129,0.10)', 'rgba(245,158,11,0.12)', 'rgba(139,92,246,0.10)', 'rgba(239,68,68,0.10)'];
const chartsBanded = new Set();
function drawPhaseBands(u) {
  if (!phases.length) return;
  chartsBanded.add(u);
  const { ctx } = u;
  const { top, height } = u.bbox;
  ctx.save();
  ctx.font = `${Math.round(10 * devicePixelRatio)}px sans-serif`;
  ctx.textBaseline = 'top';
  phases.forEach((p, k) => {
    const x0 = u.valToPos(p.start_s, 'x', true), x1 = u.valToPos(p.end_s, 'x', true);
    ctx.fillStyle = phaseColours[k % phaseColours.length];
    ctx.fillRect(x0, top, Math.max(1, x1 - x0), height);
    ctx.fillStyle = '#374151';
    if (x1 - x0 > ctx.measureText(p.name).width + 4) ctx.fillText(p.name, x0 + 3, top + 3);
  });
  ctx.restore();
}
function addChart(title, key, unit, extra, opts = {}) {
  const host = el('div', { class: 'chart' });
  right.append(host);
  const map = opts.map || ((v) => v);
  const cols = [series.t_s, ...series.uavs.map((s) => s[key].map((v) => (v == null ? null : map(v))))];
  const sers = [{ label: 't (s)' }, ...series.uavs.map((s) => ({ label: s.id, stroke: colourOf[s.id], width: 1.5 }))];
  if (extra) { cols.push(series.t_s.map(() => extra.value)); sers.push(extra.series); }
  const chart = new uPlot({
    title: `${title} (${unit})`, width: chartWidth(), height: 170, series: sers,
    scales: { x: { time: false }, ...(opts.scales || {}) }, axes: [{ label: 't (s)' }, { size: 64 }],
    legend: { show: series.uavs.length <= 12 },
    hooks: { drawClear: [drawPhaseBands] },
  }, cols, host);
  charts.push(chart);
  return chart;
}
if (series.t_s.length > 0) {
  addChart('Altitude', 'altitude_m', 'm');
  addChart('Speed', 'speed_mps', 'm/s');
  if (series.uavs.length > 1) {
    // A log scale shows close approaches next to the separation; distances under 1 cm are drawn at 1 cm.
    addChart(data.mission === 'formation_mission' ? 'Spacing: distance to the nearest UAV in the air' : 'Distance to the nearest UAV',
      'nearest_m', 'm, log scale',
      data.separation_m > 0 ? { value: data.separation_m, series: { label: 'separation', stroke: '#000', dash: [6, 4], width: 1 } } : null,
      { map: (v) => Math.max(v, 0.01), scales: { y: { distr: 3, log: 10 } } });
  }
} else {
  right.append(el('p', { class: 'muted' }, 'No trajectory to chart.'));
}

// Height above ground along the route of the UAV chosen: its altitude, the ground under it
// (filled) and the difference.
const profiled = data.uavs.filter((u) => u.profile);
const profileCharts = [];
if (profiled.length) {
  const pick = el('select', { id: 'profile-uav' }, ...profiled.map((u) => el('option', { value: u.id }, u.id)));
  right.append(el('h2', {}, 'Height above ground along the route of ', pick));
  const host = el('div', { class: 'chart', id: 'profile' });
  right.append(host);
  const draw = () => {
    const u = profiled.find((x) => x.id === pick.value);
    const p = u.profile;
    const agl = p.z_m.map((z, k) => z - p.ground_m[k]);
    const sers = [{ label: 'distance (m)' },
      { label: 'ground', stroke: terrainBrown, fill: 'rgba(140, 123, 94, 0.35)', width: 1 },
      { label: `${u.id} altitude`, stroke: u.colour, width: 2 },
      { label: 'height above ground', stroke: u.colour, dash: [5, 4], width: 1 }];
    const cols = [p.s_m, p.ground_m, p.z_m, agl];
    if (u.min_agl > 0) { sers.push({ label: 'min_agl', stroke: '#8a1420', dash: [2, 3], width: 1 }); cols.push(p.s_m.map(() => u.min_agl)); }
    if (u.max_agl != null) { sers.push({ label: 'max_agl', stroke: '#8a1420', dash: [6, 3], width: 1 }); cols.push(p.s_m.map(() => u.max_agl)); }
    for (const c of profileCharts.splice(0)) c.destroy();
    profileCharts.push(new uPlot({
      title: `${u.id}: altitude and ground (m) over distance flown (m)`, width: chartWidth(), height: 190, series: sers,
      scales: { x: { time: false } }, axes: [{ label: 'distance flown (m)', space: 90 }, {}],  // room for 1,750,000
    }, cols, host));
  };
  pick.addEventListener('change', draw);
  draw();
}

// ---- metrics and verification ----
left.append(el('h2', {}, 'Metrics per UAV'));
const cols = [['length_m', 'length (m)'], ['departure_s', 'departure (s)'], ['flight_time_s', 'flight time (s)'],
  ['arrival_s', 'arrival (s)'], ['max_turn_deg', 'max turn (deg)'], ['max_climb_deg', 'max climb (deg)'],
  ['kept_off_m', 'kept off obstacles (m): radius + clearance'], ['min_gap_m', 'min gap to obstacles (m)'], ['min_agl_m', 'min AGL (m)'],
  ['reversals', 'reversals']];
if (data.uavs.some((u) => 'time_in_shape_s' in u.metrics)) cols.push(['time_in_shape_s', 'in shape (s)'], ['breaks', 'breaks'], ['backing_up_m', 'backing up (m)']);
const table = el('table', { id: 'uav-metrics' },
  el('tr', {}, el('th', {}, 'uav'), el('th', {}, 'status'), ...cols.map(([, h]) => el('th', {}, h))));
for (const u of data.uavs)
  table.append(el('tr', {}, el('td', {}, u.id), el('td', {}, u.status), ...cols.map(([c]) => el('td', {}, metricText(u, c)))));
left.append(el('div', { class: 'scroll' }, table));
// The route's metrics leave the vertical take-off and landing legs out (evaluation/metrics.cpp).
left.append(el('p', { class: 'muted' }, 'max turn, max climb and min AGL: the route between take-off and landing (the vertical legs are left out).'));
// No margin is added by default (docs/decisions/0013): say so where the routes keep only the body.
const bare = data.uavs.filter((u) => !(u.clearance > 0)).map((u) => u.id);
if (bare.length)
  left.append(el('p', { class: 'muted', id: 'clearance-note' }, `No clearance set for ${bare.join(', ')}: routes keep only the body's radius from ` +
    'obstacles and airspace zones (the contract; min gap shows how close each comes). Set clearance for room for the autopilot\'s tracking.'));
left.append(el('h2', {}, 'Plan metrics'));
const planTable = el('table', { id: 'plan-metrics' });
for (const [k, v] of Object.entries(data.metrics)) planTable.append(el('tr', {}, el('td', {}, k), el('td', {}, fmt(v, 4))));
left.append(planTable);
left.append(el('h2', {}, 'Verification'));
if (holds) left.append(el('p', {}, 'Every check holds: bounds, obstacles, terrain, moving obstacles, separation, turn and climb limits, speed, via points' +
  (data.airfield ? ', the runway one UAV at a time, every UAV landed on it.' : '.')));
else left.append(el('ul', { class: 'violations' }, ...data.violations.map((v) => el('li', {}, v))));
for (const u of data.uavs) if (u.message) left.append(el('p', { class: 'muted' }, `${u.id}: ${u.message}`));

// North: the screen direction of +y at the view's centre. Scale: metres per pixel there, a round
// length drawn as a bar of about 120 px.
function toScreen(v) {
  const p = v.clone().project(camera);
  return [(p.x + 1) * 0.5 * view.clientWidth, (1 - p.y) * 0.5 * view.clientHeight];
}
function updateOverlays() {
  const t = controls.target;
  const [ax, ay] = toScreen(t);
  const [nx, ny] = toScreen(t.clone().add(new THREE.Vector3(0, 0.05 * diag, 0)));
  north.style.transform = `rotate(${Math.atan2(nx - ax, ay - ny)}rad)`;
  const side = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0).normalize();
  const [rx, ry] = toScreen(t.clone().addScaledVector(side, 0.05 * diag));
  const pxPerM = Math.hypot(rx - ax, ry - ay) / (0.05 * diag);
  if (!(pxPerM > 0)) return;
  const metres = niceStep(120 / pxPerM, 1);
  scaleBar.firstChild.style.width = `${Math.round(metres * pxPerM)}px`;
  scaleBar.lastChild.textContent = fmtM(metres);
}

// ---- run ----
resize();
window.addEventListener('resize', resize);
setTime(0);
function frame(now) {
  if (playing) {
    const span = data.t_end_s || 0;
    setTime(currentTime + ((now - lastFrame) / 1000) * (span / 20));  // the whole plan in 20 s
    if (currentTime >= span) { playing = false; play.textContent = 'Play'; }
  }
  lastFrame = now;
  controls.update();
  updateOverlays();
  renderer.render(scene, camera);
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);

// For tests and scripting: the page's state and a few switches.
window.uavplanReport = {
  ready: true,
  uavs: data.uavs.length,
  radarShells: shellCount,
  // Airspace drawn apart from obstacles: no-fly zones and the fence's outside, zones named.
  zones,
  movingTracks: movers.length,
  flownTracks,
  phases: phases.length,
  chartsWithPhaseBands: () => chartsBanded.size,
  timeLabel: () => timeLabel.textContent,
  uavStates: (t) => data.uavs.map((u) => stateAt(u, t)),
  axisLabels: axisLabels.length,
  // What the mission asks for, as drawn: starts, goals, via points, task points, the runway; and
  // the smallest gap between two z labels, in label heights (under 1: they run together).
  drawn,
  zLabelGap: () => {
    const zs = [...zLabels].sort((a, b) => a - b);
    let gap = Infinity;
    for (let i = 1; i < zs.length; i++) gap = Math.min(gap, (zs[i] - zs[i - 1]) / zLabelHeight);
    return gap;
  },
  // Axis labels drawn under the north arrow or the scale bar (their screen boxes overlap).
  labelsUnderOverlays: () => {
    const boxes = [north, scaleBar].map((o) => o.getBoundingClientRect());
    const origin = view.getBoundingClientRect();
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0).normalize();
    const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1).normalize();
    const under = [];
    for (const s of axisLabels) {
      const corners = [[-1, -1], [1, 1]].map(([a, b]) => toScreen(s.position.clone()
        .addScaledVector(right, (a * s.scale.x) / 2).addScaledVector(up, (b * s.scale.y) / 2)));
      const [x0, x1] = [corners[0][0], corners[1][0]].sort((a, b) => a - b).map((v) => v + origin.left);
      const [y0, y1] = [corners[0][1], corners[1][1]].sort((a, b) => a - b).map((v) => v + origin.top);
      if (boxes.some((r) => x0 < r.right && x1 > r.left && y0 < r.bottom && y1 > r.top)) under.push(s.userData.text);
    }
    return under;
  },
  setTime,
  setRoutesVisible(v) { routesToggle.checked = v; routeGroup.visible = v; renderer.render(scene, camera); },
};
