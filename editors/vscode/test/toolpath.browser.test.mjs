// The toolpath page (`millpath render --html`) in a real browser: Debian's chromium driven by
// playwright-core, WebGL in software. Checks the drawn move count, zoom and orbit, playback
// and clicking a move of a chain's second segment against the program `millpath compile`
// writes. Screenshots go to target/artifacts/toolpath-*.png.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
const repo = join(here, '../../..');
const bin = process.env.MILLPATH_BIN || join(repo, 'target/release/millpath');
const browserPath = process.env.CHROMIUM || '/usr/bin/chromium';
const artifacts = join(repo, 'target/artifacts');
const skip = !existsSync(browserPath) && `no browser at ${browserPath}`;
const CHROMIUM_ARGS = ['--headless', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// a chain of three segments: mill, a vertical branch, a mark back to the start
const CHAIN = `path 2040.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (0, 0)
  mill (0, 0) -> (20, 0)
  mill (20, 0) -> (20, 10)
  mark (20, 10) -> (0, 0)  D2
}
`;

let browser, dir;
before(async () => {
  if (skip) return;
  dir = mkdtempSync(join(tmpdir(), 'millpath-toolpath-'));
  writeFileSync(join(dir, 'millpath.toml'), 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n');
  writeFileSync(join(dir, '2040.mpath'), CHAIN);
  mkdirSync(artifacts, { recursive: true });
  browser = await chromium.launch({ executablePath: browserPath, args: CHROMIUM_ARGS });
});
after(async () => { if (browser) await browser.close(); });

/// Renders `file` with millpath, opens the page; returns the page and the embedded data.
async function open(file, viewport = { width: 1000, height: 700 }, extra = []) {
  const html = join(dir, `${Math.random().toString(36).slice(2)}.html`);
  execFileSync(bin, ['render', file, '--html', html, ...extra], { stdio: 'ignore' });
  const json = /<script id="toolpath-data" type="application\/json">(.*?)<\/script>/s.exec(readFileSync(html, 'utf8'))[1];
  const data = JSON.parse(json.replace(/<\\\//g, '</'));
  const page = await browser.newPage({ viewport });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(pathToFileURL(html).href);
  await page.waitForFunction(() => document.body.dataset.ready, null, { timeout: 20000 });
  assert.deepEqual(errors, []);
  return { page, data };
}

const camera = (page) => page.evaluate(() => window.millpathToolpath.cameraMatrix());
const differs = (a, b) => a.some((v, k) => Math.abs(v - b[k]) > 1e-6);

test('every move of the program is drawn', { skip, timeout: 120000 }, async () => {
  const { page, data } = await open(join(repo, 'examples/text/2010.mpath'));
  const drawn = Number(await page.evaluate(() => document.body.dataset.moves));
  assert.equal(drawn, data.moves.length);
  assert.ok(drawn > 20, `${drawn} moves`);
  // the statistics' command count is the program's move count
  assert.match(data.stats[4], new RegExp(`\\b${data.moves.length}$`));
  assert.match(await page.locator('#stats').textContent(), /Milling length/);
  // the exact estimated time ends the statistics, as compile's summary has it
  assert.match(data.time, /^\d+:\d\d:\d\d$/);
  assert.match(await page.locator('#stats').textContent(), new RegExp(`Estimated time: ${data.time}$`));
  // a numeric depth legend: the top and the bottom of the cuts in mm
  const b = data.bounds;
  assert.equal(b.minZ, -0.2);
  assert.ok((await page.locator('#legend').textContent()).includes(`Z ${b.maxZ.toFixed(3)}${b.minZ.toFixed(3)} mm`));
  await page.screenshot({ path: join(artifacts, 'toolpath-iso.png') });
  await page.locator('[data-view="top"]').click();
  await page.screenshot({ path: join(artifacts, 'toolpath-top.png') });
  await page.locator('[data-view="front"]').click();
  await page.screenshot({ path: join(artifacts, 'toolpath-front.png') });
  await page.close();
});

test('zoom and orbit change the view', { skip, timeout: 120000 }, async () => {
  const { page } = await open(join(repo, 'examples/text/2010.mpath'));
  const canvas = await page.locator('#stage > canvas').boundingBox();
  const cx = canvas.x + canvas.width / 2, cy = canvas.y + canvas.height / 2;
  const m0 = await camera(page);
  const shot0 = await page.locator('#stage > canvas').screenshot();
  await page.mouse.move(cx, cy);
  await page.mouse.wheel(0, -400);
  await page.waitForTimeout(200);
  const m1 = await camera(page);
  assert.ok(differs(m0, m1), 'the wheel zooms');
  const shot1 = await page.locator('#stage > canvas').screenshot();
  assert.ok(!shot0.equals(shot1), 'the zoomed picture differs');
  // orbit: drag with the left button
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  await page.mouse.move(cx + 120, cy + 40, { steps: 8 });
  await page.mouse.up();
  await page.waitForTimeout(200);
  const m2 = await camera(page);
  assert.ok(differs(m1, m2), 'dragging orbits');
  await page.locator('#stage > canvas').screenshot({ path: join(artifacts, 'toolpath-orbit.png') });
  await page.close();
});

test('playback puts the tool where the program is at a given time', { skip, timeout: 120000 }, async () => {
  const { page, data } = await open(join(dir, '2040.mpath'));
  // the time of every move, as the data gives it: the tool is halfway along a straight cut
  // halfway through its time, and at its end at its end
  const k = data.moves.findIndex((m) => m.kind === 'mill' && !m.arc && m.t > 0 && m.from[0] !== m.to[0]);
  assert.ok(k > 0);
  const start = data.moves.slice(0, k).reduce((s, m) => s + m.t, 0);
  const m = data.moves[k];
  const half = await page.evaluate((t) => { window.millpathToolpath.setTime(t); return window.millpathToolpath.toolPosition(); }, start + m.t / 2);
  for (let a = 0; a < 3; a++) assert.ok(Math.abs(half[a] - (m.from[a] + m.to[a]) / 2) < 1e-3, `${half} vs ${m.from}→${m.to}`);
  const end = await page.evaluate((t) => { window.millpathToolpath.setTime(t); return window.millpathToolpath.toolPosition(); }, start + m.t);
  for (let a = 0; a < 3; a++) assert.ok(Math.abs(end[a] - m.to[a]) < 1e-3, `${end} vs ${m.to}`);
  // the readout names the position, the feed and the line
  const readout = await page.locator('#readout').textContent();
  assert.match(readout, new RegExp(`X ${m.to[0].toFixed(3)} Y ${m.to[1].toFixed(3)}`));
  // elapsed and remaining time as h:mm:ss.s
  assert.match(readout, /\d+:\d\d:\d\d\.\d \/ −\d+:\d\d:\d\d\.\d$/);
  // the play button runs the program to its end
  const total = data.moves.reduce((s, mv) => s + mv.t, 0);
  await page.selectOption('#speed', '1000');
  await page.evaluate(() => window.millpathToolpath.setTime(0));
  await page.locator('#play').click();
  await page.waitForFunction((tt) => Number(document.body.dataset.time) >= tt - 1e-6, total, { timeout: 20000 });
  const last = data.moves[data.moves.length - 1].to;
  const pos = await page.evaluate(() => window.millpathToolpath.toolPosition());
  for (let a = 0; a < 3; a++) assert.ok(Math.abs(pos[a] - last[a]) < 1e-3);
  await page.close();
});

test('clicking a move of the second segment reports that segment and its G-code line', { skip, timeout: 120000 }, async () => {
  const { page, data } = await open(join(dir, '2040.mpath'));
  const src = (m) => data.sources[m.source];
  // the vertical branch (20,0)->(20,10): the chain's second segment, line 5 of the file
  const i = data.moves.findIndex((m) => m.kind === 'mill' && m.from[0] === 20 && m.to[0] === 20 && m.to[1] === 10 && m.from[1] === 0);
  assert.ok(i >= 0);
  assert.equal(src(data.moves[i]).line, 4);
  const [x, y] = await page.evaluate((k) => window.millpathToolpath.screenOf(k, 0.5), i);
  // the listener is in place before the click (an evaluate not awaited may run after it)
  await page.evaluate(() => {
    window.selected = new Promise((resolve) => window.addEventListener('millpath-select', (e) => resolve(e.detail), { once: true }));
  });
  await page.mouse.click(x, y);
  const detail = await page.evaluate(() => Promise.race([
    window.selected,
    new Promise((_, reject) => setTimeout(() => reject(new Error('no millpath-select event within 10 s of the click')), 10000)),
  ]));
  assert.equal(detail.source.line, 4, JSON.stringify(detail));
  assert.equal(detail.source.text, 'mill (20, 0) -> (20, 10)');
  assert.equal(detail.gcodeLine, data.moves[detail.index].line);
  // that line of the program `millpath compile` writes is the move to the branch's end
  execFileSync(bin, ['compile', join(dir, '2040.mpath')], { stdio: 'ignore' });
  const program = readFileSync(join(dir, '2040_Milling.gcode'), 'utf8').split('\n');
  assert.match(program[detail.gcodeLine - 1], /^G01 .*X20\.000 Y10\.000/);
  const info = await page.locator('#info').textContent();
  assert.match(info, /2040\.mpath:5/);
  assert.match(info, new RegExp(`G-code line ${detail.gcodeLine}: G01`));
  assert.equal(await page.evaluate(() => document.body.dataset.highlighted), '1');
  // the source → view direction: an element's line highlights all of its moves
  const n = await page.evaluate(({ file }) => window.millpathToolpath.highlight({ file, line: 5 }).length, { file: src(data.moves[i]).file });
  assert.equal(n, data.moves.filter((m) => src(m) && src(m).line === 5).length);
  assert.ok(n >= 2, `${n} mark moves`);
  await page.screenshot({ path: join(artifacts, 'toolpath-click.png') });
  await page.close();
});

test('probe labels are sized in screen pixels', { skip, timeout: 120000 }, async () => {
  const { page, data } = await open(join(repo, 'examples/text/2020.mpath'));
  assert.ok(data.probes.length > 0);
  const label = page.locator('#labels span').first();
  assert.equal(await label.textContent(), data.probes[0].name);
  const box = await label.boundingBox();
  assert.ok(box.height < 20, `label height ${box.height}px`);
  await page.screenshot({ path: join(artifacts, 'toolpath-probes.png') });
  await page.close();
});

test('inside VS Code the page takes the theme colours', { skip, timeout: 120000 }, async () => {
  const { page } = await open(join(repo, 'examples/text/2010.mpath'), { width: 400, height: 300 });
  const corner = () => page.evaluate(() => {
    const c = document.querySelector('#stage > canvas');
    const g = c.getContext('webgl2') || c.getContext('webgl');
    const px = new Uint8Array(4);
    g.readPixels(2, 2, 1, 1, g.RGBA, g.UNSIGNED_BYTE, px);
    return [...px.slice(0, 3)];
  });
  await page.evaluate(() => document.documentElement.style.setProperty('--vscode-editor-background', 'rgb(10, 60, 20)'));
  await page.waitForTimeout(300);
  assert.deepEqual(await corner(), [10, 60, 20]);
  await page.close();
});

test('the title says when placeholder machine settings are in use', { skip, timeout: 120000 }, async () => {
  // the language server's data carries `warnings` when millpath.toml lacks the machine
  // settings (`render` refuses then, as `compile` does): the page shows them in its title
  const html = join(dir, 'placeholder.html');
  execFileSync(bin, ['render', join(dir, '2040.mpath'), '--html', html], { stdio: 'ignore' });
  const warning = 'missing machine settings: feed (placeholder F150)';
  writeFileSync(html, readFileSync(html, 'utf8').replace('"warnings":[]', `"warnings":[${JSON.stringify(warning)}]`));
  const page = await browser.newPage();
  await page.goto(pathToFileURL(html).href);
  await page.waitForFunction(() => document.body.dataset.ready, null, { timeout: 20000 });
  assert.match(await page.locator('#title').textContent(), /⚠ missing machine settings: feed/);
  await page.close();
  const { page: plain } = await open(join(dir, '2040.mpath'));
  assert.doesNotMatch(await plain.locator('#title').textContent(), /⚠/);
  await plain.close();
});

test('the height map: a measured surface coloured by its heights, a grid not measured at the top', { skip, timeout: 120000 }, async () => {
  // 2001 compiled with [heightmap]; LinuxCNC's log of a tilted board at its own probe points
  const hdir = mkdtempSync(join(tmpdir(), 'millpath-heightmap-'));
  writeFileSync(join(hdir, '2001.mpath'), readFileSync(join(repo, 'examples/text/2001.mpath')));
  writeFileSync(join(hdir, 'millpath.toml'), 'dialect = "linuxcnc"\nfeed = 300\nsweep_speed = 1000\nsweep_height = 10\nprobe_feed = 50\n[heightmap]\nstep = 10\nmargin = 2\n');
  execFileSync(bin, ['compile', '2001.mpath'], { cwd: hdir, stdio: 'ignore' });
  let x = 0, y = 0;
  const log = [];
  for (const line of readFileSync(join(hdir, '2001_Probing.gcode'), 'utf8').split('\n')) {
    if (line.startsWith('G38')) log.push(`${x} ${y} ${(3 + 0.01 * x + 0.05 * y).toFixed(6)} 0 0 0 0 0 0`);
    else if (line.startsWith('G00')) {
      x = Number((/X(\S+)/.exec(line) || [0, x])[1]);
      y = Number((/Y(\S+)/.exec(line) || [0, y])[1]);
    }
  }
  writeFileSync(join(hdir, '2001_probes.txt'), log.join('\n') + '\n');
  const { page, data } = await open(join(hdir, '2001.mpath'), undefined, ['--surface', join(hdir, '2001_probes.txt')]);
  const hm = data.heightmap;
  assert.equal(hm.measured, true);
  assert.equal(await page.evaluate(() => document.body.dataset.surface), `measured ${hm.xs.length}x${hm.ys.length}`);
  assert.match(await page.locator('#legend').textContent(), new RegExp(`surface 4×2 Z ${hm.legend.min.toFixed(3)}.*${hm.legend.max.toFixed(3)} mm`));
  await page.locator('[data-view="top"]').click();
  await page.waitForTimeout(300);
  // the pixel at each probe point has the colour the data gives its height
  const pixel = (p) => page.evaluate((p) => {
    const [cx, cy] = window.millpathToolpath.screenOfPoint(p);
    const c = document.querySelector('#stage > canvas'), r = c.getBoundingClientRect();
    const g = c.getContext('webgl2') || c.getContext('webgl');
    const px = new Uint8Array(4), k = c.width / r.width;
    g.readPixels(Math.round((cx - r.left) * k), Math.round(c.height - (cy - r.top) * k), 1, 1, g.RGBA, g.UNSIGNED_BYTE, px);
    return [...px.slice(0, 3)];
  }, p);
  const hex = (h) => [1, 3, 5].map((k) => parseInt(h.slice(k, k + 2), 16));
  const near = (a, b) => a.every((v, k) => Math.abs(v - b[k]) <= 12);
  let lowest = null, highest = null;
  for (let j = 0; j < hm.ys.length; j++) {
    for (let i = 0; i < hm.xs.length; i++) {
      const z = hm.z[j][i], got = await pixel([hm.xs[i], hm.ys[j], z]), want = hex(hm.colours[j][i]);
      assert.ok(near(got, want), `(${hm.xs[i]}, ${hm.ys[j]}) z ${z}: ${got} vs ${want}`);
      if (!lowest || z < lowest.z) lowest = { z, got };
      if (!highest || z > highest.z) highest = { z, got };
    }
  }
  // low is blue, high is yellow: the colours follow the heights
  assert.ok(lowest.got[2] > lowest.got[0] + 80 && highest.got[0] > highest.got[2] + 80, `${lowest.got} / ${highest.got}`);
  // between the points the translucent surface is drawn (not the background)
  const bg = await pixel([hm.xs[0] - 50, hm.ys[0] - 50, 0]);
  const inside = await pixel([(hm.xs[0] + hm.xs[1]) / 2, hm.ys[0] + (hm.ys[1] - hm.ys[0]) / 4, hm.z[0][0]]);
  assert.ok(!near(inside, bg), `inside ${inside} vs background ${bg}`);
  // the moves lie over it: the slot's cut keeps its own colour on the surface
  const cut = data.moves.findIndex((m) => m.kind === 'mill' && m.from[0] !== m.to[0]);
  const onCut = await page.evaluate((i) => window.millpathToolpath.screenOf(i, 0.3), cut);
  const slot = await page.evaluate(([cx, cy]) => {
    const c = document.querySelector('#stage > canvas'), r = c.getBoundingClientRect();
    const g = c.getContext('webgl2') || c.getContext('webgl');
    const px = new Uint8Array(4), k = c.width / r.width;
    g.readPixels(Math.round((cx - r.left) * k), Math.round(c.height - (cy - r.top) * k), 1, 1, g.RGBA, g.UNSIGNED_BYTE, px);
    return [...px.slice(0, 3)];
  }, onCut);
  assert.ok(!near(slot, inside), `the cut ${slot} is drawn over the surface ${inside}`);
  await page.screenshot({ path: join(artifacts, 'toolpath-surface.png') });
  await page.close();
  // being edited, not measured: the probe points at the nominal top
  const grid = await open(join(hdir, '2001.mpath'));
  assert.equal(grid.data.heightmap.measured, false);
  assert.equal(await grid.page.evaluate(() => document.body.dataset.surface), 'grid 4x2');
  assert.match(await grid.page.locator('#legend').textContent(), /height map 4×2 probe points at the top 3\.000 mm \(not measured\)/);
  await grid.page.close();
});

test('clamps are drawn and a move into one is marked in red', { skip, timeout: 120000 }, async () => {
  // a slot with sweeps at S10; a vice under the last sweep with its top at the sweep height
  const cdir = mkdtempSync(join(tmpdir(), 'millpath-clamps-'));
  writeFileSync(join(cdir, '3001.mpath'), 'path 3001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 S10\n  end (60, 0)\n  sweep (0, 0) -> (10, 0)\n  mill (10, 0) -> (50, 0)\n  sweep (50, 0) -> (60, 0)\n}\n');
  writeFileSync(join(cdir, 'millpath.toml'), 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n[[clamp]]\nname = "vice"\nmin = [54, -3, 0]\nmax = [56, 3, 10]\n[[clamp]]\nname = "stop"\nmin = [20, 8, 0]\nmax = [30, 12, 5]\n');
  const { page, data } = await open(join(cdir, '3001.mpath'));
  assert.equal(data.clamps.length, 2);
  assert.equal(await page.evaluate(() => document.body.dataset.clamps), '2');
  const hits = await page.evaluate(() => window.millpathToolpath.clampHits());
  assert.equal(hits.length, 1);
  const hit = data.moves[hits[0]];
  assert.equal(hit.kind, 'rapid');
  assert.deepEqual(hit.hits, [0]);
  assert.match(await page.locator('#legend').textContent(), /clamps 2 · 1 move into a clamp/);
  await page.locator('[data-view="top"]').click();
  await page.waitForTimeout(300);
  const pixel = (p) => page.evaluate((p) => {
    const [cx, cy] = window.millpathToolpath.screenOfPoint(p);
    const c = document.querySelector('#stage > canvas'), r = c.getBoundingClientRect();
    const g = c.getContext('webgl2') || c.getContext('webgl');
    const px = new Uint8Array(4), k = c.width / r.width;
    g.readPixels(Math.round((cx - r.left) * k), Math.round(c.height - (cy - r.top) * k), 1, 1, g.RGBA, g.UNSIGNED_BYTE, px);
    return [...px.slice(0, 3)];
  }, p);
  // the hit is red at the move (its middle mark)
  const mid = [0, 1, 2].map((a) => (hit.from[a] + hit.to[a]) / 2);
  const red = await pixel(mid);
  assert.ok(red[0] > 180 && red[0] > red[1] + 100 && red[0] > red[2] + 100, `hit pixel ${red}`);
  // the untouched clamp is drawn (its translucent face differs from the background beside it)
  const inBox = await pixel([25, 10.5, 5]), beside = await pixel([25, 20, 5]);
  assert.ok(inBox.some((v, k) => Math.abs(v - beside[k]) > 12), `box ${inBox} vs background ${beside}`);
  assert.ok(!(inBox[0] > inBox[1] + 100), `the untouched clamp is not red: ${inBox}`);
  await page.screenshot({ path: join(artifacts, 'toolpath-clamps-top.png') });
  // clicking the hit says which clamp
  const [x, y] = await page.evaluate((i) => window.millpathToolpath.screenOf(i, 0.5), hits[0]);
  await page.mouse.click(x, y);
  assert.match(await page.locator('#info').textContent(), /runs into clamp 'vice'/);
  await page.locator('[data-view="iso"]').click();
  await page.waitForTimeout(200);
  await page.screenshot({ path: join(artifacts, 'toolpath-clamps.png') });
  await page.close();
});

/// The colour of the canvas pixel at model point `p`.
const pixelAt = (page, p) => page.evaluate((p) => {
  const [cx, cy] = window.millpathToolpath.screenOfPoint(p);
  const c = document.querySelector('#stage > canvas'), r = c.getBoundingClientRect();
  const g = c.getContext('webgl2') || c.getContext('webgl');
  const px = new Uint8Array(4), k = c.width / r.width;
  g.readPixels(Math.round((cx - r.left) * k), Math.round(c.height - (cy - r.top) * k), 1, 1, g.RGBA, g.UNSIGNED_BYTE, px);
  return [...px.slice(0, 3)];
}, p);
const unlike = (a, b) => a.some((v, k) => Math.abs(v - b[k]) > 12);

test('the cut part appears and its lowest point is the program\'s lowest cut', { skip, timeout: 120000 }, async () => {
  const { page, data } = await open(join(repo, 'examples/text/2010.mpath'));
  const cut = data.cut;
  assert.ok(cut && cut.nx > 10 && cut.ny > 10, 'cut part data');
  assert.equal(await page.evaluate(() => document.body.dataset.cut), `${cut.nx}x${cut.ny}`);
  // the verify resolution: O/8
  assert.equal(cut.cell, data.tool.diameter / 8);
  const lowestCut = Math.min(...data.moves.filter((m) => m.kind !== 'rapid').flatMap((m) => [m.from[2], m.to[2]]));
  const shown = await page.evaluate(() => window.millpathToolpath.cutLowest());
  assert.ok(Math.abs(shown - lowestCut) < 1e-4, `lowest shown ${shown}, lowest cut ${lowestCut}`);
  assert.match(await page.locator('#legend').textContent(), /cut part \d+×\d+ of 0\.250 mm/);
  await page.screenshot({ path: join(artifacts, 'toolpath-cut-iso.png') });
  await page.locator('[data-view="top"]').click();
  await page.waitForTimeout(300);
  // a slot (its floor) looks unlike the uncut stock beside it, which is unlike the background
  const slot = data.moves.find((m) => m.kind === 'mill' && m.from[1] === m.to[1] && m.from[0] !== m.to[0] && m.to[2] === lowestCut);
  const y = slot.to[1], x = (slot.from[0] + slot.to[0]) / 2;
  const floor = await pixelAt(page, [x, y + 0.3, lowestCut]), stock = await pixelAt(page, [x, y + 4, 3]);
  const outside = await pixelAt(page, [cut.x0 - 20, cut.y0 - 20, 3]);
  assert.ok(unlike(floor, stock) && unlike(stock, outside), `floor ${floor}, stock ${stock}, background ${outside}`);
  await page.screenshot({ path: join(artifacts, 'toolpath-cut-top.png') });
  // switched off: the background shows where the stock was
  await page.evaluate(() => window.millpathToolpath.showCut(false));
  await page.waitForTimeout(200);
  assert.ok(!unlike(await pixelAt(page, [x, y + 4, 3]), outside), 'the cut part is hidden');
  await page.close();
});

test('a playback half-way shows the cuts of the first half only', { skip, timeout: 120000 }, async () => {
  const { page, data } = await open(join(repo, 'examples/text/2010.mpath'));
  const moves = data.moves, top = data.cut.top;
  const total = await page.evaluate(() => window.millpathToolpath.duration());
  await page.evaluate((t) => window.millpathToolpath.setTime(t), total / 2);
  // the moves done at half time, from the data's own times
  let t = 0, done = 0;
  while (done < moves.length && t + moves[done].t <= total / 2 + 1e-9) t += moves[done++].t;
  assert.equal(await page.evaluate(() => window.millpathToolpath.cutMoves()), done);
  const planar = (m) => m.kind !== 'rapid' && m.from[2] === m.to[2] && (m.from[0] !== m.to[0] || m.from[1] !== m.to[1]);
  const mid = (m) => [(m.from[0] + m.to[0]) / 2, (m.from[1] + m.to[1]) / 2];
  const height = (p) => page.evaluate(([x, y]) => window.millpathToolpath.cutHeightAt(x, y), p);
  const before = moves.slice(0, done).filter(planar), after = moves.slice(done).filter(planar);
  assert.ok(before.length > 0 && after.length > 0, `${before.length} cuts before, ${after.length} after`);
  // every cut of the first half is in the stock; a cut of the second half away from them is not yet
  for (const m of before) assert.ok((await height(mid(m))) <= m.to[2] + 1e-4, `cut at line ${m.line} shown`);
  const far = after.find((m) => before.every((b) => Math.hypot(mid(m)[0] - mid(b)[0], mid(m)[1] - mid(b)[1]) > 2 * data.tool.diameter));
  assert.ok(far, 'a later cut away from the earlier ones');
  assert.equal(await height(mid(far)), top);
  await page.screenshot({ path: join(artifacts, 'toolpath-cut-half.png') });
  // at the start nothing is cut; at the end all is
  await page.evaluate(() => window.millpathToolpath.setTime(0));
  assert.equal(await page.evaluate(() => window.millpathToolpath.cutLowest()), top);
  await page.evaluate((t) => window.millpathToolpath.setTime(t), total);
  assert.ok(Math.abs((await page.evaluate(() => window.millpathToolpath.cutLowest())) - data.cut.lowest) < 1e-6);
  assert.ok((await height(mid(far))) <= far.to[2] + 1e-4);
  await page.close();
});

test('cuts drawn with the tool width, moves coloured by feed', { skip, timeout: 120000 }, async () => {
  const { page, data } = await open(join(repo, 'examples/text/2010.mpath'));
  await page.evaluate(() => window.millpathToolpath.showCut(false));
  await page.locator('[data-view="top"]').click();
  const slot = data.moves.find((m) => m.kind === 'mill' && m.from[1] === m.to[1] && m.from[0] !== m.to[0]);
  const r = data.tool.diameter / 2, p = [(slot.from[0] + slot.to[0]) / 2, slot.to[1] + 0.7 * r, slot.to[2]];
  await page.waitForTimeout(200);
  const thin = await pixelAt(page, p);
  await page.evaluate(() => window.millpathToolpath.showToolWidth(true));
  await page.waitForTimeout(200);
  const wide = await pixelAt(page, p);
  assert.ok(unlike(thin, wide), `0.7 r beside the cut: ${thin} without, ${wide} with the tool width`);
  // 1.3 r beside it the band does not reach
  const past = [p[0], slot.to[1] + 1.3 * r, p[2]];
  assert.ok(!unlike(await pixelAt(page, past), thin), 'the band is the tool diameter wide');
  await page.screenshot({ path: join(artifacts, 'toolpath-width.png') });
  await page.evaluate(() => window.millpathToolpath.setColour('feed'));
  assert.match(await page.locator('#legend').textContent(), /F \d+.*\d+ mm\/min/);
  await page.close();
});
