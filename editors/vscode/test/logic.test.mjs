// Unit tests of the extension's logic (no VS Code needed).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createRequire } from 'node:module';
const require = createRequire(import.meta.url);
const logic = require('../dist/logic.js');

test('initialization options carry only the settings that are set', () => {
  assert.deepEqual(logic.initializationOptions({ feed: 150, sweepSpeed: null, sweepHeight: 12.5, probeFeed: undefined, language: 'de' }), {
    feed: 150,
    sweep_height: 12.5,
    lang: 'de',
  });
  assert.deepEqual(logic.initializationOptions({ feed: Number.NaN, language: 'fr' }), {});
  // the feed override as millpath.toml's key
  assert.deepEqual(logic.initializationOptions({ feedOverride: 120 }), { feed_override: 120 });
  assert.deepEqual(logic.initializationOptions({ feedOverride: null }), {});
});

test('server command: setting, bundled binary, PATH', () => {
  assert.equal(logic.serverCommand(' /opt/millpath ', '/ext/server/millpath', () => true), '/opt/millpath');
  assert.equal(logic.serverCommand('', '/ext/server/millpath', () => true), '/ext/server/millpath');
  assert.equal(logic.serverCommand('', '/ext/server/millpath', () => false), 'millpath');
});

test('server lookup: setting, the .vsix server, PATH, else a clear error', () => {
  const has = (...ps) => (p) => ps.includes(p);
  assert.deepEqual(logic.findServer(' /opt/mp ', '/ext/server/millpath', '/usr/bin', 'linux', has('/opt/mp')), { command: '/opt/mp', source: 'setting' });
  assert.match(logic.findServer('/opt/mp', '/ext/server/millpath', '/usr/bin', 'linux', has()).error, /millpath\.server\.path is set to '\/opt\/mp'/);
  assert.deepEqual(logic.findServer('', '/ext/server/millpath', '/usr/bin', 'linux', has('/ext/server/millpath', '/usr/bin/millpath')), { command: '/ext/server/millpath', source: 'bundled' });
  assert.deepEqual(logic.findServer('', '/ext/server/millpath', '/bin:/usr/local/bin/', 'linux', has('/usr/local/bin/millpath')), { command: '/usr/local/bin/millpath', source: 'PATH' });
  assert.deepEqual(logic.findServer('', undefined, 'C:\\bin;D:\\mp', 'win32', has('D:\\mp\\millpath.exe')), { command: 'D:\\mp\\millpath.exe', source: 'PATH' });
  const none = logic.findServer('', '/ext/server/millpath', '/usr/bin', 'darwin', has());
  assert.match(none.error, /brings none for darwin.*no 'millpath' on PATH.*millpath\.server\.path/);
});

test('preview URIs round-trip source and path', () => {
  const src = 'file:///home/me/parts/2010 a.mpath';
  const u = logic.previewUri(src, '2010.1P');
  assert.ok(u.startsWith('millpath-preview:/2010.1P.gcode?'));
  assert.deepEqual(logic.parsePreviewUri(u), { source: src, path: '2010.1P' });
  assert.deepEqual(logic.parsePreviewUri(logic.previewUri(src, undefined)), { source: src, path: undefined });
  assert.equal(logic.parsePreviewUri('file:///x'), undefined);
});

test('the path around the cursor', () => {
  const text = '# x\npath 2001.1P {\n  start (0, 0)\n}\n\npath "odd name" {\n  end (1, 1)\n}\n';
  assert.equal(logic.pathAtLine(text, 2), '2001.1P');
  assert.equal(logic.pathAtLine(text, 6), 'odd name');
  assert.equal(logic.pathAtLine(text, 0), '2001.1P');
  assert.equal(logic.pathAtLine('nothing', 0), undefined);
});

test('status text from statistics lines (English and German)', () => {
  const en = ['Milling length:   115 mm   ca.  2 min', 'Drill length:     4 mm   ca.  1 min', 'Sweeps:         66 mm   ca.  1 min', 'Sum:           185 mm   ca.  2 min', 'Command count: 8'];
  assert.equal(logic.statusText('8999.1P', en), '8999.1P · 185 mm · ≈2 min · 8 commands');
  const de = ['Fräslänge:     115 mm   ca.  2 min', 'Bohrungen:       4 mm   ca.  1 min', 'Leerfahrten:    66 mm   ca.  1 min', 'Summe:         185 mm   ca.  2 min', 'Befehlszahl: 8'];
  assert.equal(logic.statusText('8999.1P', de), '8999.1P · 185 mm · ≈2 min · 8 commands');
  // the exact time instead of the whole minutes when the server sends it
  assert.equal(logic.statusText('8999.1P', en, '0:01:47'), '8999.1P · 185 mm · 0:01:47 · 8 commands');
  assert.equal(logic.statusText('8999.1P', en, ''), '8999.1P · 185 mm · ≈2 min · 8 commands');
  assert.equal(logic.statusText('8999.1P', en, 'soon'), '8999.1P · 185 mm · ≈2 min · 8 commands');
  // the feed override the estimate assumes follows the time (none at 100 %)
  assert.equal(logic.statusText('8999.1P', en, '0:01:31', 120), '8999.1P · 185 mm · 0:01:31 at 120 % · 8 commands');
  assert.equal(logic.statusText('8999.1P', en, '', 80), '8999.1P · 185 mm · ≈2 min at 80 % · 8 commands');
  assert.equal(logic.statusText('8999.1P', en, '0:01:47', 100), '8999.1P · 185 mm · 0:01:47 · 8 commands');
  assert.equal(logic.statusText('8999.1P', en, '0:01:47', null), '8999.1P · 185 mm · 0:01:47 · 8 commands');
});

test('preview text: the G-code, or the errors instead of it', () => {
  assert.equal(logic.previewText({ path: 'a', gcode: '%\nM30\n%\n', stats: [], errors: [] }), '%\nM30\n%\n');
  const refused = logic.previewText({ path: '2001.1P', gcode: '', stats: [], errors: ['B value missing', 'path 2001.1P cannot be built: (x)'] });
  assert.equal(refused, '(millpath: B value missing)\n(millpath: path 2001.1P cannot be built: [x])\n');
  // errors beside G-code (placeholder settings) come first
  assert.ok(logic.previewText({ path: 'a', gcode: 'G00 Z5\n', stats: [], errors: ['feed missing'] }).startsWith('(millpath: feed missing)\nG00 Z5'));
});

test('source references from the toolpath page are checked', () => {
  assert.ok(logic.isSourceRef({ file: '/a.mpath', line: 3, character: 2 }));
  assert.ok(!logic.isSourceRef({ file: '/a.mpath', line: '3' }));
  assert.ok(!logic.isSourceRef(null));
});

test('compare with HEAD: the diff command writes the page of a changed file, no change opens it too, errors are shown', async () => {
  const { execFileSync, spawnSync } = await import('node:child_process');
  const { mkdtempSync, writeFileSync, readFileSync, existsSync } = await import('node:fs');
  const { tmpdir } = await import('node:os');
  const { join, dirname, resolve } = await import('node:path');
  const { fileURLToPath } = await import('node:url');
  const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../../..');
  const bin = process.env.MILLPATH_BIN || join(repo, 'target/release/millpath');
  const dir = mkdtempSync(join(tmpdir(), 'mp-compare-'));
  const git = (...a) => execFileSync('git', a, { cwd: dir });
  const slot = (x) => `path 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (${x}, 0)\n  sweep (${x}, 0) -> (30, 0)\n}\n`;
  const file = join(dir, '2001.mpath');
  git('init', '-q');
  git('config', 'user.email', 't@example.com');
  git('config', 'user.name', 't');
  writeFileSync(file, slot(25));
  git('add', '.');
  git('commit', '-qm', 'first');
  assert.deepEqual(logic.compareArgs(file, '/t/p.html'), ['diff', 'HEAD', '--html', '/t/p.html', '--', file]);
  const compare = (html, rev) => {
    const r = spawnSync(bin, logic.compareArgs(file, html, rev), { cwd: dir, encoding: 'utf8' });
    return logic.compareOutcome(r.status, r.stderr ?? '', r.error?.message);
  };
  const same = join(dir, 'same.html');
  assert.deepEqual(compare(same), { open: true, changed: false });
  assert.ok(existsSync(same));
  writeFileSync(file, slot(20));
  const changed = join(dir, 'changed.html');
  assert.deepEqual(compare(changed), { open: true, changed: true });
  const page = readFileSync(changed, 'utf8');
  assert.match(page, /<svg/);
  assert.match(page, /mill \(5, 0\) -&gt; \(20, 0\)|mill \(5, 0\) -> \(20, 0\)/);
  const bad = compare(join(dir, 'bad.html'), 'no-such-rev');
  assert.equal(bad.open, false);
  assert.match(bad.message, /no-such-rev/);
  assert.equal(existsSync(join(dir, 'bad.html')), false);
  // a missing binary: its error, no page
  assert.deepEqual(logic.compareOutcome(null, '', 'spawn millpath ENOENT'), { open: false, changed: false, message: 'spawn millpath ENOENT' });
});
