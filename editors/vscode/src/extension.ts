// VS Code glue: the language client, G-code preview documents, the toolpath webview, DXF
// conversions and the status bar. The logic lives in logic.ts.
import * as vscode from 'vscode';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { execFile } from 'node:child_process';
import { LanguageClient, LanguageClientOptions, ServerOptions } from 'vscode-languageclient/node';
import {
  initializationOptions, serverCommand, previewUri, parsePreviewUri, pathAtLine, statusText, isSourceRef, PREVIEW_SCHEME, MachineSettings,
} from './logic';

let client: LanguageClient | undefined;

function settings(): MachineSettings {
  const c = vscode.workspace.getConfiguration('millpath');
  return {
    feed: c.get<number | null>('machine.feed'),
    sweepSpeed: c.get<number | null>('machine.sweepSpeed'),
    sweepHeight: c.get<number | null>('machine.sweepHeight'),
    probeFeed: c.get<number | null>('machine.probeFeed'),
    language: c.get<string>('language'),
  };
}

function command(ctx: vscode.ExtensionContext): string {
  const exe = process.platform === 'win32' ? 'millpath.exe' : 'millpath';
  const bundled = ctx.asAbsolutePath(path.join('server', exe));
  return serverCommand(vscode.workspace.getConfiguration('millpath').get<string>('server.path') ?? '', bundled, fs.existsSync);
}

interface Preview { path: string; gcode: string; stats: string[]; errors: string[] }

class PreviewProvider implements vscode.TextDocumentContentProvider {
  readonly changed = new vscode.EventEmitter<vscode.Uri>();
  readonly onDidChange = this.changed.event;
  async provideTextDocumentContent(uri: vscode.Uri): Promise<string> {
    const p = parsePreviewUri(uri.toString(true));
    if (!p || !client) return '(no preview)';
    try {
      const r = await client.sendRequest<Preview>('millpath/gcodePreview', { textDocument: { uri: p.source }, path: p.path });
      return r.gcode;
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
  const serverOptions: ServerOptions = { command: command(ctx), args: ['lsp'] };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [{ language: 'millpath' }],
    initializationOptions: initializationOptions(settings()),
  };
  client = new LanguageClient('millpath', 'MillPath', serverOptions, clientOptions);
  await client.start();

  const provider = new PreviewProvider();
  ctx.subscriptions.push(vscode.workspace.registerTextDocumentContentProvider(PREVIEW_SCHEME, provider));
  const open = new Set<string>();
  let timer: NodeJS.Timeout | undefined;
  ctx.subscriptions.push(
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
  );

  ctx.subscriptions.push(
    vscode.commands.registerCommand('millpath.preview', async (uriArg?: string, pathArg?: string) => {
      const editor = vscode.window.activeTextEditor;
      const source = uriArg ?? editor?.document.uri.toString();
      if (!source) return;
      const name = pathArg ?? (editor ? pathAtLine(editor.document.getText(), editor.selection.active.line) : undefined);
      const u = previewUri(source, name);
      open.add(u);
      const doc = await vscode.workspace.openTextDocument(vscode.Uri.parse(u));
      await vscode.window.showTextDocument(doc, { viewColumn: vscode.ViewColumn.Beside, preview: false, preserveFocus: true });
    }),
    vscode.commands.registerCommand('millpath.toolpath', async () => {
      const editor = vscode.window.activeTextEditor;
      if (!editor || !client) return;
      const name = pathAtLine(editor.document.getText(), editor.selection.active.line);
      const panel = vscode.window.createWebviewPanel('millpathToolpath', `Toolpath ${name ?? ''}`, vscode.ViewColumn.Beside, { enableScripts: true });
      panel.webview.html = fs.readFileSync(ctx.asAbsolutePath('media/toolpath.html'), 'utf8');
      const send = async () => {
        try {
          const data = await client!.sendRequest('millpath/toolpath', { textDocument: { uri: editor.document.uri.toString() }, path: name });
          await panel.webview.postMessage({ type: 'toolpath', data });
        } catch (e) {
          await panel.webview.postMessage({ type: 'toolpath', data: { error: (e as Error).message, moves: [] } });
        }
      };
      panel.webview.onDidReceiveMessage(async (m) => {
        if (m?.type === 'ready') await send();
        if (m?.type === 'reveal' && isSourceRef(m.source)) {
          const doc = await vscode.workspace.openTextDocument(vscode.Uri.file(m.source.file));
          const pos = new vscode.Position(m.source.line, m.source.character);
          await vscode.window.showTextDocument(doc, { viewColumn: vscode.ViewColumn.One, selection: new vscode.Range(pos, pos) });
        }
      });
      const sub = vscode.workspace.onDidChangeTextDocument((e) => {
        if (e.document.uri.toString() === editor.document.uri.toString()) void send();
      });
      panel.onDidDispose(() => sub.dispose());
    }),
    vscode.commands.registerCommand('millpath.dxfToText', async (uri?: vscode.Uri) => {
      const file = uri?.fsPath ?? (await vscode.window.showOpenDialog({ filters: { DXF: ['dxf', 'DXF'] } }))?.[0]?.fsPath;
      if (!file) return;
      try {
        const text = await run(ctx, ['dxf2text', file]);
        const doc = await vscode.workspace.openTextDocument({ language: 'millpath', content: text });
        await vscode.window.showTextDocument(doc);
      } catch (e) {
        void vscode.window.showErrorMessage(`millpath dxf2text: ${(e as Error).message}`);
      }
    }),
    vscode.commands.registerCommand('millpath.textToDxf', async () => {
      const editor = vscode.window.activeTextEditor;
      if (!editor) return;
      await editor.document.save();
      const target = await vscode.window.showSaveDialog({ defaultUri: vscode.Uri.file(editor.document.uri.fsPath.replace(/\.mpath$/i, '.dxf')), filters: { DXF: ['dxf'] } });
      if (!target) return;
      try {
        await run(ctx, ['text2dxf', editor.document.uri.fsPath, '-o', target.fsPath]);
        void vscode.window.showInformationMessage(`Written ${target.fsPath}`);
      } catch (e) {
        void vscode.window.showErrorMessage(`millpath text2dxf: ${(e as Error).message}`);
      }
    }),
  );

  const status = vscode.window.createStatusBarItem(vscode.StatusBarAlignment.Left, 50);
  status.command = 'millpath.preview';
  ctx.subscriptions.push(status);
  async function updateStatus() {
    const editor = vscode.window.activeTextEditor;
    if (!editor || editor.document.languageId !== 'millpath' || !client) {
      status.hide();
      return;
    }
    const name = pathAtLine(editor.document.getText(), editor.selection.active.line);
    try {
      const r = await client.sendRequest<Preview>('millpath/gcodePreview', { textDocument: { uri: editor.document.uri.toString() }, path: name });
      status.text = `$(tools) ${statusText(r.path, r.stats)}`;
      status.tooltip = r.stats.join('\n');
    } catch {
      status.text = `$(tools) ${name ?? 'millpath'}: no G-code`;
    }
    status.show();
  }
  ctx.subscriptions.push(
    vscode.window.onDidChangeActiveTextEditor(() => void updateStatus()),
    vscode.window.onDidChangeTextEditorSelection(() => void updateStatus()),
  );
  void updateStatus();
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
