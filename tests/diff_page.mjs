// The visual diff in real Chromium (playwright-core): the colours of removed, added,
// changed-depth and unchanged moves, the before/after toggle, clicks from a move to its
// element in either version; and the PNG of the same diff sampled pixel by pixel where
// the page draws each kind of move.
//   node tests/diff_page.mjs PAGE.html PICTURE.png
// Prints one JSON line of what it saw; exits 1 on the first failed check.
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { readFileSync } from 'node:fs';

const repo = join(dirname(fileURLToPath(import.meta.url)), '..');
const { chromium } = createRequire(join(repo, 'editors/vscode/package.json'))('playwright-core');
const [pageFile, pngFile] = process.argv.slice(2).map((p) => resolve(p));
const fail = (msg) => { console.error(`FAIL: ${msg}`); process.exitCode = 1; throw new Error(msg); };
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1000, height: 900 } });
  await page.goto(pathToFileURL(pageFile).href);
  const colours = await page.evaluate(() => {
    const out = {};
    for (const p of document.querySelectorAll('#view path')) {
      out[p.getAttribute('class')] = getComputedStyle(p).stroke;
    }
    return out;
  });
  const want = { removed: 'rgb(214, 39, 40)', added: 'rgb(44, 160, 44)', depth: 'rgb(31, 95, 214)', same: 'rgb(154, 154, 154)' };
  for (const [k, v] of Object.entries(want)) if (colours[k] !== v) fail(`${k} drawn ${colours[k]}, want ${v}`);
  // a click on a move marks its element: old only, new only, both
  const click = async (cls) => {
    const box = await page.locator(`#view path.${cls}`).first().boundingBox();
    await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
    return page.evaluate(() => [...document.querySelectorAll('.line.selected')].map((e) => e.id));
  };
  const clicked = { removed: await click('removed'), added: await click('added'), depth: await click('depth') };
  const expect = { removed: ['old-6'], added: ['new-6'], depth: ['old-8', 'new-8'] };
  for (const [k, v] of Object.entries(expect)) if (JSON.stringify(clicked[k]) !== JSON.stringify(v)) fail(`click on ${k}: ${clicked[k]}, want ${v}`);
  // the toggle: before hides what was added, after what was removed
  const visible = async (which) => {
    await page.click(`#show-${which}`);
    return page.evaluate(() => ({
      added: getComputedStyle(document.querySelector('#view path.added')).display !== 'none',
      removed: getComputedStyle(document.querySelector('#view path.removed')).display !== 'none',
    }));
  };
  const toggles = { before: await visible('before'), after: await visible('after'), both: await visible('both') };
  if (toggles.before.added || !toggles.before.removed) fail(`before: ${JSON.stringify(toggles.before)}`);
  if (!toggles.after.added || toggles.after.removed) fail(`after: ${JSON.stringify(toggles.after)}`);
  if (!toggles.both.added || !toggles.both.removed) fail(`both: ${JSON.stringify(toggles.both)}`);
  // the PNG: where the page's SVG (800 units wide) draws a move of each kind, the PNG has its colour
  const png = 'data:image/png;base64,' + readFileSync(pngFile).toString('base64');
  const sampled = await page.evaluate(async (png) => {
    const img = new Image();
    img.src = png;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width; c.height = img.height;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const svg = document.querySelector('#view svg').getBoundingClientRect();
    const k = img.width / 800;
    const out = {};
    for (const cls of ['removed', 'added', 'depth', 'same']) {
      const r = document.querySelector(`#view path.${cls}`).getBoundingClientRect();
      const cx = Math.round((r.x + r.width / 2 - svg.x) * k), cy = Math.round((r.y + r.height / 2 - svg.y) * k);
      const half = Math.round(Math.max(r.width, r.height) * k / 2) + 3;
      const d = g.getImageData(cx - half, cy - half, 2 * half + 1, 2 * half + 1).data;
      const seen = new Set();
      for (let i = 0; i < d.length; i += 4) if (d[i] + d[i + 1] + d[i + 2] < 700) seen.add(`${d[i]},${d[i + 1]},${d[i + 2]}`);
      out[cls] = [...seen];
    }
    return out;
  }, png);
  const near = (rgb, want) => rgb.split(',').map(Number).every((v, i) => Math.abs(v - want[i]) <= 12);
  const rgbs = { removed: [214, 39, 40], added: [44, 160, 44], depth: [31, 95, 214], same: [154, 154, 154] };
  for (const [k, v] of Object.entries(rgbs)) if (!sampled[k].some((s) => near(s, v))) fail(`PNG has no ${k} colour where the page draws it: ${sampled[k].slice(0, 8)}`);
  console.log(JSON.stringify({ colours, clicked, toggles, png: Object.fromEntries(Object.entries(sampled).map(([k, v]) => [k, v.length])) }));
} finally {
  await browser.close();
}
