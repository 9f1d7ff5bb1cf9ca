// The effect summary in VS Code's diff editor: when a diff editor compares two versions of a
// drawing (git's "Open Changes", a staged change, any two .mpath/.dxf files), `millpath diff
// --format json|markdown` compares them and the summary shows as a line at the top of the
// modified side and (its head) in the status bar, its hover holds millpath's markdown report,
// and the title-bar command
// "MillPath: Show Effect of the Changes" opens that report. The sides are read through VS Code
// (workspace.fs, open documents), so git revisions and unsaved edits count; the copies are
// compiled as the drawing in the work tree (`--at`: its millpath.toml and subpaths).
import * as vscode from 'vscode';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { execFile } from 'node:child_process';
import { diffSide, copyFolders, effectArgs, effectLine, MachineSettings, DiffSide } from './logic';

/** What the summary of one pair of versions says. */
interface Summary {
  line: string;
  markdown: string;
}

export const EFFECT_COMMAND = 'millpath.effectSummary';
const REPORT_SCHEME = 'millpath-effect';

/** Runs `millpath diff`; 0 (no change) and 1 (changed) are answers, anything else an error. */
function diffRun(bin: string, args: string[], cwd: string): Promise<string> {
  return new Promise((resolve, reject) => {
    execFile(bin, args, { cwd, maxBuffer: 64 * 1024 * 1024, timeout: 120_000 }, (err, stdout, stderr) => {
      const code = err ? (typeof err.code === 'number' ? err.code : null) : 0;
      if (code === 0 || code === 1) resolve(String(stdout));
      else reject(new Error(String(stderr).trim() || err?.message || `millpath diff exited with ${code}`));
    });
  });
}

/** A side's bytes: an open .mpath document's text (unsaved edits count), else the file
 *  through VS Code's file systems (a `git:` URI is the revision), else the document. */
async function contents(uri: vscode.Uri, side: DiffSide): Promise<Uint8Array> {
  const open = vscode.workspace.textDocuments.find((d) => d.uri.toString() === uri.toString());
  if (open && /\.mpath$/i.test(side.drawing)) return Buffer.from(open.getText(), 'utf8');
  try {
    return await vscode.workspace.fs.readFile(uri);
  } catch {
    return Buffer.from((await vscode.workspace.openTextDocument(uri)).getText(), 'utf8');
  }
}

/** The text diff tabs whose two sides are versions of drawings. */
function drawingDiffs(): { tab: vscode.Tab; input: vscode.TabInputTextDiff }[] {
  const out: { tab: vscode.Tab; input: vscode.TabInputTextDiff }[] = [];
  for (const group of vscode.window.tabGroups.all) {
    const tab = group.activeTab;
    const input = tab?.input;
    if (tab && input instanceof vscode.TabInputTextDiff && side(input.original) && side(input.modified)) out.push({ tab, input });
  }
  return out;
}

function side(uri: vscode.Uri): DiffSide | undefined {
  return diffSide(uri.scheme, uri.fsPath, uri.query);
}

export function registerEffectSummary(
  ctx: vscode.ExtensionContext,
  bin: () => string,
  settings: () => MachineSettings,
  log: (line: string) => void,
): void {
  const decoration = vscode.window.createTextEditorDecorationType({
    isWholeLine: true,
    after: { color: new vscode.ThemeColor('editorCodeLens.foreground'), fontStyle: 'italic', margin: '0 0 0 3em' },
  });
  // the head of the line in the status bar while a drawing's diff editor is the active one
  // (the line atop the modified side may be out of sight in a narrow editor)
  const status = vscode.window.createStatusBarItem('millpath.effect', vscode.StatusBarAlignment.Left, 49);
  status.name = vscode.l10n.t('MillPath: effect of the changes');
  status.command = EFFECT_COMMAND;
  const cache = new Map<string, Promise<Summary>>();
  const reports = new Map<string, string>();
  const changed = new vscode.EventEmitter<vscode.Uri>();
  let timer: NodeJS.Timeout | undefined;

  const version = (uri: vscode.Uri) => vscode.workspace.textDocuments.find((d) => d.uri.toString() === uri.toString())?.version ?? 0;

  async function compute(original: vscode.Uri, modified: vscode.Uri): Promise<Summary> {
    const o = side(original)!, m = side(modified)!;
    const [oldBytes, newBytes] = await Promise.all([contents(original, o), contents(modified, m)]);
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'millpath-effect-'));
    try {
      const [of, nf] = copyFolders(o, m);
      const oldCopy = path.join(of, path.basename(o.drawing));
      const newCopy = path.join(nf, path.basename(m.drawing));
      for (const [copy, bytes] of [[oldCopy, oldBytes], [newCopy, newBytes]] as const) {
        fs.mkdirSync(path.join(dir, path.dirname(copy)), { recursive: true });
        fs.writeFileSync(path.join(dir, copy), bytes);
      }
      const s = settings();
      const [json, markdown] = await Promise.all([
        diffRun(bin(), effectArgs(oldCopy, newCopy, m.drawing, 'json', s), dir),
        diffRun(bin(), effectArgs(oldCopy, newCopy, m.drawing, 'markdown', s), dir),
      ]);
      return { line: effectLine(JSON.parse(json), vscode.l10n.t, /^de\b/.test(vscode.env.language)), markdown };
    } finally {
      fs.rmSync(dir, { recursive: true, force: true });
    }
  }

  /** The summary of a pair (cached per version of the open documents). */
  function summary(original: vscode.Uri, modified: vscode.Uri): Promise<Summary> {
    const key = `${original.toString()}|${version(original)}|${modified.toString()}|${version(modified)}`;
    let s = cache.get(key);
    if (!s) {
      if (cache.size > 32) cache.clear();
      s = compute(original, modified);
      cache.set(key, s);
      s.catch(() => cache.delete(key));
    }
    return s;
  }

  async function refresh(): Promise<void> {
    const diffs = drawingDiffs();
    const shown = new Set<vscode.TextEditor>();
    for (const { tab, input } of diffs) {
      // the modified side: an editor of that document without a column of its own (VS Code
      // gives the sides of a diff editor none), not the same file open beside
      const editors = vscode.window.visibleTextEditors.filter(
        (e) => e.document.uri.toString() === input.modified.toString() && (e.viewColumn === undefined || e.viewColumn === tab.group.viewColumn),
      );
      if (editors.length === 0) {
        const seen = vscode.window.visibleTextEditors.map((e) => `${e.document.uri.toString(true)}@${e.viewColumn}`).join(', ');
        log(`[info] effect summary: no editor of ${input.modified.toString(true)} in column ${tab.group.viewColumn} (${seen})`);
        continue;
      }
      let line: string, hover: vscode.MarkdownString;
      try {
        const s = await summary(input.original, input.modified);
        line = s.line;
        log(`[info] effect summary of ${input.original.toString(true)} → ${input.modified.toString(true)}: ${line}`);
        hover = new vscode.MarkdownString(s.markdown);
      } catch (e) {
        const msg = (e as Error).message.split('\n')[0];
        log(`[warn] effect summary of ${input.modified.toString(true)}: ${msg}`);
        line = vscode.l10n.t('millpath: no effect summary: {0}', msg);
        hover = new vscode.MarkdownString();
        hover.appendText((e as Error).message);
      }
      for (const editor of editors) {
        const range = editor.document.lineAt(0).range;
        editor.setDecorations(decoration, [{ range, hoverMessage: hover, renderOptions: { after: { contentText: line } } }]);
        shown.add(editor);
      }
    }
    for (const e of vscode.window.visibleTextEditors) if (!shown.has(e)) e.setDecorations(decoration, []);
    const active = vscode.window.tabGroups.activeTabGroup.activeTab?.input;
    const pair = active instanceof vscode.TabInputTextDiff && diffs.find(({ input }) => input === active)?.input;
    const s = pair ? await summary(pair.original, pair.modified).catch(() => undefined) : undefined;
    if (s) {
      status.text = `$(diff) ${s.line.split(' · ')[0]}`;
      status.tooltip = new vscode.MarkdownString(s.markdown);
      status.show();
    } else {
      status.hide();
    }
  }

  const later = (ms = 300) => {
    clearTimeout(timer);
    timer = setTimeout(() => void refresh().catch((e) => log(`[warn] effect summary: ${(e as Error).message}`)), ms);
  };

  ctx.subscriptions.push(
    decoration,
    status,
    changed,
    vscode.workspace.registerTextDocumentContentProvider(REPORT_SCHEME, {
      onDidChange: changed.event,
      provideTextDocumentContent: (uri) => reports.get(uri.toString()) ?? '',
    }),
    vscode.commands.registerCommand(EFFECT_COMMAND, async () => {
      try {
        const input = vscode.window.tabGroups.activeTabGroup.activeTab?.input;
        const pair = input instanceof vscode.TabInputTextDiff && side(input.original) && side(input.modified) ? input : drawingDiffs()[0]?.input;
        if (!pair) throw new Error(vscode.l10n.t('no diff editor of two versions of a drawing (.mpath, .dxf)'));
        const s = await summary(pair.original, pair.modified);
        const name = path.basename(side(pair.modified)!.drawing);
        const uri = vscode.Uri.from({ scheme: REPORT_SCHEME, path: `/${name}.effect.md`, query: pair.modified.toString() });
        reports.set(uri.toString(), s.markdown);
        changed.fire(uri);
        const doc = await vscode.workspace.openTextDocument(uri);
        await vscode.languages.setTextDocumentLanguage(doc, 'markdown');
        await vscode.window.showTextDocument(doc, { viewColumn: vscode.ViewColumn.Beside, preview: false });
      } catch (e) {
        const msg = (e as Error).message;
        log(`[error] ${EFFECT_COMMAND}: ${msg}`);
        void vscode.window.showErrorMessage(`MillPath: ${msg}`);
      }
    }),
    vscode.window.tabGroups.onDidChangeTabs(() => later()),
    vscode.window.tabGroups.onDidChangeTabGroups(() => later()),
    vscode.window.onDidChangeVisibleTextEditors(() => later(100)),
    vscode.workspace.onDidChangeTextDocument((e) => {
      if (drawingDiffs().some(({ input }) => input.modified.toString() === e.document.uri.toString())) later(500);
    }),
    vscode.workspace.onDidCloseTextDocument((d) => {
      if (d.uri.scheme === REPORT_SCHEME) reports.delete(d.uri.toString());
    }),
  );
  later(0);
}
