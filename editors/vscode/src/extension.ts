// VS Code glue: the language client, G-code preview documents, the toolpath webview, DXF
// conversions and the status bar; the diff editor's effect summary is effect.ts. The logic
// lives in logic.ts.
import * as vscode from 'vscode';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as os from 'node:os';
import { execFile } from 'node:child_process';
import { LanguageClient, LanguageClientOptions, ServerOptions } from 'vscode-languageclient/node';
import {
  initializationOptions, findServer, ServerLookup, previewUri, parsePreviewUri, pathAtLine, statusText, previewText, PreviewResult, isSourceRef, PREVIEW_SCHEME, MachineSettings,
  documentSelector, compareArgs, compareOutcome,
} from './logic';
import { registerEffectSummary, EFFECT_COMMAND } from './effect';

let client: LanguageClient | undefined;

function settings(): MachineSettings {
  const c = vscode.workspace.getConfiguration('millpath');
  return {
    feed: c.get<number | null>('machine.feed'),
    sweepSpeed: c.get<number | null>('machine.sweepSpeed'),
    sweepHeight: c.get<number | null>('machine.sweepHeight'),
    probeFeed: c.get<number | null>('machine.probeFeed'),
    feedOverride: c.get<number | null>('feedOverride'),
    language: c.get<string>('language'),
  };
}

let log: vscode.OutputChannel | undefined;

/** The extension's own commands. */
const OWN_COMMANDS = ['millpath.preview', 'millpath.toolpath', 'millpath.dxfToText', 'millpath.textToDxf', 'millpath.compareWithHead', EFFECT_COMMAND];

/** A language client that never registers a server command under the name of one of ours:
 *  vscode-languageclient registers every command the server advertises
 *  (`executeCommandProvider`) as a VS Code command, and a second registration of a name fails
 *  ("command 'millpath.preview' already exists"). Our server says `millpath.server.preview`;
 *  this keeps an older or foreign server from breaking the extension. */
class MillpathClient extends LanguageClient {
  override registerFeature(feature: Parameters<LanguageClient['registerFeature']>[0]): void {
    const f = feature as { registrationType?: { method?: string }; register?: (data: any) => void };
    if (f.registrationType?.method === 'workspace/executeCommand' && typeof f.register === 'function') {
      const register = f.register.bind(feature);
      f.register = (data: any) => {
        const commands = ((data?.registerOptions?.commands ?? []) as string[]).filter((c) => {
          if (!OWN_COMMANDS.includes(c)) return true;
          log?.appendLine(`[warn] the server's command ${c} has the name of one of the extension's: not registered`);
          return false;
        });
        register({ ...data, registerOptions: { ...data?.registerOptions, commands } });
      };
    }
    super.registerFeature(feature);
  }
}

/** The server binary (setting, bundled in the .vsix, PATH), or an error saying there is none. */
function server(ctx: vscode.ExtensionContext): ServerLookup {
  const exe = process.platform === 'win32' ? 'millpath.exe' : 'millpath';
  const bundled = ctx.asAbsolutePath(path.join('server', exe));
  const setting = vscode.workspace.getConfiguration('millpath').get<string>('server.path') ?? '';
  return findServer(setting, bundled, process.env.PATH, process.platform, fs.existsSync);
}

function command(ctx: vscode.ExtensionContext): string {
  const s = server(ctx);
  if ('error' in s) throw new Error(s.error);
  return s.command;
}

/** Shows an error (and logs it) instead of losing it in the extension host. */
function report(what: string, e: unknown): void {
  const msg = e instanceof Error ? e.message : String(e);
  log?.appendLine(`[error] ${what}: ${msg}`);
  void vscode.window.showErrorMessage(`MillPath: ${what}: ${msg}`);
}

/** A command whose failure is shown to the user. */
function guarded(name: string, f: (...args: any[]) => unknown): (...args: any[]) => Promise<void> {
  return async (...args: any[]) => {
    try {
      await f(...args);
    } catch (e) {
      report(name, e);
    }
  };
}

type Preview = PreviewResult;

class PreviewProvider implements vscode.TextDocumentContentProvider {
  readonly changed = new vscode.EventEmitter<vscode.Uri>();
  readonly onDidChange = this.changed.event;
  async provideTextDocumentContent(uri: vscode.Uri): Promise<string> {
    const p = parsePreviewUri(uri.toString(true));
    if (!p || !client) return '(no preview)';
    try {
      const r = await client.sendRequest<Preview>('millpath/gcodePreview', { textDocument: { uri: p.source }, path: p.path });
      return previewText(r);
    } catch (e) {
      return `(millpath: ${(e as Error).message})`;
    }
  }
}

function run(ctx: vscode.ExtensionContext, args: string[]): Promise<string> {
  return new Promise((resolve, reject) => {
    execFile(command(ctx), args, { maxBuffer: 64 * 1024 * 1024 }, (err, stdout, stderr) => (err ? reject(new Error(stderr || err.message)) : resolve(stdout)));
  });
}

export async function activate(ctx: vscode.ExtensionContext): Promise<void> {
  // Everything that later code relies on exists before anything that can fail.
  log = vscode.window.createOutputChannel('MillPath');
  ctx.subscriptions.push(log);
  const status = vscode.window.createStatusBarItem('millpath.status', vscode.StatusBarAlignment.Left, 50);
  status.name = 'MillPath';
  status.command = 'millpath.preview';
  ctx.subscriptions.push(status);
  const provider = new PreviewProvider();
  const open = new Set<string>();
  let timer: NodeJS.Timeout | undefined;

  async function updateStatus() {
    const editor = vscode.window.activeTextEditor;
    if (!editor || editor.document.languageId !== 'millpath') {
      status.hide();
      return;
    }
    const name = pathAtLine(editor.document.getText(), editor.selection.active.line);
    if (!client) {
      status.text = '$(warning) millpath: no server';
      status.tooltip = 'The millpath language server is not running: see the MillPath output.';
    } else {
      try {
        const r = await client.sendRequest<Preview>('millpath/gcodePreview', { textDocument: { uri: editor.document.uri.toString() }, path: name });
        if (!r.gcode && r.errors.length > 0) {
          status.text = `$(error) ${r.path || name || 'millpath'}: no G-code`;
          status.tooltip = r.errors.join('\n');
        } else {
          status.text = `$(tools) ${statusText(r.path, r.stats, r.time, settings().feedOverride)}`;
          status.tooltip = r.stats.join('\n');
        }
      } catch {
        status.text = `$(tools) ${name ?? 'millpath'}: no G-code`;
        status.tooltip = undefined;
      }
    }
    status.show();
  }

  // client-side commands (the server's own command is `millpath.server.preview`, so the
  // language client's registration of it does not collide with these)
  const commands: [string, (...args: any[]) => unknown][] = [
    ['millpath.preview', async (uriArg?: string | vscode.Uri, pathArg?: string) => {
      const editor = vscode.window.activeTextEditor;
      const source = uriArg ? uriArg.toString() : editor?.document.uri.toString();
      if (!source) throw new Error('no MillPath document to preview');
      const doc = source === editor?.document.uri.toString() ? editor.document : undefined;
      const name = pathArg ?? (doc && editor ? pathAtLine(doc.getText(), editor.selection.active.line) : undefined);
      const u = previewUri(source, name);
      open.add(u);
      const pdoc = await vscode.workspace.openTextDocument(vscode.Uri.parse(u));
      await vscode.window.showTextDocument(pdoc, { viewColumn: vscode.ViewColumn.Beside, preview: false, preserveFocus: true });
    }],
    ['millpath.toolpath', async () => {
      const editor = vscode.window.activeTextEditor;
      if (!editor || editor.document.languageId !== 'millpath') throw new Error('no MillPath document in the editor');
      if (!client) throw new Error('the language server is not running');
      const name = pathAtLine(editor.document.getText(), editor.selection.active.line);
      const panel = vscode.window.createWebviewPanel('millpathToolpath', `Toolpath ${name ?? ''}`, vscode.ViewColumn.Beside, { enableScripts: true, retainContextWhenHidden: true });
      panel.webview.html = fs.readFileSync(ctx.asAbsolutePath('media/toolpath.html'), 'utf8');
      const send = async () => {
        try {
          const data = await client!.sendRequest('millpath/toolpath', { textDocument: { uri: editor.document.uri.toString() }, path: name });
          await panel.webview.postMessage({ type: 'toolpath', data });
        } catch (e) {
          await panel.webview.postMessage({ type: 'toolpath', data: { error: (e as Error).message, moves: [] } });
        }
      };
      const sourceUri = editor.document.uri.toString();
      // the preview of this path, opened (beside) when a click wants its line shown
      const revealGcode = async (line: number) => {
        const u = previewUri(sourceUri, name);
        let pe = vscode.window.visibleTextEditors.find((e) => e.document.uri.toString() === u);
        if (!pe) {
          open.add(u);
          const pdoc = await vscode.workspace.openTextDocument(vscode.Uri.parse(u));
          pe = await vscode.window.showTextDocument(pdoc, { viewColumn: vscode.ViewColumn.Beside, preview: false, preserveFocus: true });
        }
        const pos = new vscode.Position(Math.max(0, line - 1), 0);
        pe.selection = new vscode.Selection(pos, pos);
        pe.revealRange(new vscode.Range(pos, pos), vscode.TextEditorRevealType.InCenterIfOutsideViewport);
      };
      panel.webview.onDidReceiveMessage(async (m) => {
        try {
          if (m?.type === 'ready') await send();
          if (m?.type === 'reveal' && isSourceRef(m.source)) {
            if (typeof m.gcodeLine === 'number') await revealGcode(m.gcodeLine);
            const same = editor.document.uri.scheme !== 'file' || editor.document.uri.fsPath === m.source.file;
            const doc = same ? editor.document : await vscode.workspace.openTextDocument(vscode.Uri.file(m.source.file));
            const pos = new vscode.Position(m.source.line, m.source.character);
            await vscode.window.showTextDocument(doc, { viewColumn: editor.viewColumn ?? vscode.ViewColumn.One, selection: new vscode.Range(pos, pos) });
          }
        } catch (e) {
          report('toolpath', e);
        }
      });
      const sub = vscode.workspace.onDidChangeTextDocument((e) => {
        if (e.document.uri.toString() === sourceUri) void send();
      });
      // the cursor in the source (any file of the drawing) or in this path's G-code preview
      // highlights the moves it made
      const follow = vscode.window.onDidChangeTextEditorSelection((e) => {
        const doc = e.textEditor.document, line = e.selections[0]?.active.line ?? 0;
        if (doc.uri.scheme === PREVIEW_SCHEME) {
          if (parsePreviewUri(doc.uri.toString(true))?.source === sourceUri) {
            void panel.webview.postMessage({ type: 'highlight', gcodeLine: line + 1 });
          }
        } else if (doc.languageId === 'millpath' || /\.dxf$/i.test(doc.uri.fsPath)) {
          void panel.webview.postMessage({ type: 'highlight', file: doc.uri.fsPath, line });
        }
      });
      panel.onDidDispose(() => {
        sub.dispose();
        follow.dispose();
      });
    }],
    ['millpath.dxfToText', async (uri?: vscode.Uri) => {
      const file = uri?.fsPath ?? (await vscode.window.showOpenDialog({ filters: { DXF: ['dxf', 'DXF'] } }))?.[0]?.fsPath;
      if (!file) return;
      const text = await run(ctx, ['dxf2text', file]);
      const doc = await vscode.workspace.openTextDocument({ language: 'millpath', content: text });
      await vscode.window.showTextDocument(doc);
    }],
    ['millpath.textToDxf', async () => {
      const editor = vscode.window.activeTextEditor;
      if (!editor) return;
      await editor.document.save();
      const target = await vscode.window.showSaveDialog({ defaultUri: vscode.Uri.file(editor.document.uri.fsPath.replace(/\.mpath$/i, '.dxf')), filters: { DXF: ['dxf'] } });
      if (!target) return;
      await run(ctx, ['text2dxf', editor.document.uri.fsPath, '-o', target.fsPath]);
      void vscode.window.showInformationMessage(`Written ${target.fsPath}`);
    }],
    ['millpath.compareWithHead', async () => {
      const editor = vscode.window.activeTextEditor;
      if (!editor || editor.document.uri.scheme !== 'file') return;
      await editor.document.save();
      const file = editor.document.uri.fsPath;
      const html = path.join(os.tmpdir(), `millpath-diff-${process.pid}-${path.basename(file)}.html`);
      // exit status 1 means "changed": run() would call it a failure
      const outcome = await new Promise<ReturnType<typeof compareOutcome>>((resolve) => {
        execFile(command(ctx), compareArgs(file, html), { cwd: path.dirname(file), maxBuffer: 64 * 1024 * 1024 }, (err, _stdout, stderr) => {
          const code = err ? (typeof err.code === 'number' ? err.code : null) : 0;
          resolve(compareOutcome(code, String(stderr), err?.message));
        });
      });
      if (!outcome.open) throw new Error(outcome.message);
      if (!outcome.changed) void vscode.window.showInformationMessage(`${path.basename(file)}: no change since HEAD`);
      await vscode.env.openExternal(vscode.Uri.file(html));
    }],
  ];
  for (const [name, f] of commands) {
    try {
      ctx.subscriptions.push(vscode.commands.registerCommand(name, guarded(name, f)));
    } catch (e) {
      report(`registering ${name}`, e);
    }
  }
  try {
    registerEffectSummary(ctx, () => command(ctx), settings, (line) => log?.appendLine(line));
  } catch (e) {
    report('the effect summary of diff editors', e);
  }
  ctx.subscriptions.push(
    vscode.workspace.registerTextDocumentContentProvider(PREVIEW_SCHEME, provider),
    vscode.workspace.onDidChangeTextDocument((e) => {
      if (e.document.languageId !== 'millpath') return;
      clearTimeout(timer);
      timer = setTimeout(() => {
        for (const u of open) {
          if (parsePreviewUri(u)?.source === e.document.uri.toString()) provider.changed.fire(vscode.Uri.parse(u));
        }
        void updateStatus();
      }, 150);
    }),
    vscode.workspace.onDidCloseTextDocument((d) => {
      if (d.uri.scheme === PREVIEW_SCHEME) open.delete(d.uri.toString());
    }),
    vscode.window.onDidChangeActiveTextEditor(() => void updateStatus()),
    vscode.window.onDidChangeTextEditorSelection(() => void updateStatus()),
  );

  // the language client last: without a server the commands above still say what is wrong
  const found = server(ctx);
  if ('error' in found) {
    report('language server', found.error);
  } else {
    log.appendLine(`millpath server: ${found.command} (${found.source})`);
    const serverOptions: ServerOptions = { command: found.command, args: ['lsp'] };
    const clientOptions: LanguageClientOptions = {
      documentSelector,
      initializationOptions: initializationOptions(settings()),
      outputChannel: log,
    };
    const c = new MillpathClient('millpath', 'MillPath', serverOptions, clientOptions);
    try {
      await c.start();
      client = c;
    } catch (e) {
      report(`starting ${found.command} lsp`, e);
    }
  }
  void updateStatus();
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
