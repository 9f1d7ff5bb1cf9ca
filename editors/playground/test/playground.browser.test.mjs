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
import { WORDS as VIEWER_WORDS } from '../../toolpath/src/words.js';

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
// Wall-clock budgets are judged with PLAYGROUND_TIME_BUDGETS=1 on a quiet machine; otherwise
// (CI on a shared machine) the figures are printed and only a hang (30 s) fails: speed is
// checked by benchmarks, not by timed tests.
const strictTime = process.env.PLAYGROUND_TIME_BUDGETS === '1';
const withinTime = (ms, budget) => ms <= (strictTime ? budget : 30000);

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

/** What `millpath compile` writes for `file` in `dir` (with `args`): {name: content}. */
function compiled(dir, file, args = []) {
  const before = new Set(readdirSync(dir));
  for (const f of before) if (/_(Milling|Clean|Probing)\.gcode$|_Z\.txt$/.test(f)) execFileSync('rm', [join(dir, f)]);
  execFileSync(bin, ['compile', ...args, file], { cwd: dir, stdio: 'pipe' });
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
  assert.ok(withinTime(first, FIRST_DIAGNOSTICS_MS), `first diagnostics after ${first} ms`);
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
  assert.ok(withinTime(worst, EDIT_MS), `${worst} ms`);
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

test('the post selector: the G-code switches to what millpath compile --post writes', { skip, timeout: 180000 }, async () => {
  const { page, errors } = await open('?example=2001.mpath');
  const offered = await page.$$eval('#post option', (os) => os.map((o) => o.value));
  for (const p of ['', 'reference', 'linuxcnc', 'grbl', 'mach3']) assert.ok(offered.includes(p), JSON.stringify(offered));
  const seen = {};
  for (const post of ['grbl', 'linuxcnc', 'mach3', 'grbl']) {
    const n = await outputsCount(page);
    await page.selectOption('#post', post);
    await page.waitForFunction((k) => Number(document.body.dataset.outputs) > k, n);
    const got = await page.evaluate(() => window.playground.outputs());
    const want = compiled(work, '2001.mpath', ['--post', post]);
    assert.deepEqual(got.files.map((x) => x.name).sort(), Object.keys(want).sort(), post);
    for (const x of got.files) assert.equal(x.content, want[x.name], `${post}: ${x.name}`);
    const pane = await page.locator('#gcode').evaluate((e) => e.textContent);
    assert.equal(pane, want[got.files[0].name], post);
    seen[post] = pane;
  }
  // GRBL writes no `%` lines, LinuxCNC does; Mach3's program is another again
  assert.ok(seen.linuxcnc.startsWith('%\n') && !seen.grbl.startsWith('%'));
  assert.notEqual(seen.mach3, seen.linuxcnc);
  // the toolpath view follows the post too: its moves name lines of the program shown
  const tp = await page.evaluate(() => window.playground.toolpath());
  const mill = tp.moves.find((m) => m.kind === 'mill');
  assert.equal(seen.grbl.split('\n')[mill.line - 1], mill.gcode);
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

/** The toolbars of the viewer (in its iframe): each bar's overflow and every item's place. */
async function viewerBars(page) {
  return page.evaluate(() => {
    const doc = document.getElementById('viewer').contentDocument;
    return ['header', '#playbar'].map((sel) => {
      const bar = doc.querySelector(sel), box = bar.getBoundingClientRect();
      const outside = [...bar.children].filter((c) => {
        const r = c.getBoundingClientRect();
        return r.width > 0 && (r.left < box.left - 0.5 || r.right > box.right + 0.5);
      }).map((c) => c.id || c.className || c.tagName);
      return { bar: sel, overflow: bar.scrollWidth - bar.clientWidth, outside, page: doc.documentElement.scrollWidth - doc.documentElement.clientWidth };
    });
  });
}

test('the layout at 1280, 1400 and 1920 px: a click in the editor shifts nothing sideways, the toolbars stay in their boxes', { skip, timeout: 180000 }, async () => {
  for (const width of [1280, 1400, 1920]) {
    for (const lang of ['en', 'de']) {
      const { page, errors } = await open(`?example=2010.mpath&lang=${lang}`, { width, height: 850 });
      await page.waitForFunction(() => window.playground.viewer() && window.playground.viewer().drawnMoves() > 0);
      // a click at the end of the longest line of the editor, then the cursor to its end
      const lines = page.locator('#editor .cm-line');
      let longest = 0, most = -1;
      for (let k = 0; k < await lines.count(); k++) {
        const n = (await lines.nth(k).textContent()).length;
        if (n > most) { most = n; longest = k; }
      }
      const box = await lines.nth(longest).boundingBox();
      await page.mouse.click(box.x + Math.min(box.width - 2, 400), box.y + box.height / 2);
      await page.keyboard.press('End');
      await page.waitForTimeout(150);
      const m = await page.evaluate(() => {
        const r = (el) => el.getBoundingClientRect();
        const left = document.getElementById('left'), toml = document.getElementById('toml-pane');
        const gutter = document.querySelector('#editor .cm-gutters');
        // nothing scrolled sideways but the editors' own scrollers
        const shifted = [document.documentElement, document.body, ...document.querySelectorAll('main, main *')]
          .filter((e) => e.scrollLeft !== 0 && !e.classList.contains('cm-scroller'))
          .map((e) => `${e.tagName}#${e.id}.${e.className}: ${e.scrollLeft}`);
        return {
          shifted,
          gutterInside: r(gutter).left - r(left).left,
          tomlInside: [r(toml).left - r(left).left, r(left).right - r(toml).right],
          pageOverflow: document.documentElement.scrollWidth - document.documentElement.clientWidth,
          focused: document.activeElement && document.activeElement.classList.contains('cm-content'),
        };
      });
      const at = `${width} px, ${lang}`;
      assert.ok(m.focused, `${at}: the click focused the editor`);
      assert.deepEqual(m.shifted, [], `${at}: scrolled sideways`);
      assert.ok(m.gutterInside >= 0, `${at}: the line numbers start ${m.gutterInside} px left of the column`);
      assert.ok(m.tomlInside[0] >= 0 && m.tomlInside[1] >= -0.5, `${at}: the settings pane reaches out of the column: ${m.tomlInside}`);
      assert.ok(m.pageOverflow <= 0, `${at}: the page scrolls sideways by ${m.pageOverflow} px`);
      for (const b of await viewerBars(page)) {
        assert.ok(b.overflow <= 0 && b.page <= 0, `${at}: the viewer's ${b.bar} overflows by ${b.overflow} px (page ${b.page})`);
        assert.deepEqual(b.outside, [], `${at}: items of the viewer's ${b.bar} outside it`);
      }
      if (width === 1400) await page.screenshot({ path: join(artifacts, `playground-1400-${lang}.png`) });
      assert.deepEqual(errors, []);
      await page.close();
    }
  }
});

/** The English words of the viewer's controls that German does not share (from its one
 *  source of words, function words with placeholders): none may show in German. */
function englishOnly() {
  const words = (table) => {
    const out = [];
    const add = (v) => {
      if (typeof v === 'function') v = v(7, 8, 9, 10);
      if (typeof v === 'string') out.push(...v.split(/[^A-Za-zÄÖÜäöüß-]+/));
      else if (v && typeof v === 'object') Object.values(v).forEach(add);
    };
    Object.values(table).forEach(add);
    return out.filter((x) => x.replace(/-/g, '').length >= 3);
  };
  const german = new Set(words(VIEWER_WORDS.de).map((x) => x.toLowerCase()));
  return [...new Set(words(VIEWER_WORDS.en))].filter((x) => !german.has(x.toLowerCase()));
}

/** The viewer's control labels, titles, legend and hint as shown, then the info line after
 *  hovering move `i` (`offset`: the viewer's place in the page). */
async function viewerLabels(page, doc, offset, i) {
  const shown = await page.evaluate(`(() => {
    const d = ${doc};
    const texts = [...d.querySelectorAll('header, #playbar, summary, #legend, #info, #empty')].map((e) => e.innerText);
    const attrs = [...d.querySelectorAll('[title], [aria-label]')].map((e) => [e.title, e.getAttribute('aria-label')].join(' '));
    const options = [...d.querySelectorAll('option')].map((o) => o.textContent);
    return { lang: d.documentElement.lang, all: [...texts, ...attrs, ...options].join('\\n') };
  })()`);
  const [x, y] = await page.evaluate(`(${doc}).defaultView.millpathToolpath.screenOf(${i}, 0.5)`);
  await page.mouse.move(offset.x + x, offset.y + y);
  await page.waitForFunction(`/\\d+\\/\\d+/.test((${doc}).getElementById('info').textContent)`);
  shown.info = await page.evaluate(`(${doc}).getElementById('info').textContent`);
  return shown;
}

function assertGerman(shown, where) {
  assert.equal(shown.lang, 'de', where);
  const found = englishOnly().filter((w) => new RegExp(`(^|[^A-Za-zÄÖÜäöüß])${w}([^A-Za-zÄÖÜäöüß]|$)`).test(shown.all));
  assert.deepEqual(found, [], `${where}: English words in German: ${found.join(', ')}\n${shown.all}`);
  for (const w of ['Farbe', 'nach Tiefe', 'gefrästes Teil', 'Werkzeugbreite', 'Legende', 'Tempo', 'Raster', 'Eine Bewegung berühren']) {
    assert.ok(shown.all.includes(w), `${where}: no "${w}"\n${shown.all}`);
  }
  // the hover line: its words German (the element's own text is the user's)
  assert.match(shown.info, /^Bewegung \d+\/\d+ .*\nG-Code-Zeile \d+/s, where);
}

test('in German the toolpath viewer has no English control label: the playground and millpath render\'s page', { skip, timeout: 120000 }, async () => {
  assert.ok(englishOnly().length > 30, englishOnly().join(' '));
  // the playground in German: the viewer follows the page's language
  const { page, errors } = await open('?example=2010.mpath&lang=de');
  await page.waitForFunction(() => window.playground.viewer() && window.playground.viewer().drawnMoves() > 0);
  const frame = await page.locator('#viewer').boundingBox();
  const doc = "document.getElementById('viewer').contentDocument";
  assertGerman(await viewerLabels(page, doc, frame, 3), 'playground');
  // and back to English at once
  await page.selectOption('#lang', 'en');
  await page.waitForFunction(() => document.getElementById('viewer').contentDocument.documentElement.lang === 'en');
  const en = await page.evaluate(() => document.getElementById('viewer').contentDocument.querySelector('header').innerText);
  assert.match(en, /colour/);
  assert.deepEqual(errors, []);
  await page.close();
  // the page millpath render writes with --lang de (the data carries the language)
  const dir = mkdtempSync(join(tmpdir(), 'millpath-render-de-'));
  for (const f of readdirSync(work)) if (/\.mpath$|^millpath\.toml$/.test(f)) copyFileSync(join(work, f), join(dir, f));
  execFileSync(bin, ['render', '2010.mpath', '--lang', 'de', '--html', 'de.html'], { cwd: dir, stdio: 'pipe' });
  const p2 = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  const errs2 = [];
  p2.on('pageerror', (e) => errs2.push(e.message));
  await p2.goto(`file://${join(dir, 'de.html')}`);
  await p2.waitForFunction(() => document.body.dataset.ready);
  assertGerman(await viewerLabels(p2, 'document', { x: 0, y: 0 }, 3), 'millpath render --lang de');
  assert.deepEqual(errs2, []);
  await p2.close();
});
