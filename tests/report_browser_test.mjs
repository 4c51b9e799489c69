// Opens an HTML report in headless Chromium (Debian's, driven by playwright-core) in a 1400 px
// window, fails on any console error or page error, and checks what a pilot looks for:
//  - a screenshot of the 3-D view shows the routes: pixels of the UAVs' colours are there with
//    the routes shown and (nearly) gone with them hidden, so a blank or broken canvas fails;
//  - every metric cell holds a value or says why it has none (never "-", empty, NaN);
//  - a legend entry per UAV in its colour, axes labelled in metres, a north arrow, a scale bar,
//    the altitude / speed / separation (log) charts and the height-above-ground profile;
//  - radar shells and moving-obstacle tracks when the scenario has them; a flight's tracks when
//    one is given (FLOWN_TRACKS: how many);
//  - a phased mission's phases as bands on the time charts, named beside the time slider;
//  - the page is no wider than the window.
// The screenshot written is of the whole page.
//   node report_browser_test.mjs REPORT.html NODE_MODULES_DIR SCREENSHOT.png
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [report, nodeModules, shotPath] = process.argv.slice(2);
if (!report || !nodeModules || !shotPath) {
  console.error('usage: node report_browser_test.mjs REPORT.html NODE_MODULES_DIR SCREENSHOT.png');
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(nodeModules), 'index.js'));
const { chromium } = require('playwright-core');
const { PNG } = require('pngjs');

const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
if (!fs.existsSync(executablePath)) {
  console.error(`report_browser_test: no Chromium at ${executablePath} (scripts/install-deps.sh installs it)`);
  process.exit(1);
}

function fail(msg) {
  console.error(`report_browser_test: FAIL: ${msg}`);
  process.exitCode = 1;
}

const hex = (c) => [1, 3, 5].map((i) => parseInt(c.slice(i, i + 2), 16));
// Pixels within `tol` of any of the colours, per channel.
function countColoured(pngBuffer, colours, tol = 40) {
  const png = PNG.sync.read(pngBuffer);
  const rgb = colours.map(hex);
  let n = 0;
  for (let i = 0; i < png.data.length; i += 4) {
    const r = png.data[i], g = png.data[i + 1], b = png.data[i + 2];
    for (const [cr, cg, cb] of rgb) {
      if (Math.abs(r - cr) <= tol && Math.abs(g - cg) <= tol && Math.abs(b - cb) <= tol) { n++; break; }
    }
  }
  return n;
}

const browser = await chromium.launch({
  executablePath,
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  await page.goto(pathToFileURL(path.resolve(report)).href, { waitUntil: 'load' });
  await page.waitForFunction(() => window.uavplanReport && window.uavplanReport.ready, null, { timeout: 30000 });
  await page.waitForTimeout(500);  // a few frames

  const colours = await page.evaluate(() =>
    JSON.parse(document.getElementById('uavplan-data').textContent).uavs.filter((u) => u.trajectory.length >= 2).map((u) => u.colour));
  if (colours.length === 0) fail('the report has no route to show');
  const canvas = page.locator('#view canvas');
  const shown = await canvas.screenshot();
  await page.evaluate(() => window.uavplanReport.setRoutesVisible(false));
  await page.waitForTimeout(200);
  const hidden = await canvas.screenshot();
  await page.evaluate(() => window.uavplanReport.setRoutesVisible(true));

  // Per colour: a colour the scene itself shows (a shade of the ground) says nothing about the
  // routes, so only colours nearly absent with the routes hidden count.
  let withRoutes = 0, without = 0, telling = 0;
  for (const c of new Set(colours)) {
    const a = countColoured(shown, [c]), b = countColoured(hidden, [c]);
    if (b > 50) continue;
    telling++;
    withRoutes += a;
    without += b;
  }
  console.log(`route-coloured pixels (${telling} telling colours): ${withRoutes} with routes shown, ${without} hidden`);
  if (telling === 0) fail('every route colour also appears without the routes');
  if (withRoutes < 300) fail(`too few route-coloured pixels (${withRoutes}): the routes are not drawn`);
  if (withRoutes < 5 * Math.max(without, 20)) fail('hiding the routes hardly changes the picture: the colours are not the routes');
  const charts = await page.locator('.uplot').count();
  const info = await page.evaluate(() => {
    const d = JSON.parse(document.getElementById('uavplan-data').textContent);
    const cells = [...document.querySelectorAll('#uav-metrics td, #plan-metrics td')].map((c) => c.textContent.trim());
    const legend = [...document.querySelectorAll('#legend span.uav')].map((s) => [s.textContent, getComputedStyle(s, '::before').backgroundColor]);
    const r = window.uavplanReport;
    return {
      cells, legend, uavs: d.uavs.map((u) => [u.id, u.colour]), radars: d.threats.length, moving: d.moving.length,
      profiled: d.uavs.filter((u) => u.profile).length, shells: r.radarShells, tracks: r.movingTracks, axisLabels: r.axisLabels,
      drawn: r.drawn, zLabelGap: r.zLabelGap(), underOverlays: r.labelsUnderOverlays(), goals: d.uavs.filter((u) => u.goal).length,
      viaPoints: (d.via_points || []).length, taskPoints: (d.task_points || []).length, airfield: !!d.airfield,
      north: !!document.querySelector('#north svg'), scale: document.querySelector('#scalebar span').textContent,
      scaleWidth: document.querySelector('#scalebar .bar').getBoundingClientRect().width,
      logScale: [...document.querySelectorAll('.uplot .u-title')].some((t) => /log scale/.test(t.textContent)),
      flown: d.uavs.filter((u) => (u.trajectory || []).length > 1).length,
      profile: document.querySelectorAll('#profile .uplot').length,
      flownGiven: (d.flown || []).filter((f) => f.trajectory.length > 1).length, flownDrawn: r.flownTracks,
      pageWidth: document.documentElement.scrollWidth, rows: document.querySelectorAll('#uav-metrics tr').length,
      zonesInData: { airspace: d.obstacles.filter((o) => o.kind === 'airspace').length,
        fence: d.obstacles.filter((o) => o.kind === 'fence').length,
        named: d.obstacles.filter((o) => o.kind === 'airspace' && o.id).length },
      zonesDrawn: r.zones, keys: [...document.querySelectorAll('#legend span.key')].map((s) => s.textContent),
      bare: d.uavs.filter((u) => !(u.clearance > 0)).length,
      clearanceNote: document.getElementById('clearance-note')?.textContent || '',
    };
  });
  const expectedCharts = 2 + (info.uavs.length > 1 ? 1 : 0) + (info.profiled ? 1 : 0);
  if (charts < expectedCharts) fail(`expected ${expectedCharts} charts (altitude, speed, separation, height profile), found ${charts}`);
  if (info.rows < 2) fail('the metrics table is empty');
  const bad = info.cells.filter((c) => c === '' || c === '-' || /NaN|undefined|null|not computed/.test(c));
  if (bad.length) fail(`metric cells without a value: ${JSON.stringify(bad)}`);
  const rgb = (h) => `rgb(${hex(h).join(', ')})`;
  for (const [id, colour] of info.uavs) {
    const entry = info.legend.find(([t]) => t.startsWith(`${id} `));
    if (!entry) fail(`no legend entry for ${id}`);
    else if (entry[1] !== rgb(colour)) fail(`legend entry of ${id} is ${entry[1]}, its route is ${rgb(colour)}`);
  }
  if (info.axisLabels < 6) fail(`the 3-D view has ${info.axisLabels} axis labels in metres`);
  if (!info.north) fail('no north arrow');
  if (!/^\d+(\.\d)? m$/.test(info.scale) || !(info.scaleWidth > 20)) fail(`the scale bar says '${info.scale}' over ${info.scaleWidth} px`);
  if (info.flown > 1 && !info.logScale) fail('the separation chart is not on a log scale');
  if (info.profiled && info.profile !== 1) fail('no height-above-ground profile');
  if (info.radars && info.shells < info.radars) fail(`${info.radars} radars but ${info.shells} range shells`);
  if (info.tracks !== info.moving) fail(`${info.moving} moving obstacles but ${info.tracks} tracks`);
  // A flight given (report --flown): every flown track drawn, as many as the caller expects.
  const flownExpected = Number(process.env.FLOWN_TRACKS || 0);
  if (info.flownGiven !== flownExpected || info.flownDrawn !== flownExpected)
    fail(`expected ${flownExpected} flown tracks: ${info.flownGiven} in the data, ${info.flownDrawn} drawn`);
  // What the mission asks for is on the map, for failed UAVs too: every start and goal, the via
  // points, the task points, the runway; the z labels one clear of the next.
  // Airspace apart from obstacles: every no-fly zone and the fence's outside drawn in its own
  // colour with a legend key, every zone named; where no clearance is set the report says so.
  for (const k of ['airspace', 'fence', 'named'])
    if (info.zonesDrawn[k] !== info.zonesInData[k]) fail(`${info.zonesInData[k]} ${k} zones in the data, ${info.zonesDrawn[k]} drawn`);
  if (info.zonesInData.airspace && !info.keys.some((t) => t.startsWith('no-fly zone'))) fail('no legend key for the no-fly zones');
  if (info.zonesInData.fence && !info.keys.some((t) => t.startsWith('outside the geofence'))) fail('no legend key for the fence');
  if (process.env.EXPECT_ZONES && !(info.zonesInData.airspace > 0)) fail('no airspace zone in the data of a scenario with zones');
  if (info.bare && !/^No clearance set for .*docs|^No clearance set for /.test(info.clearanceNote))
    fail(`${info.bare} UAVs without clearance and no note saying so`);
  if (!info.bare && info.clearanceNote) fail('a clearance note where every UAV has one');
  const dr = info.drawn;
  if (dr.starts !== info.uavs.length) fail(`${info.uavs.length} UAVs but ${dr.starts} start markers`);
  if (dr.goals !== info.goals) fail(`${info.goals} goals but ${dr.goals} goal markers`);
  if (dr.viaPoints !== info.viaPoints) fail(`${info.viaPoints} via points but ${dr.viaPoints} drawn`);
  if (dr.taskPoints !== info.taskPoints) fail(`${info.taskPoints} task points but ${dr.taskPoints} drawn`);
  if (dr.runway !== info.airfield) fail(`airfield ${info.airfield} but runway drawn ${dr.runway}`);
  if (info.underOverlays.length) fail(`axis labels under the north arrow or scale bar: ${info.underOverlays.join(', ')}`);
  if (!(info.zLabelGap >= 1)) fail(`z-axis labels overlap (gap ${info.zLabelGap} label heights)`);
  // A phased mission: bands on every time chart, and the phase named beside the time slider.
  const phases = await page.evaluate(() => JSON.parse(document.getElementById('uavplan-data').textContent).phases || []);
  if (phases.length) {
    const banded = await page.evaluate(() => window.uavplanReport.chartsWithPhaseBands());
    const timeCharts = 2 + (info.uavs.length > 1 ? 1 : 0);
    if (banded < timeCharts) fail(`${phases.length} phases but bands on ${banded} of ${timeCharts} time charts`);
    for (const p of phases) {
      const label = await page.evaluate((t) => { window.uavplanReport.setTime(t); return window.uavplanReport.timeLabel(); }, (p.start_s + p.end_s) / 2);
      if (!label.includes(p.name)) fail(`at t = ${(p.start_s + p.end_s) / 2} s the label says '${label}', not ${p.name}`);
    }
    await page.evaluate(() => window.uavplanReport.setTime(0));
  }
  // Each UAV's state as the slider shows it: flying on a moving piece, waiting where it holds
  // still (before its arrival), arrived once at its goal to stay; never flying while it waits.
  const states = await page.evaluate(() => {
    const d = JSON.parse(document.getElementById('uavplan-data').textContent);
    const out = [];
    for (const [i, u] of d.uavs.entries()) {
      const tr = u.trajectory;
      for (let k = 1; k < tr.length; k++) {
        const t = (tr[k - 1][0] + tr[k][0]) / 2;
        if (!(tr[k][0] > tr[k - 1][0])) continue;
        const moving = Math.hypot(tr[k][1] - tr[k - 1][1], tr[k][2] - tr[k - 1][2], tr[k][3] - tr[k - 1][3]) > 1e-6;
        const want = typeof u.arrival_s === 'number' && t >= u.arrival_s ? 'arrived' : moving ? 'flying' : 'waiting';
        const got = window.uavplanReport.uavStates(t)[i];
        if (got !== want) { out.push(`${u.id} at t = ${t}: shown ${got}, is ${want}`); break; }
      }
    }
    window.uavplanReport.setTime(0);
    return { wrong: out, label: document.getElementById('uav-states').textContent };
  });
  for (const w of states.wrong) fail(w);
  if (!/\d+ (flying|waiting|arrived)/.test(states.label)) fail(`no UAV states beside the time slider ('${states.label}')`);
  if (info.pageWidth > 1400) fail(`the page is ${info.pageWidth} px wide in a 1400 px window`);
  await page.screenshot({ path: shotPath, fullPage: true });
  for (const e of errors) fail(e);
  if (!process.exitCode)
    console.log(`report_browser_test: ok (${colours.length} routes, ${charts} charts, ${info.shells} radar shells, ${info.tracks} tracks)`);
} finally {
  await browser.close();
}
