// Opens each motion.html given on the command line in headless Chromium (Debian's, never a downloaded
// one) and checks what a person would see: the page loads offline without console errors, the 3D view
// draws something, the scrubber moves the figure, and playback advances in real time. Screenshots go to
// target/browser-artifacts/ (viewer.png is the first page's).
//
//   node viewer.mjs path/to/motion.html [more.html ...]
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const artifacts = process.env.ARTIFACTS_DIR ?? path.resolve(here, '../../target/browser-artifacts');
const pages = process.argv.slice(2);
if (pages.length === 0) {
  console.error('usage: node viewer.mjs motion.html [...]');
  process.exit(2);
}
fs.mkdirSync(artifacts, { recursive: true });

let passed = 0, failed = 0;
function check(name, ok, detail = '') {
  if (ok) passed++; else failed++;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${detail ? ` — ${detail}` : ''}`);
}

const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'mintorque-chromium-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync'],
  viewport: { width: 1280, height: 800 },
});

// Decodes a PNG in the browser (no image library needed here) and says how varied its pixels are, and how
// many have one of the floor grid's two line colours (0x9aa5b1, 0xc9d1da; lines are not lit, so they keep
// their colour), within a small tolerance for blending.
async function pixelStats(page, png) {
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width; c.height = img.height;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const near = (i, [r, gr, b]) => Math.abs(d[i] - r) + Math.abs(d[i + 1] - gr) + Math.abs(d[i + 2] - b) <= 6;
    const colours = new Set();
    let differing = 0, floor = 0;
    for (let i = 0; i < d.length; i += 4) {
      colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
      if (Math.abs(d[i] - d[0]) + Math.abs(d[i + 1] - d[1]) + Math.abs(d[i + 2] - d[2]) > 30) differing++;
      if (near(i, [0x9a, 0xa5, 0xb1]) || near(i, [0xc9, 0xd1, 0xda])) floor++;
    }
    return { colours: colours.size, differing: differing / (d.length / 4), width: c.width, height: c.height, floor };
  }, png.toString('base64'));
}

// How many pixels differ between two screenshots of the same size (decoded in the browser).
async function pixelsChanged(page, a, b) {
  return page.evaluate(async ([a64, b64]) => {
    const load = async (b64) => {
      const img = new Image();
      img.src = `data:image/png;base64,${b64}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width; c.height = img.height;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, c.width, c.height).data;
    };
    const [da, db] = [await load(a64), await load(b64)];
    let n = 0;
    for (let i = 0; i < Math.min(da.length, db.length); i += 4) {
      if (Math.abs(da[i] - db[i]) + Math.abs(da[i + 1] - db[i + 1]) + Math.abs(da[i + 2] - db[i + 2]) > 30) n++;
    }
    return n;
  }, [a.toString('base64'), b.toString('base64')]);
}

// How far the bodies moved between two poses: position (m) plus turn (quaternion distance), since a
// pendulum's only body turns about its origin without moving it.
const diff = (u, v) => Math.hypot(...u.map((x, k) => x - v[k]));
const maxMove = (a, b) => Math.max(...a.map((body, i) =>
  diff(body.position, b[i].position) + Math.min(diff(body.quaternion, b[i].quaternion), diff(body.quaternion, b[i].quaternion.map((x) => -x)))));

try {
  for (const [n, file] of pages.entries()) {
    const name = path.basename(path.dirname(path.resolve(file)));
    const page = await context.newPage();
    const errors = [];
    const external = [];
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('request', (r) => { if (!/^(file|data|blob):/.test(r.url())) external.push(r.url()); });

    await page.goto(pathToFileURL(path.resolve(file)).href, { waitUntil: 'load' });
    await page.waitForFunction(() => window.mintorque !== undefined, null, { timeout: 15000 });
    check(`${name}: WebGL context`, await page.evaluate(() => window.mintorque.webgl));
    const duration = await page.evaluate(() => window.mintorque.duration);
    check(`${name}: duration`, duration > 0, `${duration} s`);

    // Playback runs in real time (speed 1×): half a second of wall clock moves the time on.
    await page.evaluate(() => { window.mintorque.setTime(0); window.mintorque.play(); });
    await page.waitForTimeout(500);
    const played = await page.evaluate(() => { window.mintorque.pause(); return window.mintorque.time(); });
    check(`${name}: playback advances`, played > 0.15 && played <= duration, `t = ${played.toFixed(3)} s after 0.5 s`);

    // The scrubber moves the figure; going back to t = 0 gives back the same pose.
    await page.evaluate(() => window.mintorque.setTime(0));
    const pose0 = await page.evaluate(() => window.mintorque.pose());
    const target = 0.6 * duration;
    await page.locator('#scrubber').fill(String(target));
    const scrubbed = await page.evaluate(() => ({ t: window.mintorque.time(), pose: window.mintorque.pose() }));
    const moved = maxMove(pose0, scrubbed.pose);
    check(`${name}: scrubber sets the time`, Math.abs(scrubbed.t - target) < duration / 500 + 1e-9, `t = ${scrubbed.t}`);
    check(`${name}: scrubber moves the figure`, moved > 1e-3, `largest body move ${moved.toFixed(4)} (m + quaternion distance)`);
    const again = await page.evaluate(() => { window.mintorque.setTime(0); return window.mintorque.pose(); });
    check(`${name}: setTime is repeatable`, maxMove(pose0, again) < 1e-9);

    // What a person sees: the 3D canvas holds a drawing, not one flat colour, and the figure in it moves
    // between the start and mid-motion (so it is not just the floor grid that was drawn).
    await page.evaluate(() => window.mintorque.setTime(0));
    await page.waitForTimeout(100);
    const startShot = await page.locator('#view canvas').screenshot();
    await page.evaluate((t) => window.mintorque.setTime(t), target);
    await page.waitForTimeout(100);
    const canvasShot = await page.locator('#view canvas').screenshot();
    const changed = await pixelsChanged(page, startShot, canvasShot);
    check(`${name}: the figure moves on screen`, changed > 500, `${changed} pixels changed from t = 0`);
    const stats = await pixelStats(page, canvasShot);
    check(`${name}: 3D view is not blank`, stats.colours > 50 && stats.differing > 0.01,
      `${stats.colours} colours, ${(100 * stats.differing).toFixed(1)}% of ${stats.width}×${stats.height} px differ from the corner`);
    const shot = path.join(artifacts, `viewer-${name}.png`);
    await page.screenshot({ path: shot });
    if (n === 0) fs.copyFileSync(shot, path.join(artifacts, 'viewer.png'));
    console.log(`     screenshot ${shot}`);

    // Obstacles: every declared one drawn; a plan that names obstacles (the dip-down's bar) shows them and
    // the collision capsules of the bodies kept off them.
    const declared = await page.evaluate(() => window.mintorque.declaredObstacles);
    const drawn = await page.evaluate(() => window.mintorque.drawnObstacles());
    check(`${name}: every obstacle drawn`, declared.every((o) => drawn.includes(o)), `declared ${declared.join(', ') || 'none'}; drawn ${drawn.join(', ') || 'none'}`);
    if (name.includes('dip_down')) {
      check(`${name}: the bar is drawn`, drawn.includes('bar'));
      const capsules = await page.evaluate(() => window.mintorque.collisionShapes());
      check(`${name}: collision capsules drawn`, capsules > 0, `${capsules} capsules`);
    }
    // The floor: drawn under a figure held by the world, none under a free-floating one (the astronaut), as
    // the filmstrip draws no ground line. Seen, not only declared: the grid's line colours in the canvas (held
    // figures show 6000–18000 such pixels, the astronaut's shading about 60).
    const floor = await page.evaluate(() => ({ drawn: window.mintorque.floorDrawn(), declared: window.mintorque.floorDeclared }));
    const floating = name.includes('astronaut');
    const gridPixels = stats.floor; // the canvas shot decoded above
    check(`${name}: ${floating ? 'no floor under the free-floating figure' : 'the floor is drawn'}`,
      floor.drawn === !floating && floor.declared === !floating && (floating ? gridPixels < 1000 : gridPixels > 2000),
      `floor in the scene: ${floor.drawn}, in the plan: ${floor.declared}; ${gridPixels} px of the grid's colours`);
    // The chart: one unit per axis, time in seconds, a legend entry per series inside its box (it scrolls).
    const chart = await page.evaluate(() => window.mintorque.chart());
    check(`${name}: chart axes carry one unit each`, chart.xLabel === 'time (s)' && /\((N·m|N|%)\)$/.test(chart.yLabel)
      && !chart.yLabel.includes(' or ') && chart.modes.every((m) => ['N·m', 'N', '%'].includes(m)), JSON.stringify(chart.modes) + ' ' + chart.yLabel);
    check(`${name}: chart legend fits`, chart.legendEntries === chart.series.length && chart.legendInside, `${chart.legendEntries} entries`);
    if (name.includes('mixed')) {
      const force = await page.evaluate(() => { window.mintorque.setChart('N'); return window.mintorque.chart(); });
      check(`${name}: torque and force on separate axes`, chart.modes.includes('N·m') && force.mode === 'N'
        && force.yLabel === 'force (N)' && force.series.length === 1 && chart.series.length === 1, JSON.stringify([chart.series, force.series]));
      await page.evaluate(() => window.mintorque.setChart('N·m'));
    }
    const joints = await page.evaluate(() => window.mintorque.pose().length);
    if (name.includes('moon')) {
      check(`${name}: a legend entry for each of the many joints`, chart.series.length >= 30, `${chart.series.length} series, ${joints} bodies`);
    }
    const strength = await page.evaluate(() => Boolean(window.mintorque.chart().modes.includes('%')));
    if (name.includes('weight_lift') || name.includes('moon')) {
      check(`${name}: strength share chart offered`, strength);
      await page.evaluate(() => window.mintorque.setChart('%'));
      const share = await page.evaluate(() => window.mintorque.chart());
      check(`${name}: strength share and population capable shown`, share.mode === '%' && share.series.some((n) => n.endsWith('capable'))
        && share.series.some((n) => n.endsWith('|τ|/strength')) && share.legendInside, `${share.series.length} series`);
      fs.mkdirSync(artifacts, { recursive: true });
      await page.locator('#plot-box').screenshot({ path: path.join(artifacts, `chart-strength-${n}.png`) });
      await page.evaluate(() => window.mintorque.setChart('N·m'));
    }
    await page.locator('#plot-box').screenshot({ path: path.join(artifacts, `chart-${n}.png`) });
    check(`${name}: no console errors`, errors.length === 0, errors.join(' | '));
    check(`${name}: nothing fetched from the network`, external.length === 0, external.join(' '));
    await page.close();
  }
} finally {
  await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
