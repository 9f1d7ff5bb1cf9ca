// Drives `millpath lsp` exactly as the extension does (its initialization options, the
// preview and toolpath requests) with vscode-jsonrpc.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, writeFileSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createRequire } from 'node:module';
const require = createRequire(import.meta.url);
const rpc = require('vscode-jsonrpc/node');
const logic = require('../dist/logic.js');

const repo = join(dirname(fileURLToPath(import.meta.url)), '../../..');
const bin = process.env.MILLPATH_BIN || join(repo, 'target/release/millpath');
// under Wine (tests/windows.sh: MILLPATH_WINE=1) the server is a Windows program, which
// knows files by drive letter: Wine's drive Z: is the Unix root
const fileUri = (p) => (process.env.MILLPATH_WINE ? `file:///Z:${pathToFileURL(p).pathname}` : pathToFileURL(p).href);

test('initialize with the extension options, preview and toolpath', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'millpath-vscode-'));
  const text = readFileSync(join(repo, 'examples/text/2020.mpath'), 'utf8');
  const file = join(dir, '2020.mpath');
  writeFileSync(file, text);
  const proc = spawn(bin, ['lsp'], { stdio: ['pipe', 'pipe', 'ignore'] });
  const conn = rpc.createMessageConnection(new rpc.StreamMessageReader(proc.stdout), new rpc.StreamMessageWriter(proc.stdin));
  const diagnostics = new Promise((resolve) => conn.onNotification('textDocument/publishDiagnostics', resolve));
  conn.listen();
  const settings = { feed: 300, sweepSpeed: 1000, sweepHeight: 10, probeFeed: 50, language: 'en' };
  const init = await conn.sendRequest('initialize', {
    processId: process.pid,
    rootUri: fileUri(dir),
    capabilities: {},
    initializationOptions: logic.initializationOptions(settings),
    workspaceFolders: [{ uri: fileUri(dir), name: 'ws' }],
  });
  assert.equal(init.serverInfo.name, 'millpath');
  assert.ok(init.capabilities.hoverProvider);
  await conn.sendNotification('initialized', {});
  const uri = fileUri(file);
  await conn.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'millpath', version: 1, text } });
  const d = await diagnostics;
  assert.deepEqual(d.diagnostics, []);

  const path = logic.pathAtLine(text, 3);
  assert.equal(path, '2020.1P');
  const pv = await conn.sendRequest('millpath/gcodePreview', { textDocument: { uri }, path });
  // the settings from the extension were used: feed 300, probe feed 50
  assert.match(pv.gcode, /G01 F300\.000/);
  assert.match(pv.probing, /G38\.3 Z0 F50\.000/);
  assert.equal(pv.stats.length, 5);
  assert.match(logic.statusText(pv.path, pv.stats), /^2020\.1P · \d+ mm/);
  // the exact time, which the status bar shows instead of the whole minutes
  assert.match(pv.time, /^\d+:\d\d:\d\d$/);
  assert.match(logic.statusText(pv.path, pv.stats, pv.time), new RegExp(`^2020\\.1P · \\d+ mm · ${pv.time} · \\d+ commands$`));
  // and it is what `millpath compile` writes with the same settings (its summary: the same time)
  const summary = spawnSync(bin, ['compile', '-f', '300', '-v', '1000', '-s', '10', '-z', '50', '--lang', 'en', file], { encoding: 'utf8' }).stderr;
  assert.equal(pv.gcode, readFileSync(join(dir, '2020_Clean.gcode'), 'utf8'));
  assert.match(summary, new RegExp(`Estimated time: ${pv.time}\\n`));

  // a path compile would refuse: a result (not an error) whose errors the preview shows
  const refused = await conn.sendRequest('millpath/gcodePreview', { textDocument: { uri }, path: '2020.1p' });
  assert.equal(refused.gcode, '');
  assert.match(refused.errors[0], /no path 2020\.1p/);
  assert.match(logic.previewText(refused), /^\(millpath: no path 2020\.1p/);

  const tp = await conn.sendRequest('millpath/toolpath', { textDocument: { uri }, path });
  assert.equal(tp.path, '2020.1P');
  assert.ok(tp.moves.length > 5);
  const mill = tp.moves.find((m) => m.kind === 'mill');
  assert.equal(tp.sources[mill.source].line, 5);
  assert.equal(tp.sources[mill.source].text, 'mill (0, 0) -> (60, 0)');
  // each move names its line of the program the preview shows
  assert.equal(pv.gcode.split('\n')[mill.line - 1], mill.gcode);
  assert.equal(tp.probes.length, 2);

  await assert.rejects(conn.sendRequest('millpath/toolpath', { textDocument: { uri }, path: '9.9Q' }));
  await conn.sendRequest('shutdown');
  await conn.sendNotification('exit');
  conn.dispose();
  proc.kill();
});

test('a post file: the extension serves it, its errors are diagnostics, the preview writes through it', async () => {
  // the extension sends millpath.toml and the post files of posts/ to the server
  assert.ok(logic.documentSelector.some((s) => s.pattern === '**/posts/*.toml'));
  assert.ok(logic.documentSelector.some((s) => s.pattern === '**/millpath.toml'));
  const dir = mkdtempSync(join(tmpdir(), 'millpath-vscode-post-'));
  mkdirSync(join(dir, 'posts'));
  const shown = spawnSync(bin, ['post', 'show', 'grbl'], { encoding: 'utf8' }).stdout;
  const mine = shown.replace('name = "grbl"', 'name = "mine"').replace('decimals = 3', 'decimals = 4');
  const broken = mine.replace('tool = "T{tool_number}"', 'tool = "T{tool_numbr}"');
  const postFile = join(dir, 'posts/mine.toml');
  writeFileSync(postFile, broken);
  writeFileSync(join(dir, 'millpath.toml'), 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\npost = "posts/mine.toml"\n');
  const text = readFileSync(join(repo, 'examples/text/2020.mpath'), 'utf8');
  const file = join(dir, '2020.mpath');
  writeFileSync(file, text);
  const proc = spawn(bin, ['lsp'], { stdio: ['pipe', 'pipe', 'ignore'] });
  const conn = rpc.createMessageConnection(new rpc.StreamMessageReader(proc.stdout), new rpc.StreamMessageWriter(proc.stdin));
  const waiting = new Map();
  // the server may spell a URI another way than the client (Windows: `Z%3A` for `Z:`), as
  // VS Code and Neovim allow: the same file either way; a missing answer fails, never hangs
  const sameFile = (u) => decodeURIComponent(u).replace(/^file:\/\/\/([a-z]):/i, (m, d) => `file:///${d.toUpperCase()}:`);
  conn.onNotification('textDocument/publishDiagnostics', (p) => {
    const w = waiting.get(sameFile(p.uri));
    if (w) { waiting.delete(sameFile(p.uri)); w(p); }
  });
  const diagnosticsOf = (uri) => new Promise((resolve, reject) => {
    waiting.set(sameFile(uri), resolve);
    setTimeout(() => reject(new Error(`no diagnostics for ${uri} in 60 s`)), 60000).unref();
  });
  conn.listen();
  await conn.sendRequest('initialize', {
    processId: process.pid, rootUri: fileUri(dir), capabilities: {},
    initializationOptions: logic.initializationOptions({ language: 'en' }),
    workspaceFolders: [{ uri: fileUri(dir), name: 'ws' }],
  });
  await conn.sendNotification('initialized', {});
  const postUri = fileUri(postFile);
  let d = diagnosticsOf(postUri);
  await conn.sendNotification('textDocument/didOpen', { textDocument: { uri: postUri, languageId: 'toml', version: 1, text: broken } });
  const found = (await d).diagnostics;
  assert.equal(found.length, 1);
  assert.match(found[0].message, /templates\.tool: unknown variable \{tool_numbr\}/);
  assert.equal(found[0].range.start.line, broken.split('\n').findIndex((l) => l.startsWith('tool = ')));
  // fixed and saved: no diagnostics, and the drawing's preview is written by this post
  writeFileSync(postFile, mine);
  d = diagnosticsOf(postUri);
  await conn.sendNotification('textDocument/didChange', { textDocument: { uri: postUri, version: 2 }, contentChanges: [{ text: mine }] });
  assert.deepEqual((await d).diagnostics, []);
  const uri = fileUri(file);
  d = diagnosticsOf(uri);
  await conn.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'millpath', version: 1, text } });
  assert.deepEqual((await d).diagnostics, []);
  const pv = await conn.sendRequest('millpath/gcodePreview', { textDocument: { uri }, path: '2020.1P' });
  assert.match(pv.gcode, /X60\.0000/);
  spawnSync(bin, ['compile', file], { encoding: 'utf8' });
  assert.equal(pv.gcode, readFileSync(join(dir, '2020_Clean.gcode'), 'utf8'));
  await conn.sendRequest('shutdown');
  await conn.sendNotification('exit');
  conn.dispose();
  proc.kill();
});

test('the feed override setting reaches the server: the estimate at that override', async () => {
  // a machine model (LinuxCNC's planner from [machine]): the estimate follows the override
  const dir = mkdtempSync(join(tmpdir(), 'millpath-vscode-'));
  const text = readFileSync(join(repo, 'examples/text/2020.mpath'), 'utf8');
  const file = join(dir, '2020.mpath');
  writeFileSync(file, text);
  writeFileSync(join(dir, 'millpath.toml'), '[machine]\nmax_velocity = 4000\nmax_acceleration = 200\n');
  const seconds = (hms) => hms.split(':').reduce((a, v) => a * 60 + Number(v), 0);
  const preview = async (feedOverride) => {
    const proc = spawn(bin, ['lsp'], { stdio: ['pipe', 'pipe', 'ignore'] });
    const conn = rpc.createMessageConnection(new rpc.StreamMessageReader(proc.stdout), new rpc.StreamMessageWriter(proc.stdin));
    conn.listen();
    const settings = { feed: 300, sweepSpeed: 1000, sweepHeight: 10, probeFeed: 50, feedOverride, language: 'en' };
    await conn.sendRequest('initialize', {
      processId: process.pid,
      rootUri: fileUri(dir),
      capabilities: {},
      initializationOptions: logic.initializationOptions(settings),
      workspaceFolders: [{ uri: fileUri(dir), name: 'ws' }],
    });
    await conn.sendNotification('initialized', {});
    const uri = fileUri(file);
    await conn.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'millpath', version: 1, text } });
    const pv = await conn.sendRequest('millpath/gcodePreview', { textDocument: { uri }, path: '2020.1P' });
    await conn.sendRequest('shutdown');
    await conn.sendNotification('exit');
    conn.dispose();
    proc.kill();
    return pv;
  };
  const plain = await preview(null);
  const faster = await preview(300);
  // the same moves (the statistics in the program's comments name the override), a shorter
  // estimate (but more than a third: rapids and ramps stay)
  const moves = (gcode) => gcode.split('\n').filter((l) => !l.trim().startsWith('('));
  assert.deepEqual(moves(faster.gcode), moves(plain.gcode));
  assert.match(faster.gcode, /feed override 300 %/);
  assert.doesNotMatch(plain.gcode, /override/);
  assert.ok(seconds(faster.time) < seconds(plain.time), `${faster.time} ${plain.time}`);
  assert.ok(seconds(faster.time) > seconds(plain.time) / 3, `${faster.time} ${plain.time}`);
  // what `millpath compile --feed-override 300` says, and the status bar names it
  const summary = spawnSync(bin, ['compile', '-f', '300', '-v', '1000', '-s', '10', '-z', '50', '--feed-override', '300', '--lang', 'en', file], { encoding: 'utf8' }).stderr;
  assert.match(summary, new RegExp(`Estimated time: ${faster.time}\\n`));
  assert.match(summary, /feed override 300 %/);
  assert.match(logic.statusText(faster.path, faster.stats, faster.time, 300), new RegExp(`· ${faster.time} at 300 % ·`));
});

// The diff editor's effect summary: the arguments the extension gives `millpath diff` for the
// copies of two versions it reads from VS Code, and the line it shows from the JSON answer.
// (not under Wine: tests/windows.sh runs this file for the language server; the extension runs
// `millpath diff` with the host's paths, and Wine's were not tried)
test('effect summary of a diff editor from millpath diff', { skip: process.env.MILLPATH_WINE ? 'the language server only, under Wine' : false }, () => {
  const dir = mkdtempSync(join(tmpdir(), 'millpath-effect-'));
  for (const f of ['2001.mpath', '2010.mpath', '2020.mpath', 'millpath.toml']) writeFileSync(join(dir, f), readFileSync(join(repo, 'examples/text', f)));
  const text = readFileSync(join(dir, '2001.mpath'), 'utf8');
  // the sides as the git extension names them: the index (~) and the file on disk
  const old = logic.diffSide('git', '/x/2001.mpath.git', JSON.stringify({ path: join(dir, '2001.mpath'), ref: '~' }));
  const neu = logic.diffSide('file', join(dir, '2001.mpath'), '');
  assert.deepEqual([old.label, neu.label], ['index', 'working tree']);
  const copies = mkdtempSync(join(tmpdir(), 'millpath-effect-copies-'));
  const [of, nf] = logic.copyFolders(old, neu);
  mkdirSync(join(copies, of));
  mkdirSync(join(copies, nf));
  writeFileSync(join(copies, of, '2001.mpath'), text);
  writeFileSync(join(copies, nf, '2001.mpath'), text.replace('B-0,2', 'B-0,5'));
  const run = (format, settings = {}, files = [join(of, '2001.mpath'), join(nf, '2001.mpath')], at = neu.drawing) =>
    spawnSync(bin, logic.effectArgs(files[0], files[1], at, format, settings), { cwd: copies, encoding: 'utf8' });
  const r = run('json');
  assert.equal(r.status, 1, r.stderr);
  const json = JSON.parse(r.stdout);
  const line = logic.effectLine(json);
  assert.match(line, /^millpath: 1 path changed; 1 element edited, 1 more reached by the effect · 2001\.1P: /);
  assert.match(line, /B -0,2 → -0,5 on 1 element \(path start \(line 4\)\); lowest Z -0\.2 → -0\.5; milling 63\.2 → 63\.5 mm; /);
  assert.match(line, /; 12 moves; G-code changed$/);
  // the time as millpath.toml beside the drawing makes it (F and sweeps of the examples)
  const seconds = json.files[0].paths[0].after.seconds;
  const clock = `${Math.floor(seconds / 3600)}:${String(Math.floor(seconds / 60) % 60).padStart(2, '0')}:${String(Math.round(seconds) % 60).padStart(2, '0')}`;
  assert.ok(line.includes(clock), `${clock} in ${line}`);
  // the extension's machine settings are passed as the language server gets them
  assert.deepEqual(logic.effectArgs('a', 'b', '/w/c.mpath', 'json', { feed: 10, sweepHeight: Number.NaN, language: 'de' }),
    ['diff', '--format', 'json', '--at', '/w/c.mpath', '--feed', '10', '--lang', 'de', 'a', 'b']);
  assert.equal(run('json', { feed: 10 }).status, 1);
  // the markdown report for the hover and the command
  const md = run('markdown');
  assert.equal(md.status, 1, md.stderr);
  assert.match(md.stdout, /^### index\/2001\.mpath → working tree\/2001\.mpath/);
  assert.match(md.stdout, /\| lowest Z \| -0\.2 \| \*\*-0\.5\*\* \|/);
  // German: every message the line uses is in the bundle, numbers with decimal commas
  const de = JSON.parse(readFileSync(join(repo, 'editors/vscode/l10n/bundle.l10n.de.json'), 'utf8'));
  const used = new Set();
  const t = (m, ...args) => {
    used.add(m);
    return logic.english(de[m] ?? m, ...args);
  };
  const german = logic.effectLine(JSON.parse(run('json', { language: 'de' }).stdout), t, true);
  assert.match(german, /^millpath: 1 Pfad geändert; 1 Element bearbeitet, 1 weitere durch die Wirkung erreicht · 2001\.1P: B -0,2 → -0,5 an 1 Element \(/);
  assert.match(german, /tiefstes Z -0,2 → -0,5; Fräsweg 63,2 → 63,5 mm; .*; 12 Bewegungen; G-Code geändert$/);
  // no change; a path added and one removed; a file that does not compile
  writeFileSync(join(copies, nf, '2001.mpath'), text);
  const same = run('json');
  assert.equal(same.status, 0, same.stderr);
  assert.equal(logic.effectLine(JSON.parse(same.stdout), t), 'millpath: keine Änderung am Teil');
  assert.equal(logic.effectLine(JSON.parse(same.stdout)), 'millpath: no change to the part');
  writeFileSync(join(copies, nf, '2001.mpath'), text.replace(/path 2001\.1P/g, 'path 2001.2P') + '\npath 2001.3P {\n  start (0, 0)  T1 O2 B-1\n  end (5, 0)\n  mill (0, 0) -> (5, 5)  B-9 B\n}\n');
  const renamed = run('json');
  const moved = logic.effectLine(JSON.parse(renamed.stdout), t);
  assert.match(moved, /1 Pfad umbenannt|1 Pfad hinzugefügt/, moved);
  assert.match(moved, /lässt sich nicht übersetzen|G-Code/, moved);
  const sources = ['src/logic.ts', 'src/effect.ts'].map((f) => readFileSync(join(repo, 'editors/vscode', f), 'utf8')).join('\n');
  for (const m of sources.matchAll(/l10n\.t\('([^']+)'/g)) used.add(m[1]);
  const missing = [...used].filter((m) => !(m in de));
  assert.deepEqual(missing, [], 'messages without German');
  // drawings: the copies of two revisions of part.dxf, read as part.dxf beside millpath.toml
  writeFileSync(join(copies, nf, '2001.mpath'), text.replace('B-0,2', 'B-0,5'));
  const dxf = (from, to) => assert.equal(spawnSync(bin, ['text2dxf', from, '-o', to]).status, 0);
  dxf(join(copies, of, '2001.mpath'), join(copies, of, 'part.dxf'));
  dxf(join(copies, nf, '2001.mpath'), join(copies, nf, 'part.dxf'));
  const d = run('json', {}, [join(of, 'part.dxf'), join(nf, 'part.dxf')], join(dir, 'part.dxf'));
  assert.equal(d.status, 1, d.stderr);
  assert.match(logic.effectLine(JSON.parse(d.stdout)), /2001\.1P: B -0,2 → -0,5 on 1 element .*; G-code changed$/);
  // hostile: a side that is no drawing is an error (exit 2), not an answer
  writeFileSync(join(copies, nf, '2001.mpath'), Buffer.from([0, 1, 2, 0, 255]));
  const bad = run('json');
  assert.equal(bad.status, 2, bad.stdout);
  // sides that are no drawing, or no URI the extension reads, have no summary
  assert.equal(logic.diffSide('file', '/x/notes.txt', ''), undefined);
  assert.equal(logic.diffSide('git', '/x/a.mpath', 'not json'), undefined);
  assert.equal(logic.diffSide('vscode-remote', '/x/a.mpath', ''), undefined);
  assert.deepEqual(logic.diffSide('git', '/x/p.DXF', JSON.stringify({ path: '/x/p.DXF', ref: 'a'.repeat(40) })), { drawing: '/x/p.DXF', label: 'aaaaaaaaaa' });
  assert.deepEqual(logic.copyFolders({ drawing: '/a', label: '-rf' }, { drawing: '/a', label: '-rf' }), ['_rf (old)', '_rf (new)']);
});
