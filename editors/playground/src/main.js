// The playground page: CodeMirror over the compiler in wasm (crates/wasm), the G-code of the
// path under the cursor, and the toolpath viewer of the editors (editors/toolpath, its built
// page in an iframe: the same code as VS Code's and Neovim's view). Every answer about the
// files comes from the wasm; this file only shows them.
import init, { Millpath } from 'millpath-wasm';
import { EditorState } from '@codemirror/state';
import { EditorView, keymap, lineNumbers, highlightActiveLine, highlightActiveLineGutter, drawSelection, hoverTooltip } from '@codemirror/view';
import { defaultKeymap, history, historyKeymap, indentWithTab } from '@codemirror/commands';
import { autocompletion, completionKeymap } from '@codemirror/autocomplete';
import { lintGutter, lintKeymap, setDiagnostics } from '@codemirror/lint';
import { millpathLanguage } from './language.js';
import { markdownToHtml } from './markdown.js';
import { encodeShare, decodeShare } from './share.js';
import { WORDS } from './i18n.js';
import examples from 'virtual:examples';
import viewerPage from 'virtual:viewer';

const DIR = '/play/';
const TOML = 'millpath.toml';
const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);

let mp = null;
let lang = params.get('lang') || localStorage.getItem('millpath-lang') || (navigator.language.startsWith('de') ? 'de' : 'en');
const files = new Map(); // name → EditorState (.mpath)
let active = null;
let diagnostics = [];
let outputs = { files: [], stats: [], messages: [] };
let toolpathData = null;
let currentPath = null;
const timings = { firstDiagnostics: null, edits: [] };
const w = () => WORDS[lang] || WORDS.en;

// ---- status line ----
function status(text, error = false) {
  $('status').textContent = text;
  $('status').className = error ? 'err' : '';
}

function translate() {
  document.documentElement.lang = lang;
  $('lang').value = lang;
  for (const el of document.querySelectorAll('[data-t]')) {
    const v = w()[el.dataset.t];
    if (typeof v === 'string') el.textContent = v;
  }
  $('files').querySelector('li .x')?.setAttribute('title', w().removeFile);
}

// ---- the editors ----
function editorExtensions() {
  return [
    lineNumbers(), highlightActiveLineGutter(), highlightActiveLine(), drawSelection(), history(),
    millpathLanguage, lintGutter(),
    autocompletion({ override: [complete] }),
    hoverTooltip(hover, { hideOnChange: true }),
    keymap.of([...defaultKeymap, ...historyKeymap, ...completionKeymap, ...lintKeymap, indentWithTab]),
    EditorView.updateListener.of(onUpdate),
  ];
}
const view = new EditorView({ parent: $('editor') });
const toml = new EditorView({
  parent: $('toml'),
  state: EditorState.create({
    doc: '',
    extensions: [lineNumbers(), history(), keymap.of([...defaultKeymap, ...historyKeymap]),
      EditorView.updateListener.of((u) => { if (u.docChanged) { mp.set_file(DIR + TOML, u.state.doc.toString()); analyse(); scheduleOutputs(); } })],
  }),
});

function onUpdate(u) {
  if (!mp || !active) return;
  if (u.docChanged) {
    const t0 = performance.now();
    files.set(active, u.state);
    mp.set_file(DIR + active, u.state.doc.toString());
    // dispatching inside an update is not allowed: right after it
    queueMicrotask(() => { analyse(); timings.edits.push(performance.now() - t0); document.body.dataset.lastEditMs = String(performance.now() - t0); });
    scheduleOutputs();
  } else if (u.selectionSet) {
    files.set(active, u.state);
    const name = pathAtCursor();
    if (name !== currentPath) scheduleOutputs(0);
    followCursor();
  }
}

/** Diagnostics of the active file, as `millpath check` reports them. */
function analyse() {
  if (!active) return;
  diagnostics = JSON.parse(mp.diagnostics(DIR + active));
  const len = view.state.doc.length;
  const list = diagnostics.map((d) => ({
    from: Math.min(d.from, len), to: Math.min(Math.max(d.to, d.from), len),
    severity: d.severity, source: d.code, message: `${d.code}: ${d.message}`,
  }));
  view.dispatch(setDiagnostics(view.state, list));
  const e = diagnostics.filter((d) => d.severity === 'error').length;
  status(w().problems(e, diagnostics.length - e), e > 0);
  document.body.dataset.diagnostics = String(diagnostics.length);
  if (timings.firstDiagnostics === null) {
    timings.firstDiagnostics = performance.now();
    document.body.dataset.firstDiagnostics = String(timings.firstDiagnostics);
  }
}

function hover(v, pos) {
  if (!mp || !active) return null;
  const h = JSON.parse(mp.hover(DIR + active, pos));
  if (!h) return null;
  return {
    pos: h.from, end: h.to, above: true,
    create() { const dom = document.createElement('div'); dom.className = 'md'; dom.innerHTML = markdownToHtml(h.markdown); return { dom }; },
  };
}

function complete(ctx) {
  if (!mp || !active) return null;
  const r = JSON.parse(mp.completion(DIR + active, ctx.pos));
  if (!r.items.length || (!ctx.explicit && r.from === ctx.pos && !/[>\s]$/.test(ctx.state.sliceDoc(ctx.pos - 1, ctx.pos)))) return null;
  return { from: r.from, options: r.items.map((i) => ({ label: i.label, detail: i.detail, apply: i.insert })), validFor: /^[\w.:-]*$/ };
}

// ---- G-code and toolpath of the path under the cursor ----
function pathAtCursor() {
  if (!active) return null;
  return JSON.parse(mp.path_at(DIR + active, view.state.selection.main.head));
}

let outputsTimer = null;
function scheduleOutputs(delay = 150) {
  clearTimeout(outputsTimer);
  outputsTimer = setTimeout(refreshOutputs, delay);
}

function refreshOutputs() {
  if (!active) return;
  currentPath = pathAtCursor();
  const t0 = performance.now();
  outputs = JSON.parse(mp.compile(DIR + active, currentPath));
  const sel = $('gcode-file');
  const before = sel.value.replace(/^.*_/, '');
  sel.replaceChildren(...outputs.files.map((f) => new Option(f.name, f.name)));
  const again = outputs.files.find((f) => f.name.endsWith(`_${before}`));
  if (again) sel.value = again.name;
  showGcode();
  $('gcode-errors').textContent = outputs.files.length ? outputs.messages.join('\n') : w().noGcode + (outputs.messages.join('\n') || '-');
  toolpathData = JSON.parse(mp.toolpath(DIR + active, currentPath));
  renderToolpath();
  document.body.dataset.outputsMs = String(performance.now() - t0);
  document.body.dataset.outputs = String((document.body.dataset.outputs | 0) + 1);
}

function showGcode() {
  const f = outputs.files.find((x) => x.name === $('gcode-file').value) || outputs.files[0];
  $('gcode').textContent = f ? f.content : '';
}
$('gcode-file').addEventListener('change', showGcode);

// the viewer: the editors' built page, in an iframe without an address of its own (no
// requests to a server it would otherwise poll), driven through its `millpathToolpath` API
const frame = $('viewer');
let viewerWin = null;
const viewerReady = new Promise((resolve) => {
  frame.addEventListener('load', () => {
    viewerWin = frame.contentWindow;
    viewerWin.millpathToolpath.setLang(lang);
    viewerWin.addEventListener('millpath-select', (e) => reveal(e.detail && e.detail.source));
    resolve();
  }, { once: true });
});
frame.srcdoc = viewerPage;
let shownPath = null;
async function renderToolpath() {
  await viewerReady;
  const data = toolpathData && toolpathData.moves ? toolpathData : { error: toolpathData && toolpathData.error };
  viewerWin.millpathToolpath.render(data, shownPath !== null && shownPath === data.path);
  shownPath = data.path || null;
  followCursor();
}

/** The moves of the element under the cursor, highlighted in the view. */
function followCursor() {
  if (!viewerWin || !toolpathData || !toolpathData.moves || !active) return;
  const line = view.state.doc.lineAt(view.state.selection.main.head).number - 1;
  viewerWin.millpathToolpath.highlight({ file: DIR + active, line });
}

/** A clicked move: its element's line selected in its file. */
function reveal(source) {
  if (!source || typeof source.file !== 'string' || !source.file.startsWith(DIR)) return;
  const name = source.file.slice(DIR.length);
  if (!files.has(name)) return;
  if (name !== active) open(name);
  const line = view.state.doc.line(Math.min(source.line + 1, view.state.doc.lines));
  view.dispatch({ selection: { anchor: line.from, head: line.to }, scrollIntoView: true });
  view.focus();
  document.body.dataset.revealed = `${name}:${source.line + 1}`;
}

// ---- files ----
function addFile(name, text) {
  files.set(name, EditorState.create({ doc: text, extensions: editorExtensions() }));
  mp.set_file(DIR + name, text);
  listFiles();
}

function open(name) {
  active = name;
  view.setState(files.get(name));
  listFiles();
  analyse();
  scheduleOutputs(0);
}

function listFiles() {
  const ul = $('file-list');
  ul.replaceChildren(...[...files.keys()].sort().map((name) => {
    const li = document.createElement('li');
    li.textContent = name;
    li.dataset.name = name;
    if (name === active) li.className = 'active';
    const x = document.createElement('span');
    x.className = 'x'; x.textContent = '×'; x.title = w().removeFile;
    x.addEventListener('click', (e) => { e.stopPropagation(); removeFile(name); });
    li.append(x);
    li.addEventListener('click', () => open(name));
    return li;
  }));
}

function removeFile(name) {
  if (files.size <= 1) return;
  files.delete(name);
  mp.remove_file(DIR + name);
  if (active === name) open([...files.keys()].sort()[0]);
  else { listFiles(); analyse(); scheduleOutputs(0); }
}

$('new-file').addEventListener('click', () => {
  let name = prompt(w().newFilePrompt, 'part.mpath');
  if (!name) return;
  name = name.trim();
  if (!name.toLowerCase().endsWith('.mpath')) name += '.mpath';
  if (!/^[^/\\]+$/.test(name)) return;
  if (!files.has(name)) addFile(name, '');
  open(name);
});

/** A dropped or chosen file: a drawing becomes its text (dxf2text), a text opens as it is. */
async function openFile(file) {
  const lower = file.name.toLowerCase();
  if (lower.endsWith('.dxf')) {
    const bytes = new Uint8Array(await file.arrayBuffer());
    const r = JSON.parse(mp.dxf2text(DIR + file.name, bytes));
    if (r.error) { status(r.error, true); return; }
    const name = file.name.replace(/\.dxf$/i, '.mpath');
    if (files.has(name)) mp.set_file(DIR + name, r.text);
    addFile(name, r.text);
    open(name);
    status([w().dxfOpened(file.name), ...r.messages].join(' · '), r.messages.length > 0);
  } else if (lower.endsWith('.mpath')) {
    addFile(file.name, await file.text());
    open(file.name);
  }
}
$('open').addEventListener('change', async (e) => { for (const f of e.target.files) await openFile(f); e.target.value = ''; });
window.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
window.addEventListener('dragleave', (e) => { if (!e.relatedTarget) document.body.classList.remove('dragging'); });
window.addEventListener('drop', async (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  for (const f of e.dataTransfer.files) await openFile(f);
});

// ---- commands ----
$('format').addEventListener('click', () => {
  const text = JSON.parse(mp.format(DIR + active));
  if (text !== null && text !== view.state.doc.toString()) view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: text } });
});

function download(name, text) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([text], { type: 'application/octet-stream' }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}
$('dl-mpath').addEventListener('click', () => download(active, view.state.doc.toString()));
$('dl-dxf').addEventListener('click', () => {
  const r = JSON.parse(mp.text2dxf(DIR + active));
  if (r.error) status(r.error, true);
  else download(active.replace(/\.mpath$/i, '.dxf'), r.dxf);
});
$('dl-gcode').addEventListener('click', () => { for (const f of outputs.files) download(f.name, f.content); });

async function shareUrl() {
  const state = { files: Object.fromEntries([...files].map(([n, s]) => [n, s.doc.toString()])), active };
  state.files[TOML] = toml.state.doc.toString();
  const u = new URL(location.href);
  u.search = '';
  u.hash = await encodeShare(state);
  return u.href;
}
$('share').addEventListener('click', async () => {
  const url = await shareUrl();
  window.history.replaceState(null, '', url); // `history` is CodeMirror's here
  $('share-url').value = url;
  $('share-box').classList.add('on');
  $('share-url').select();
  try { await navigator.clipboard.writeText(url); status(w().copied); } catch (_) { /* the field shows it */ }
});

// the post selector: the built-in posts (a name as `--post NAME`, over millpath.toml's `post`)
function fillPosts() {
  const sel = $('post');
  for (const p of JSON.parse(Millpath.posts())) {
    const o = new Option(p.name, p.name);
    o.title = `${p.family}: ${p.description}`;
    sel.add(o);
  }
  const wanted = params.get('post') || '';
  if ([...sel.options].some((o) => o.value === wanted)) sel.value = wanted;
  mp.set_post(sel.value);
}
$('post').addEventListener('change', () => {
  mp.set_post($('post').value);
  analyse();
  scheduleOutputs(0);
});

$('lang').addEventListener('change', () => {
  lang = $('lang').value;
  localStorage.setItem('millpath-lang', lang);
  mp.set_lang(lang);
  translate();
  // the viewer's own words (its data carries the language too, from the next outputs on)
  if (viewerWin) viewerWin.millpathToolpath.setLang(lang);
  analyse();
  scheduleOutputs(0);
});

// ---- start ----
async function start() {
  translate();
  await init({ module_or_path: new URL('millpath.wasm', import.meta.url) });
  mp = new Millpath(lang);
  fillPosts();
  $('version').textContent = Millpath.version();
  let initial = { files: examples, active: params.get('example') || '2010.mpath' };
  if (location.hash.length > 1) {
    try {
      initial = (await decodeShare(location.hash.slice(1))) || initial;
    } catch (e) {
      status(w().badShare + e.message, true);
    }
  }
  for (const [name, text] of Object.entries(initial.files)) {
    if (name === TOML) mp.set_file(DIR + TOML, text);
    else addFile(name, text);
  }
  toml.dispatch({ changes: { from: 0, insert: initial.files[TOML] || '' } });
  const first = files.has(initial.active) ? initial.active : [...files.keys()].sort()[0];
  if (first) open(first);
  document.body.dataset.ready = String(performance.now());
}

// for the browser tests
window.playground = {
  view, toml, timings,
  files: () => Object.fromEntries([...files].map(([n, s]) => [n, s.doc.toString()])),
  active: () => active,
  open,
  diagnostics: () => diagnostics,
  outputs: () => outputs,
  toolpath: () => toolpathData,
  viewer: () => viewerWin && viewerWin.millpathToolpath,
  setPost: (name) => { $('post').value = name; $('post').dispatchEvent(new Event('change')); },
  shareUrl,
  dxf2text: (name, bytes) => JSON.parse(mp.dxf2text(DIR + name, new Uint8Array(bytes))),
  openFile,
};

start().catch((e) => { status(String(e), true); console.error(e); });
