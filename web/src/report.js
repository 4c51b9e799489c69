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
    if (k === 'style') Object.assign(e.style, v);
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c instanceof Node ? c : document.createTextNode(String(c)));
  return e;
}

const fmt = (v, d = 3) => (typeof v === 'number' ? (Number.isInteger(v) ? String(v) : v.toFixed(d)) : v ?? '-');

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
const play = el('button', { type: 'button', id: 'play' }, 'Play');
const routesToggle = el('input', { type: 'checkbox', checked: '', id: 'routes' });
left.append(view,
  el('div', { class: 'controls' }, play, slider, timeLabel,
    el('label', {}, routesToggle, ' routes')));
const legend = el('div', { class: 'legend' });
for (const u of data.uavs) legend.append(el('span', { style: { '--c': u.colour } }, `${u.id} (${u.status})`));
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

if (data.terrain) {
  const t = data.terrain;
  const positions = [];
  const colours = [];
  const hmax = Math.max(1e-9, ...t.heights);
  const lo = new THREE.Color(0xc9bfa6);
  const hi = new THREE.Color(0x8c7b5e);
  for (let j = 0; j < t.ny; j++) {
    for (let i = 0; i < t.nx; i++) {
      const h = t.heights[j * t.nx + i];
      if (!(h > -1e300)) continue;
      const x0 = t.origin[0] + i * t.cell, y0 = t.origin[1] + j * t.cell;
      const x1 = x0 + t.cell, y1 = y0 + t.cell;
      positions.push(x0, y0, h, x1, y0, h, x1, y1, h, x0, y0, h, x1, y1, h, x0, y1, h);
      const c = lo.clone().lerp(hi, Math.max(0, h) / hmax);
      for (let k = 0; k < 6; k++) colours.push(c.r, c.g, c.b);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
  g.computeVertexNormals();
  scene.add(new THREE.Mesh(g, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide })));
} else {
  const ground = new THREE.Mesh(new THREE.PlaneGeometry(size.x, size.y),
    new THREE.MeshLambertMaterial({ color: 0xe2e0d8, side: THREE.DoubleSide }));
  ground.position.set(centre.x, centre.y, bmin.z);
  scene.add(ground);
}

const obstacleMaterial = new THREE.MeshLambertMaterial({ color: 0xa4abb5, transparent: true, opacity: 0.85 });
const edgeMaterial = new THREE.LineBasicMaterial({ color: 0x59626d });
function addSolid(geometry, position) {
  const m = new THREE.Mesh(geometry, obstacleMaterial);
  m.position.copy(position);
  scene.add(m);
  const e = new THREE.LineSegments(new THREE.EdgesGeometry(geometry, 30), edgeMaterial);
  e.position.copy(position);
  scene.add(e);
}
for (const o of data.obstacles) {
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
for (const r of data.threats) {
  const m = new THREE.Mesh(new THREE.OctahedronGeometry(marker * 1.5),
    new THREE.MeshLambertMaterial({ color: 0x7a4a00 }));
  m.position.set(...r.position);
  scene.add(m);
}
const movers = data.moving.map((m) => {
  const mesh = new THREE.Mesh(new THREE.SphereGeometry(Math.max(m.radius, marker), 24, 12),
    new THREE.MeshLambertMaterial({ color: 0x6b7280, transparent: true, opacity: 0.6 }));
  scene.add(mesh);
  return { m, mesh };
});

// Routes as screen-space wide lines, and one marker per UAV that the time slider moves.
const routeGroup = new THREE.Group();
scene.add(routeGroup);
const lineMaterials = [];
const uavMarkers = [];
for (const u of data.uavs) {
  if (u.trajectory.length < 2) continue;
  const pts = [];
  for (const [, x, y, z] of u.trajectory) pts.push(x, y, z);
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

let currentTime = 0;
function setTime(t) {
  currentTime = Math.min(Math.max(0, t), data.t_end_s || 0);
  slider.value = String(currentTime);
  timeLabel.textContent = `t = ${currentTime.toFixed(1)} s`;
  for (const { u, dot } of uavMarkers) dot.position.set(...positionAt(u.trajectory, currentTime));
  for (const { m, mesh } of movers)
    mesh.position.set(...(m.trajectory ? positionAt(m.trajectory, currentTime)
                                        : [0, 1, 2].map((k) => m.position[k] + currentTime * m.velocity[k])));
  for (const c of charts) c.setCursor({ left: c.valToPos(currentTime, 'x'), top: 10 }, false);
}

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h, true);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
  for (const m of lineMaterials) m.resolution.set(w, h);
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
right.append(el('h2', {}, 'Altitude, speed and separation over time'));
const series = data.series;
function addChart(title, key, unit, extra) {
  const host = el('div', { class: 'chart' });
  right.append(host);
  const cols = [series.t_s, ...series.uavs.map((s) => s[key])];
  const colourOf = Object.fromEntries(data.uavs.map((u) => [u.id, u.colour]));
  const sers = [{ label: 't (s)' }, ...series.uavs.map((s) => ({ label: s.id, stroke: colourOf[s.id], width: 1.5 }))];
  if (extra) { cols.push(series.t_s.map(() => extra.value)); sers.push(extra.series); }
  const width = Math.max(300, right.clientWidth || 400);
  charts.push(new uPlot({
    title: `${title} (${unit})`, width, height: 170, series: sers,
    scales: { x: { time: false } }, axes: [{ label: 't (s)' }, {}], legend: { show: series.uavs.length <= 12 },
  }, cols, host));
}
if (series.t_s.length > 0) {
  addChart('Altitude', 'altitude_m', 'm');
  addChart('Speed', 'speed_mps', 'm/s');
  if (series.uavs.length > 1) {
    addChart('Distance to the nearest UAV', 'nearest_m', 'm',
      data.separation_m > 0 ? { value: data.separation_m, series: { label: 'separation', stroke: '#000', dash: [6, 4], width: 1 } } : null);
  }
} else {
  right.append(el('p', { class: 'muted' }, 'No trajectory to chart.'));
}

// ---- metrics and verification ----
right.append(el('h2', {}, 'Metrics per UAV'));
const cols = ['length_m', 'flight_time_s', 'max_turn_deg', 'max_climb_deg', 'min_clearance_m'];
const table = el('table', {}, el('tr', {}, el('th', {}, 'uav'), el('th', {}, 'status'), ...cols.map((c) => el('th', {}, c))));
for (const u of data.uavs)
  table.append(el('tr', {}, el('td', {}, u.id), el('td', {}, u.status), ...cols.map((c) => el('td', {}, fmt(u.metrics[c])))));
right.append(table);
right.append(el('h2', {}, 'Plan metrics'));
const planTable = el('table');
for (const [k, v] of Object.entries(data.metrics)) planTable.append(el('tr', {}, el('td', {}, k), el('td', {}, fmt(v, 4))));
right.append(planTable);
right.append(el('h2', {}, 'Verification'));
if (holds) right.append(el('p', {}, 'Every check holds: bounds, obstacles, terrain, moving obstacles, separation, turn and climb limits, speed, via points.'));
else right.append(el('ul', { class: 'violations' }, ...data.violations.map((v) => el('li', {}, v))));
for (const u of data.uavs) if (u.message) right.append(el('p', { class: 'muted' }, `${u.id}: ${u.message}`));

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
  renderer.render(scene, camera);
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);

// For tests and scripting: the page's state and a few switches.
window.uavplanReport = {
  ready: true,
  uavs: data.uavs.length,
  setTime,
  setRoutesVisible(v) { routesToggle.checked = v; routeGroup.visible = v; renderer.render(scene, camera); },
};
