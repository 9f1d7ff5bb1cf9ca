// The playground (target/playground, built by build.sh) served on 127.0.0.1, in Debian's
// chromium driven by playwright-core: no console error, nothing asked of any other host,
// the size and time budgets, diagnostics while typing, hover, the G-code equal to
// `millpath compile` (examples, and a shared drawing dropped as DXF), dxf2text equal to the
// CLI's, share links, and a click on a move selecting its source line.
// Screenshot: target/artifacts/playground.png.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';
import { chromium } from 'playwright-core';
import { serve } from './serve.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const repo = join(here, '../../..');
const site = join(repo, 'target/playground');
const bin = process.env.MILLPATH_BIN || join(repo, 'target/release/millpath');
const browserPath = process.env.CHROMIUM || '/usr/bin/chromium';
const artifacts = join(repo, 'target/artifacts');
const fixtures = join(repo, '../shared/conformance/fixtures');
const skip = (!existsSync(browserPath) && `no browser at ${browserPath}`)
  || (!existsSync(join(site, 'index.html')) && 'no target/playground: run bash editors/playground/build.sh');
const CHROMIUM_ARGS = ['--headless', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];
const BUDGET_BYTES = 3 * 1024 * 1024;
const FIRST_DIAGNOSTICS_MS = 1500;
const EDIT_MS = 50;

let browser, server, work;
before(async () => {
  if (skip) return;
  server = await serve(site);
  browser = await chromium.launch({ executablePath: browserPath, args: CHROMIUM_ARGS });
  mkdirSync(artifacts, { recursive: true });
  // the examples as the CLI sees them
  work = mkdtempSync(join(tmpdir(), 'millpath-playground-'));
  for (const f of readdirSync(join(repo, 'examples/text'))) copyFileSync(join(repo, 'examples/text', f), join(work, f));
});
after(async () => {
  if (browser) await browser.close();
  if (server) await server.close();
});

/** Opens the page (at `query`), waits for its first diagnostics and outputs. */
async function open(query = '', viewport = { width: 1400, height: 850 }) {
  const page = await browser.newPage({ viewport });
  const errors = [], foreign = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('request', (r) => { if (!r.url().startsWith(server.url) && !r.url().startsWith('data:') && r.url() !== 'about:srcdoc') foreign.push(r.url()); });
  await page.goto(server.url + query);
  await page.waitForFunction(() => document.body.dataset.firstDiagnostics && document.body.dataset.outputs, null, { timeout: 30000 });
  return { page, errors, foreign };
}

const outputsCount = (page) => page.evaluate(() => Number(document.body.dataset.outputs || 0));
async function openFile(page, name) {
  const n = await outputsCount(page);
  await page.evaluate((f) => window.playground.open(f), name);
  await page.waitForFunction((k) => Number(document.body.dataset.outputs) > k, n);
}

/** What `millpath compile` writes for `file` in `dir`: {name: content}. */
function compiled(dir, file) {
  const before = new Set(readdirSync(dir));
  for (const f of before) if (/_(Milling|Clean|Probing)\.gcode$|_Z\.txt$/.test(f)) execFileSync('rm', [join(dir, f)]);
  execFileSync(bin, ['compile', file], { cwd: dir, stdio: 'pipe' });
  const stem = file.replace(/\.[^.]+$/, '');
  return Object.fromEntries(readdirSync(dir)
    .filter((f) => f.startsWith(stem) && /_(Milling|Clean|Probing)\.gcode$|_Z\.txt$/.test(f))
    .map((f) => [f, readFileSync(join(dir, f), 'utf8')]));
}

test('loads without errors, within its budgets, asking nothing of any other host', { skip, timeout: 120000 }, async () => {
  const { page, errors, foreign } = await open();
  const first = Number(await page.evaluate(() => document.body.dataset.firstDiagnostics));
  await page.waitForTimeout(500);
  assert.deepEqual(errors, []);
  assert.deepEqual(foreign, []);
  // every file the page asked for, gzipped
  const asked = [...new Set(server.requests)];
  const sizes = asked.map((p) => {
    const f = join(site, p.endsWith('/') ? `${p}index.html` : p);
    const raw = readFileSync(f);
    return { path: p, raw: raw.length, gzip: gzipSync(raw, { level: 9 }).length };
  });
  const total = sizes.reduce((s, x) => s + x.gzip, 0);
  for (const s of sizes) console.log(`# ${s.path}: ${s.raw} bytes, ${s.gzip} gzipped`);
  console.log(`# total ${total} bytes gzipped (budget ${BUDGET_BYTES}); first diagnostics ${first.toFixed(0)} ms after navigation (budget ${FIRST_DIAGNOSTICS_MS})`);
  assert.ok(total <= BUDGET_BYTES, `${total} bytes gzipped`);
  assert.ok(first <= FIRST_DIAGNOSTICS_MS, `first diagnostics after ${first} ms`);
  assert.deepEqual(asked.sort(), ['/', '/assets/millpath.wasm', '/assets/playground.js']);
  // highlighting from the grammar: the kind words and the path name
  assert.ok(await page.locator('.cm-content span', { hasText: /^sweep$/ }).count() > 0);
  await page.screenshot({ path: join(artifacts, 'playground.png') });
  await page.close();
});

test('typing removes a B: its error at the line millpath check names, within the edit budget', { skip, timeout: 120000 }, async () => {
  const { page, errors } = await open('?example=2001.mpath');
  assert.equal(await page.evaluate(() => window.playground.active()), '2001.mpath');
  assert.deepEqual(await page.evaluate(() => window.playground.diagnostics()), []);
  const text = readFileSync(join(work, '2001.mpath'), 'utf8');
  // the cursor after "B-0,2", then six backspaces
  const at = text.indexOf(' B-0,2') + ' B-0,2'.length;
  await page.evaluate((pos) => { const v = window.playground.view; v.focus(); v.dispatch({ selection: { anchor: pos } }); }, at);
  for (let i = 0; i < 6; i++) await page.keyboard.press('Backspace');
  await page.waitForFunction(() => window.playground.diagnostics().length > 0);
  const got = await page.evaluate(() => window.playground.diagnostics());
  // what the CLI says of the same text
  const dir = mkdtempSync(join(tmpdir(), 'millpath-b-'));
  copyFileSync(join(work, 'millpath.toml'), join(dir, 'millpath.toml'));
  execFileSync('sh', ['-c', `cat > "${dir}/2001.mpath"`], { input: text.replace(' B-0,2', '') });
  let report = '';
  try { execFileSync(bin, ['check', '--format', 'json', '2001.mpath'], { cwd: dir, stdio: 'pipe' }); } catch (e) { report = e.stdout.toString(); }
  const cli = JSON.parse(report);
  const want = (Array.isArray(cli) ? cli : cli.diagnostics || cli.files?.flatMap((f) => f.diagnostics)).find((d) => /B/.test(d.message));
  assert.ok(want, report);
  const mine = got.find((d) => d.code === want.code);
  assert.ok(mine, JSON.stringify(got));
  assert.equal(mine.message, want.message);
  assert.equal(mine.line, want.line ?? want.location?.line ?? want.range?.start?.line);
  // the editor shows it: a marker in the gutter, the squiggle at that line
  assert.ok(await page.locator('.cm-lint-marker-error').count() > 0);
  const edits = await page.evaluate(() => window.playground.timings.edits);
  const worst = Math.max(...edits);
  console.log(`# edit → diagnostics: ${edits.map((e) => e.toFixed(1)).join(', ')} ms (budget ${EDIT_MS})`);
  assert.ok(worst <= EDIT_MS, `${worst} ms`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('hover over an element shows its parameter table', { skip, timeout: 120000 }, async () => {
  const { page, errors } = await open('?example=2001.mpath');
  const line = page.locator('.cm-line', { hasText: 'mill (5, 0)' });
  const box = await line.locator('span', { hasText: /^mill$/ }).boundingBox();
  await page.mouse.move(box.x + 5, box.y + box.height / 2);
  const table = page.locator('.cm-tooltip-hover table');
  await table.waitFor({ timeout: 10000 });
  const cells = await table.locator('td, th').allTextContents();
  assert.ok(cells.length >= 6, cells.join('|'));
  // the depth the start gives (B-0,2), and where it comes from
  const b = cells.indexOf('B');
  assert.ok(b >= 0, cells.join('|'));
  assert.equal(cells[b + 1], '-0,2');
  assert.match(cells[b + 2], /path start \(line 4\)/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the G-code pane is what millpath compile writes, for every example', { skip, timeout: 180000 }, async () => {
  const { page, errors } = await open();
  for (const f of readdirSync(work).filter((n) => n.endsWith('.mpath')).sort()) {
    const want = compiled(work, f);
    await openFile(page, f);
    const got = await page.evaluate(() => window.playground.outputs());
    assert.deepEqual(got.files.map((x) => x.name).sort(), Object.keys(want).sort(), f);
    for (const x of got.files) assert.equal(x.content, want[x.name], `${f}: ${x.name}`);
    // and the pane shows the first of them, byte for byte
    const pane = await page.locator('#gcode').evaluate((e) => e.textContent);
    assert.equal(pane, want[got.files[0].name], f);
  }
  assert.deepEqual(errors, []);
  await page.close();
});

const DRAWING = '8999.01P.dxf';
const shared = existsSync(join(fixtures, DRAWING));
test('a shared drawing dropped as DXF: its text is dxf2text\'s, its G-code compile\'s', { skip: skip || (!shared && `no ${fixtures} (../shared absent)`), timeout: 120000 }, async () => {
  const { page, errors } = await open();
  const dir = mkdtempSync(join(tmpdir(), 'millpath-dxf-'));
  copyFileSync(join(work, 'millpath.toml'), join(dir, 'millpath.toml'));
  copyFileSync(join(fixtures, DRAWING), join(dir, DRAWING));
  const text = execFileSync(bin, ['dxf2text', DRAWING], { cwd: dir, stdio: ['ignore', 'pipe', 'ignore'] }).toString();
  const stem = DRAWING.replace(/\.dxf$/, '');
  execFileSync('sh', ['-c', `cat > "${dir}/${stem}.mpath"`], { input: text });
  const want = compiled(dir, `${stem}.mpath`);
  assert.ok(Object.keys(want).length > 0);
  // dropped on the page as a browser drops a file
  const n = await outputsCount(page);
  const bytes = [...readFileSync(join(dir, DRAWING))];
  await page.evaluate(({ name, bytes }) => {
    const dt = new DataTransfer();
    dt.items.add(new File([new Uint8Array(bytes)], name));
    document.querySelector('#editor').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, { name: DRAWING, bytes });
  await page.waitForFunction((k) => Number(document.body.dataset.outputs) > k && window.playground.active() === '8999.01P.mpath', n);
  const files = await page.evaluate(() => window.playground.files());
  assert.equal(files[`${stem}.mpath`], text);
  const got = await page.evaluate(() => window.playground.outputs());
  assert.deepEqual(got.files.map((x) => x.name).sort(), Object.keys(want).sort());
  for (const x of got.files) assert.equal(x.content, want[x.name], x.name);
  assert.deepEqual(errors, []);
  await page.close();
});

test('dxf2text in the page is the CLI\'s, for the drawings at hand', { skip, timeout: 120000 }, async () => {
  const { page } = await open();
  const drawings = [join(repo, 'examples/plate/1234.1P.dxf')];
  if (shared) drawings.push(...readdirSync(fixtures).filter((f) => f.endsWith('.dxf')).sort().slice(0, 8).map((f) => join(fixtures, f)));
  for (const d of drawings) {
    const dir = mkdtempSync(join(tmpdir(), 'millpath-d2t-'));
    const name = d.split('/').pop();
    copyFileSync(d, join(dir, name));
    copyFileSync(join(work, 'millpath.toml'), join(dir, 'millpath.toml'));
    let want;
    try { want = execFileSync(bin, ['dxf2text', name], { cwd: dir, stdio: ['ignore', 'pipe', 'ignore'] }).toString(); } catch { want = null; }
    const got = await page.evaluate(({ name, bytes }) => window.playground.dxf2text(name, bytes), { name, bytes: [...readFileSync(d)] });
    if (want === null) assert.ok(got.error, name);
    else assert.equal(got.text, want, name);
  }
  await page.close();
});

test('a share link reopens the same files', { skip, timeout: 120000 }, async () => {
  const { page } = await open('?example=2020.mpath');
  await page.evaluate(() => { const v = window.playground.view; v.dispatch({ changes: { from: 0, insert: '# ä shared edit 😀\n' } }); });
  await page.evaluate(() => { const t = window.playground.toml; t.dispatch({ changes: { from: t.state.doc.length, insert: 'lang = "de"\n' } }); });
  await page.locator('#share').click();
  await page.waitForFunction(() => document.querySelector('#share-url').value);
  const url = await page.locator('#share-url').inputValue();
  assert.match(url, /#v1\.[A-Za-z0-9_-]+$/);
  const files = await page.evaluate(() => window.playground.files());
  const toml = await page.evaluate(() => window.playground.toml.state.doc.toString());
  await page.close();
  const again = await open(url.slice(server.url.length));
  assert.deepEqual(await again.page.evaluate(() => window.playground.files()), files);
  assert.equal(await again.page.evaluate(() => window.playground.toml.state.doc.toString()), toml);
  assert.equal(await again.page.evaluate(() => window.playground.active()), '2020.mpath');
  assert.deepEqual(again.errors, []);
  await again.page.close();
});

test('clicking a move in the toolpath selects its source line', { skip, timeout: 120000 }, async () => {
  const { page, errors } = await open('?example=2010.mpath');
  await page.waitForFunction(() => window.playground.viewer() && window.playground.viewer().drawnMoves() > 0);
  const data = await page.evaluate(() => window.playground.toolpath());
  // the mark element (line 8 of 2010.mpath): its first move
  const i = data.moves.findIndex((m) => data.sources[m.source] && data.sources[m.source].line === 7 && data.sources[m.source].file.endsWith('2010.mpath'));
  assert.ok(i >= 0);
  await page.evaluate(() => window.playground.viewer().setView('top'));
  const frame = await page.locator('#viewer').boundingBox();
  const [x, y] = await page.evaluate((k) => window.playground.viewer().screenOf(k, 0.5), i);
  await page.mouse.click(frame.x + x, frame.y + y);
  await page.waitForFunction(() => document.body.dataset.revealed);
  assert.equal(await page.evaluate(() => document.body.dataset.revealed), '2010.mpath:8');
  const sel = await page.evaluate(() => { const v = window.playground.view; const s = v.state.selection.main; return [v.state.doc.lineAt(s.from).number, v.state.sliceDoc(s.from, s.to)]; });
  assert.equal(sel[0], 8);
  assert.match(sel[1], /^\s*mark \(40, 20\)/);
  assert.deepEqual(errors, []);
  await page.close();
});
