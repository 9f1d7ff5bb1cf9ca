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
