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
