// Opens an HTML report in headless Chromium (Debian's, driven by playwright-core), fails on any
// console error or page error, and checks a screenshot of the 3-D view for the routes: pixels
// of the UAVs' colours must be there with the routes shown and (nearly) gone with them hidden,
// so a blank or broken canvas fails.
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
  fs.writeFileSync(shotPath, shown);
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
  if (charts < 2) fail(`expected the altitude and speed charts, found ${charts}`);
  const rows = await page.locator('main table').first().locator('tr').count();
  if (rows < 2) fail('the metrics table is empty');
  for (const e of errors) fail(e);
  if (!process.exitCode) console.log(`report_browser_test: ok (${colours.length} routes, ${charts} charts)`);
} finally {
  await browser.close();
}
