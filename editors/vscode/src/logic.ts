// The extension's logic that does not need VS Code: settings → initialization options, the
// server command, preview URIs, the path under the cursor, status-bar text. Unit-tested with
// node's test runner.

export interface MachineSettings {
  feed?: number | null;
  sweepSpeed?: number | null;
  sweepHeight?: number | null;
  probeFeed?: number | null;
  /** The operator's feed override (percent) the time estimate assumes. */
  feedOverride?: number | null;
  language?: string;
}

/** Initialization options for `millpath lsp`: the keys of millpath.toml; unset values are left
 *  out so that millpath.toml applies. */
export function initializationOptions(s: MachineSettings): Record<string, unknown> {
  const out: Record<string, unknown> = {};
  const put = (key: string, v: number | null | undefined) => {
    if (typeof v === 'number' && Number.isFinite(v)) out[key] = v;
  };
  put('feed', s.feed);
  put('sweep_speed', s.sweepSpeed);
  put('sweep_height', s.sweepHeight);
  put('probe_feed', s.probeFeed);
  put('feed_override', s.feedOverride);
  if (s.language === 'en' || s.language === 'de') out.lang = s.language;
  return out;
}

/** The documents the language server serves: MillPath text, `millpath.toml` (completion and
 *  hover of post names, its errors) and the post files of a `posts/` folder (the post loader's
 *  errors as diagnostics). Any file, whatever language another extension gives TOML. */
export const documentSelector = [
  { language: 'millpath' },
  { scheme: 'file', pattern: '**/millpath.toml' },
  { scheme: 'file', pattern: '**/posts/*.toml' },
];

/** The server binary: the setting, else the bundled one when it exists, else `millpath`. */
export function serverCommand(setting: string, bundled: string | undefined, exists: (p: string) => boolean): string {
  if (setting && setting.trim()) return setting.trim();
  if (bundled && exists(bundled)) return bundled;
  return 'millpath';
}

/** Where the server comes from, or why there is none. */
export type ServerLookup =
  | { command: string; source: 'setting' | 'bundled' | 'PATH' }
  | { error: string };

/** The server binary: the setting `millpath.server.path`, else the one in the .vsix for this
 *  platform, else `millpath` on PATH; an error that says so when there is none. */
export function findServer(
  setting: string,
  bundled: string | undefined,
  pathEnv: string | undefined,
  platform: string,
  exists: (p: string) => boolean,
): ServerLookup {
  const s = (setting ?? '').trim();
  if (s) {
    if (exists(s)) return { command: s, source: 'setting' };
    return { error: `millpath.server.path is set to '${s}', which does not exist.` };
  }
  if (bundled && exists(bundled)) return { command: bundled, source: 'bundled' };
  const win = platform === 'win32';
  const names = win ? ['millpath.exe', 'millpath.cmd', 'millpath'] : ['millpath'];
  for (const dir of (pathEnv ?? '').split(win ? ';' : ':')) {
    if (!dir) continue;
    for (const n of names) {
      const p = `${dir.replace(/[\\/]+$/, '')}${win ? '\\' : '/'}${n}`;
      if (exists(p)) return { command: p, source: 'PATH' };
    }
  }
  return {
    error:
      `No millpath language server: this extension brings none for ${platform}, and there is no 'millpath' on PATH. ` +
      'Install millpath (cargo install --path crates/cli) or set millpath.server.path.',
  };
}

export const PREVIEW_SCHEME = 'millpath-preview';

/** `millpath-preview:/<name>.gcode?<encoded source uri>#<path>` — one virtual document per
 *  source and path. */
export function previewUri(sourceUri: string, path: string | undefined): string {
  const name = (path || 'preview').replace(/[^A-Za-z0-9._-]/g, '_');
  return `${PREVIEW_SCHEME}:/${name}.gcode?${encodeURIComponent(sourceUri)}#${encodeURIComponent(path ?? '')}`;
}

export function parsePreviewUri(uri: string): { source: string; path: string | undefined } | undefined {
  const m = /^millpath-preview:\/[^?]*\?([^#]*)#?(.*)$/.exec(uri);
  if (!m) return undefined;
  const path = decodeURIComponent(m[2]);
  return { source: decodeURIComponent(m[1]), path: path || undefined };
}

/** The name of the `path NAME {` block around a line (0-based), or the first one. */
export function pathAtLine(text: string, line: number): string | undefined {
  const lines = text.split(/\r?\n/);
  const header = /^\s*path\s+("(?:[^"\\]|\\.)*"|\S+)\s*\{/;
  for (let i = Math.min(line, lines.length - 1); i >= 0; i--) {
    const m = header.exec(lines[i]);
    if (m) return unquote(m[1]);
  }
  for (const l of lines) {
    const m = header.exec(l);
    if (m) return unquote(m[1]);
  }
  return undefined;
}

function unquote(s: string): string {
  return s.startsWith('"') ? s.slice(1, -1).replace(/\\(.)/g, '$1') : s;
}

/**
 * Status-bar text from the five statistics lines and the exact time (`h:mm:ss`, from a server
 * that sends it): `path · 115 mm · 0:01:47 · 8 commands`; without the exact time the
 * statistics' whole minutes, `≈2 min`. A feed override other than 100 % (the setting the
 * server estimated with) follows the time: `0:01:31 at 120 %`.
 */
export function statusText(path: string, stats: string[], time?: string, feedOverride?: number | null): string {
  const num = (line: string | undefined, re: RegExp) => (line ? re.exec(line)?.[1] : undefined);
  const total = stats[3];
  const mm = num(total, /(\d+)\s*mm/);
  const min = num(total, /ca\.\s*(\d+)\s*min/);
  const count = num(stats[4], /(\d+)\s*$/);
  const parts = [path];
  if (mm) parts.push(`${mm} mm`);
  const override = typeof feedOverride === 'number' && Number.isFinite(feedOverride) && feedOverride !== 100 ? ` at ${feedOverride} %` : '';
  if (time && /^\d+:\d\d:\d\d$/.test(time)) parts.push(time + override);
  else if (min) parts.push(`≈${min} min${override}`);
  if (count) parts.push(`${count} commands`);
  return parts.join(' · ');
}

/** What `millpath/gcodePreview` answers (README, editors section). */
export interface PreviewResult {
  path: string;
  gcode: string;
  stats: string[];
  /** The exact estimated time, `h:mm:ss` (empty when the path is refused). */
  time?: string;
  errors: string[];
}

/**
 * The preview document's text: the G-code, or — for a path `millpath compile` would refuse —
 * its errors as G-code comments instead (each error its own line). Errors beside G-code
 * (placeholder machine settings) come first, so they are not missed.
 */
export function previewText(r: PreviewResult): string {
  const errors = (r.errors ?? []).map((e) => `(millpath: ${e.replace(/[()]/g, (c) => (c === '(' ? '[' : ']')).replace(/\r?\n/g, ' ')})`);
  if (errors.length === 0) return r.gcode;
  return errors.join('\n') + '\n' + (r.gcode ?? '');
}

/** A source location sent by the toolpath page, as editor coordinates. */
export interface SourceRef {
  file: string;
  line: number;
  character: number;
}

export function isSourceRef(v: unknown): v is SourceRef {
  const s = v as SourceRef;
  return !!s && typeof s.file === 'string' && typeof s.line === 'number' && typeof s.character === 'number';
}

/** "millpath: compare with HEAD": the arguments of `millpath diff` that write the visual diff
 *  of `file` against git's `rev` to the page `html` (run in the file's folder). */
export function compareArgs(file: string, html: string, rev = 'HEAD'): string[] {
  return ['diff', rev, '--html', html, '--', file];
}

/** What to do once `millpath diff` exits: open the page (0: no change, 1: changed) or show
 *  the error (2, a signal, a missing binary: its message, else its stderr). */
export function compareOutcome(code: number | null, stderr: string, error?: string): { open: boolean; changed: boolean; message?: string } {
  if (code === 0 || code === 1) return { open: true, changed: code === 1 };
  const said = stderr.trim() || error || `millpath diff exited with ${code}`;
  return { open: false, changed: false, message: said };
}

// --- the effect summary of a diff editor -----------------------------------------------------

/** One side of a diff editor: where its drawing is in the work tree and a short label. */
export interface DiffSide {
  /** The file it is a version of (a `git:` URI names the work-tree file in its query). */
  drawing: string;
  /** `HEAD`, `index`, a short commit, or `working tree` for a file on disk. */
  label: string;
}

/** Reads a side of a diff editor from its URI's parts: `file:` is the file itself, `git:`
 *  (VS Code's git extension: the query `{"path", "ref"}`) a revision of the file at `path`.
 *  Anything else, and a side that is not a drawing (`.mpath`, `.dxf`), is undefined. */
export function diffSide(scheme: string, fsPath: string, query: string): DiffSide | undefined {
  let drawing = fsPath;
  let label = 'working tree';
  if (scheme === 'git') {
    let q: { path?: unknown; ref?: unknown };
    try {
      q = JSON.parse(query);
    } catch {
      return undefined;
    }
    if (typeof q?.path !== 'string' || typeof q.ref !== 'string') return undefined;
    drawing = q.path;
    // '~' and '' are the index (the staged version) in the git extension's URIs
    label = q.ref === '~' || q.ref === '' ? 'index' : /^[0-9a-f]{40}$/i.test(q.ref) ? q.ref.slice(0, 10) : q.ref;
  } else if (scheme !== 'file') {
    return undefined;
  }
  return /\.(mpath|dxf)$/i.test(drawing) ? { drawing, label } : undefined;
}

/** The folder names the two sides' copies are written to (they name the versions in the
 *  report's title): the labels, made safe for a file name and told apart when equal. */
export function copyFolders(old: DiffSide, neu: DiffSide): [string, string] {
  const safe = (s: string) => s.replace(/[^A-Za-z0-9 ._-]/g, '_').replace(/^[.-]/, '_') || 'version';
  const a = safe(old.label), b = safe(neu.label);
  return a === b ? [`${a} (old)`, `${b} (new)`] : [a, b];
}

/** The arguments of `millpath diff` for two copies of a drawing's versions (relative paths
 *  that do not start with `-`, as copyFolders makes them), read as the drawing `at` (its
 *  millpath.toml and subpaths), in a format; machine settings and the language as the
 *  language server gets them. */
export function effectArgs(oldCopy: string, newCopy: string, at: string, format: 'json' | 'markdown', s: MachineSettings): string[] {
  const args = ['diff', '--format', format, '--at', at];
  const put = (flag: string, v: number | null | undefined) => {
    if (typeof v === 'number' && Number.isFinite(v)) args.push(flag, String(v));
  };
  put('--feed', s.feed);
  put('--sweep-speed', s.sweepSpeed);
  put('--sweep-height', s.sweepHeight);
  put('--probe-feed', s.probeFeed);
  put('--feed-override', s.feedOverride);
  if (s.language === 'en' || s.language === 'de') args.push('--lang', s.language);
  args.push(oldCopy, newCopy);
  return args;
}

/** The compiled figures of a path in `millpath diff --format json`. */
interface Outcome {
  error: string | null;
  lowest_z: number | null;
  milling_length: number | null;
  moves: number | null;
  seconds: number | null;
}

interface PathJson {
  name: string;
  old_name: string | null;
  status: 'unchanged' | 'changed' | 'added' | 'removed' | 'renamed';
  elements: { change: string; moves_changed: boolean }[];
  effects: { key: string; old: string; new: string; source: string; count: number }[];
  before: Outcome;
  after: Outcome;
  gcode_changed: boolean;
}

/** A message in English with `{0}`-style places; the extension passes `vscode.l10n.t`. */
export type Translate = (message: string, ...args: (string | number)[]) => string;

export const english: Translate = (m, ...args) => m.replace(/\{(\d+)\}/g, (_, i) => String(args[Number(i)] ?? ''));

function clock(seconds: number | null): string | undefined {
  if (typeof seconds !== 'number' || !Number.isFinite(seconds) || seconds < 0) return undefined;
  const s = Math.round(seconds);
  return `${Math.floor(s / 3600)}:${String(Math.floor(s / 60) % 60).padStart(2, '0')}:${String(s % 60).padStart(2, '0')}`;
}

function decimal(v: number | null | undefined, digits: number): string | undefined {
  return typeof v === 'number' && Number.isFinite(v) ? String(Math.round(v * 10 ** digits) / 10 ** digits) : undefined;
}

/** "a → b", or the one there is when both are the same or one is missing. */
function change(a: string | undefined, b: string | undefined): string | undefined {
  if (a === undefined) return b;
  if (b === undefined || a === b) return a;
  return `${a} → ${b}`;
}

/** What the summary counts: paths by status, elements edited as written, elements whose moves
 *  changed through an inherited value. */
export interface EffectCounts {
  changed: boolean;
  paths: Record<'changed' | 'added' | 'removed' | 'renamed', number>;
  edited: number;
  reached: number;
  gcodeChanged: number;
}

/** The figures of `millpath diff --format json` (one file). */
export function effectCounts(json: unknown): EffectCounts {
  const file = (json as { files?: { changed?: boolean; paths?: PathJson[] }[] })?.files?.[0];
  const c: EffectCounts = { changed: !!file?.changed, paths: { changed: 0, added: 0, removed: 0, renamed: 0 }, edited: 0, reached: 0, gcodeChanged: 0 };
  for (const p of file?.paths ?? []) {
    if (p.status !== 'unchanged') c.paths[p.status]++;
    for (const e of p.elements ?? []) {
      if (e.change === 'effect') c.reached++;
      else c.edited++;
    }
    if (p.gcode_changed) c.gcodeChanged++;
  }
  return c;
}

/**
 * The effect summary in one line, shown at the top of a diff editor's modified side:
 * `millpath: 1 path changed; 1 element edited, 1 more reached · 2001.1P: B -0,2 → -0,5 on 1
 * element (path start (line 4)); lowest Z -0.2 → -0.5; milling 63.2 → 63.5 mm; 0:00:21;
 * 12 moves; G-code changed`. Every figure is millpath's (`diff --format json`); `t` translates,
 * and German writes decimal commas as millpath's German report does.
 */
export function effectLine(json: unknown, t: Translate = english, decimalComma = false): string {
  const num = (v: number | null | undefined, digits = 1) => {
    const s = decimal(v, digits);
    return decimalComma ? s?.replace('.', ',') : s;
  };
  const file = (json as { files?: { paths?: PathJson[] }[] })?.files?.[0];
  const c = effectCounts(json);
  if (!c.changed) return t('millpath: no change to the part');
  const counts: string[] = [];
  const n = (k: number, one: string, many: string) => (k === 1 ? t(one, k) : t(many, k));
  if (c.paths.changed) counts.push(n(c.paths.changed, '{0} path changed', '{0} paths changed'));
  if (c.paths.added) counts.push(n(c.paths.added, '{0} path added', '{0} paths added'));
  if (c.paths.removed) counts.push(n(c.paths.removed, '{0} path removed', '{0} paths removed'));
  if (c.paths.renamed) counts.push(n(c.paths.renamed, '{0} path renamed', '{0} paths renamed'));
  const elements: string[] = [];
  if (c.edited) elements.push(n(c.edited, '{0} element edited', '{0} elements edited'));
  if (c.reached) elements.push(n(c.reached, '{0} more reached by the effect', '{0} more reached by the effect'));
  const head = [counts.join(', '), elements.join(', ')].filter(Boolean).join('; ');
  const parts = [`millpath: ${head}`];
  for (const p of file?.paths ?? []) {
    if (p.status === 'unchanged') continue;
    const title = p.status === 'renamed' && p.old_name ? `${p.old_name} → ${p.name}` : p.name;
    if (p.status === 'removed') {
      parts.push(`${title}: ${t('removed')}`);
      continue;
    }
    const b = p.before ?? ({} as Outcome), a = p.after ?? ({} as Outcome);
    if (a.error !== null && a.error !== undefined) {
      // no figures of a version that does not compile: its first error instead
      const why = a.error.split('\n')[0].trim();
      parts.push(`${title}: ${why ? t('does not compile: {0}', why.length > 120 ? `${why.slice(0, 119)}…` : why) : t('does not compile')}`);
      continue;
    }
    const bits: string[] = [];
    if (p.status === 'added') bits.push(t('added'));
    for (const e of p.effects ?? []) {
      const on = e.count === 1 ? '{0} {1} → {2} on {3} element ({4})' : '{0} {1} → {2} on {3} elements ({4})';
      bits.push(t(on, e.key, e.old, e.new, e.count, e.source));
    }
    // the old figures only of an old version that compiled
    const was = b.error === null && p.status !== 'added';
    const fig = (f: (o: Outcome) => string | undefined) => change(was ? f(b) : undefined, f(a));
    const z = fig((o) => num(o.lowest_z, 3));
    if (z) bits.push(t('lowest Z {0}', z));
    const len = fig((o) => num(o.milling_length));
    if (len) bits.push(t('milling {0} mm', len));
    const time = fig((o) => clock(o.seconds));
    if (time) bits.push(time);
    const moves = fig((o) => num(o.moves, 0));
    if (moves) bits.push(t('{0} moves', moves));
    bits.push(p.gcode_changed ? t('G-code changed') : t('G-code unchanged'));
    parts.push(`${title}: ${bits.join('; ')}`);
  }
  return parts.join(' · ');
}
