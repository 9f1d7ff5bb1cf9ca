// Bench: the toolpath page (`millpath render --html`) loads and draws a program of 100,000
// moves or more in headless Chromium (Debian's chromium, playwright-core), with its cut part
// (the stock height field, on by default). Targets: < 2 s from navigation to the first drawn
// frame; the playback stays interactive: a jump to half-way (cutting the stock up to there)
// and its frame < PLAYBACK_MS. Prints the figures; exits 1 above a target.
//   node bench/toolpath_load.mjs [MILLPATH_BIN] [--report]
// With --report (CI's smoke run on a shared machine) the figures are printed and only a page
// that does not load, or lacks its cut part, fails: wall-clock targets are judged by hand.
// Needs editors/vscode's node_modules (npm ci there) and /usr/bin/chromium.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync, statSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const repo = join(dirname(fileURLToPath(import.meta.url)), '..');
const require = createRequire(join(repo, 'editors/vscode/package.json'));
const { chromium } = require('playwright-core');
const args = process.argv.slice(2);
const reportOnly = args.includes('--report');
const bin = args.find((a) => a !== '--report') || process.env.MILLPATH_BIN || join(repo, 'target/release/millpath');
const TARGET_MS = 2000;
const PLAYBACK_MS = 500;
const WANT_MOVES = 100_000;

// a zig-zag chain of mill segments, three passes deep (T3 I1 B0)
function program(segments) {
  const lines = ['path 9000.1P {', '  start (0, 0)  O2 T3 I1 B0', `  end (0, ${segments})`];
  for (let k = 0; k < segments; k++) {
    const [x0, x1] = k % 2 ? [100, 0] : [0, 100];
    lines.push(`  mill (${x0}, ${k}) -> (${x1}, ${k + 1})`);
  }
  lines.push('}', '');
  return lines.join('\n');
}

const dir = mkdtempSync(join(tmpdir(), 'millpath-bench-'));
writeFileSync(join(dir, 'millpath.toml'), 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n');
let segments = 20000, data, html;
for (;;) {
  writeFileSync(join(dir, '9000.mpath'), program(segments));
  html = join(dir, '9000.html');
  execFileSync(bin, ['render', join(dir, '9000.mpath'), '--html', html], { stdio: 'ignore' });
  const json = /<script id="toolpath-data" type="application\/json">(.*?)<\/script>/s.exec(readFileSync(html, 'utf8'))[1];
  data = JSON.parse(json.replace(/<\\\//g, '</'));
  if (data.moves.length >= WANT_MOVES) break;
  // an even count: the chain ends at x 0, where the end marker is
  segments = 2 * Math.ceil((segments * (WANT_MOVES / data.moves.length) * 1.02) / 2);
}
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const mb = (statSync(html).size / 1e6).toFixed(1);
const runs = [], jumps = [];
try {
  for (let r = 0; r < 3; r++) {
    const page = await browser.newPage({ viewport: { width: 1200, height: 800 } });
    await page.goto(pathToFileURL(html).href);
    await page.waitForFunction(() => document.body.dataset.ready, null, { timeout: 60000 });
    const [ready, drawn] = await page.evaluate(() => [Number(document.body.dataset.ready), Number(document.body.dataset.moves)]);
    if (drawn !== data.moves.length) throw new Error(`drew ${drawn} of ${data.moves.length} moves`);
    runs.push(ready);
    // playback: half-way (every lowering of the first half applied) and the frame after it
    jumps.push(await page.evaluate(() => new Promise((done) => {
      const api = window.millpathToolpath, t0 = performance.now();
      api.setTime(api.duration() / 2);
      requestAnimationFrame(() => requestAnimationFrame(() => done(performance.now() - t0)));
    })));
    await page.close();
  }
} finally {
  await browser.close();
  rmSync(dir, { recursive: true, force: true });
}
const best = Math.min(...runs), jump = Math.min(...jumps);
const cut = data.cut ? `cut part ${data.cut.nx}×${data.cut.ny} cells of ${data.cut.cell.toFixed(3)} mm${data.cut.thinned ? ', lowerings thinned' : ''}` : 'no cut part';
console.log(`toolpath page: ${data.moves.length} moves (${segments} segments, ${mb} MB page, ${cut}): loaded and drawn in ${runs.map((t) => t.toFixed(0)).join(' / ')} ms (best ${best.toFixed(0)} ms, target < ${TARGET_MS} ms); playback jump to half-way and its frame ${jumps.map((t) => t.toFixed(0)).join(' / ')} ms (best ${jump.toFixed(0)} ms, target < ${PLAYBACK_MS} ms)`);
const inTime = best < TARGET_MS && jump < PLAYBACK_MS;
if (!inTime) console.log(reportOnly ? 'toolpath page: above a target (reported only: --report)' : 'toolpath page: FAIL, above a target');
process.exit(data.cut && data.moves.length >= WANT_MOVES && (inTime || reportOnly) ? 0 : 1);
