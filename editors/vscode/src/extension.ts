// VS Code client for the Partscope language server (`partscope lsp`).
//
// The server does the analysis; this extension starts it, forwards settings, and adds what
// LSP itself has no UI for: the cycle time in the status bar, the dry-run report, the
// toolpath preview webview, the cycle-time lens's breakdown and "explain rule".
import * as fs from "fs";
import * as path from "path";
import { execFile } from "child_process";
import * as vscode from "vscode";
import {
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
  TransportKind,
} from "vscode-languageclient/node";
import { DryRunResult, formatDuration, stoppedText, summarize } from "./dryrun";
import { webviewHtml } from "./webview";
import { BreakdownResult, executeCommand as executeLensCommand } from "./lens";

const LANGUAGE_ID = "gcode";
// VS Code registers a client-side command for every command the server announces through
// executeCommandProvider (`partscope.dryRun` among them), so our own commands use other ids.
const SERVER_DRY_RUN_COMMAND = "partscope.dryRun";

let client: LanguageClient | undefined;
let statusItem: vscode.StatusBarItem;
let reportChannel: vscode.OutputChannel | undefined;
let preview: ToolpathPreview | undefined;
let extensionContext: vscode.ExtensionContext;

interface InitOptions {
  dialect: string | null;
  machine: string | null;
  select: string[];
  ignore: string[];
  blockTimes: string;
  maxFileSize?: number;
  maxRunFileSize?: number;
  maxToolpathPoints?: number;
}

function config(): vscode.WorkspaceConfiguration {
  return vscode.workspace.getConfiguration("partscope");
}

function serverPath(): string {
  const p = config().get<string>("server.path") || "partscope";
  // Relative paths (other than bare names looked up on PATH) are relative to the workspace.
  if (p.includes("/") || p.includes("\\")) return resolveInWorkspace(p) ?? p;
  return p;
}

function resolveInWorkspace(p: string | null | undefined): string | null {
  if (!p) return null;
  const expanded = p.replace(/^~(?=$|[\\/])/, process.env.HOME ?? "~");
  if (path.isAbsolute(expanded)) return expanded;
  const folder = vscode.workspace.workspaceFolders?.[0];
  return folder ? path.join(folder.uri.fsPath, expanded) : expanded;
}

export function initializationOptions(): InitOptions {
  const c = config();
  const dialect = c.get<string | null>("dialect") ?? null;
  return {
    dialect: dialect === "" ? null : dialect,
    machine: resolveInWorkspace(c.get<string | null>("machine") ?? null),
    select: c.get<string[]>("select") ?? [],
    ignore: c.get<string[]>("ignore") ?? [],
    blockTimes: c.get<string>("blockTimes") ?? "block",
    // Unset: the server's defaults.
    maxFileSize: c.get<number | null>("maxFileSize") ?? undefined,
    maxRunFileSize: c.get<number | null>("maxRunFileSize") ?? undefined,
    maxToolpathPoints: c.get<number | null>("maxToolpathPoints") ?? undefined,
  };
}

async function startClient(): Promise<void> {
  const command = serverPath();
  const serverOptions: ServerOptions = {
    run: { command, args: ["lsp"], transport: TransportKind.stdio },
    debug: { command, args: ["lsp"], transport: TransportKind.stdio },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [
      { scheme: "file", language: LANGUAGE_ID },
      { scheme: "untitled", language: LANGUAGE_ID },
    ],
    initializationOptions: initializationOptions(),
    synchronize: { configurationSection: "partscope" },
    middleware: {
      // A click on the cycle-time lens: the breakdown in the report channel, and the preview.
      executeCommand: (command, args, next) =>
        executeLensCommand(command, args, (c, a) => next(c, a), {
          report: showBreakdownReport,
          preview: showPreviewOf,
        }),
      workspace: {
        // Hand the server the same resolved values as in initializationOptions, so a relative
        // machine path means the same thing in both places.
        configuration: async (params, token, next) => {
          const result = await next(params, token);
          if (!Array.isArray(result)) return result;
          return params.items.map((item, i) =>
            item.section === "partscope" ? { ...(result[i] as object), ...initializationOptions() } : result[i]
          );
        },
      },
    },
  };
  const c = new LanguageClient("partscope", "Partscope", serverOptions, clientOptions);
  client = c;
  try {
    await c.start();
  } catch (err) {
    client = undefined;
    // Not awaited: activation must not wait for the user to dismiss the message.
    void vscode.window
      .showErrorMessage(
        `Partscope: could not start "${command} lsp" (${err instanceof Error ? err.message : String(err)}). ` +
          "Install partscope or set partscope.server.path.",
        "Open settings"
      )
      .then((choice) => {
        if (choice) void vscode.commands.executeCommand("workbench.action.openSettings", "partscope.server.path");
      });
  }
}

async function restartClient(): Promise<void> {
  const old = client;
  client = undefined;
  if (old) {
    try {
      await old.stop();
    } catch {
      // A server that already died cannot be stopped; starting a new one is all we want.
    }
  }
  await startClient();
  void refreshStatus();
}

/** A dry run in flight: for which document version, and how to cancel it. */
interface InFlight {
  version: number;
  cts: vscode.CancellationTokenSource;
  promise: Promise<DryRunResult>;
}

// One request per document at a time, shared by the status bar and the preview: a request for
// a newer version cancels the older one (the server drops its run), and callers asking for the
// same version get the same answer instead of a second run.
const inFlight = new Map<string, InFlight>();

/** The server's answer to a request that a newer one replaced, or that was cancelled. */
function isSuperseded(err: unknown): boolean {
  const code = (err as { code?: unknown } | undefined)?.code;
  return code === -32800 || code === -32802;
}

/** Asks the server for the dry-run result of `uri`: the custom request first, the command as fallback. */
export function requestDryRun(uri: vscode.Uri): Promise<DryRunResult> {
  const c = client;
  if (!c) return Promise.reject(new Error("the Partscope server is not running"));
  const key = uri.toString();
  const version = vscode.workspace.textDocuments.find((d) => d.uri.toString() === key)?.version ?? 0;
  const current = inFlight.get(key);
  if (current && current.version === version) return current.promise;
  current?.cts.cancel();
  const cts = new vscode.CancellationTokenSource();
  const params = { textDocument: { uri: c.code2ProtocolConverter.asUri(uri) } };
  const promise = (async () => {
    try {
      return await c.sendRequest<DryRunResult>("partscope/dryRun", params, cts.token);
    } catch (err) {
      // A cancelled or superseded run is not a failure, and must not be retried as a command
      // (which could not be cancelled).
      if (cts.token.isCancellationRequested || isSuperseded(err)) throw err;
      const viaCommand = await c
        .sendRequest<DryRunResult>(
          "workspace/executeCommand",
          { command: SERVER_DRY_RUN_COMMAND, arguments: [params.textDocument.uri] },
          cts.token
        )
        .catch(() => undefined);
      if (viaCommand) return viaCommand;
      throw err;
    } finally {
      if (inFlight.get(key)?.cts === cts) inFlight.delete(key);
      cts.dispose();
    }
  })();
  inFlight.set(key, { version, cts, promise });
  return promise;
}

function activeGcodeEditor(): vscode.TextEditor | undefined {
  const e = vscode.window.activeTextEditor;
  return e && e.document.languageId === LANGUAGE_ID ? e : undefined;
}

// ---- Status bar -------------------------------------------------------------------------

let statusTimer: NodeJS.Timeout | undefined;
let statusSeq = 0;

function scheduleStatus(delayMs: number): void {
  if (statusTimer) clearTimeout(statusTimer);
  statusTimer = setTimeout(() => void refreshStatus(), delayMs);
}

async function refreshStatus(): Promise<void> {
  const editor = activeGcodeEditor();
  if (!editor || !client) {
    statusItem.hide();
    return;
  }
  const seq = ++statusSeq;
  const doc = editor.document;
  statusItem.text = "$(sync~spin) cycle time";
  statusItem.show();
  try {
    const r = await requestDryRun(doc.uri);
    // A newer request (another edit or editor) has started; its answer will be shown instead.
    if (seq !== statusSeq) return;
    // A stopped run's time covers only part of the program.
    const stopped = stoppedText(r);
    statusItem.text = stopped
      ? `$(warning) ${formatDuration(r.cycle_time_s)} partial`
      : `$(watch) ${formatDuration(r.cycle_time_s)}`;
    statusItem.tooltip = new vscode.MarkdownString(
      "**Partscope dry run**\n\n```\n" + summarize(r) + "\n```\n\nClick to show the toolpath."
    );
  } catch (err) {
    if (seq !== statusSeq || isSuperseded(err)) return;
    statusItem.text = "$(watch) –";
    statusItem.tooltip = `Partscope dry run failed: ${err instanceof Error ? err.message : String(err)}`;
  }
}

// ---- Commands ---------------------------------------------------------------------------

async function runDryRunCommand(): Promise<void> {
  const editor = activeGcodeEditor();
  if (!editor) {
    void vscode.window.showWarningMessage("Partscope: open a G-code file first.");
    return;
  }
  try {
    const r = await requestDryRun(editor.document.uri);
    reportChannel ??= vscode.window.createOutputChannel("Partscope dry run");
    reportChannel.clear();
    reportChannel.appendLine(`${vscode.workspace.asRelativePath(editor.document.uri)}`);
    reportChannel.appendLine(summarize(r));
    reportChannel.show(true);
  } catch (err) {
    void vscode.window.showErrorMessage(`Partscope dry run failed: ${err instanceof Error ? err.message : String(err)}`);
  }
}

function showBreakdownReport(r: BreakdownResult): void {
  reportChannel ??= vscode.window.createOutputChannel("Partscope dry run");
  reportChannel.clear();
  reportChannel.appendLine(r.text);
  reportChannel.show(true);
}

async function showPreviewOf(uri: string): Promise<void> {
  const c = client;
  if (!c) return;
  const doc = await vscode.workspace.openTextDocument(c.protocol2CodeConverter.asUri(uri));
  if (preview) preview.show(doc);
  else preview = new ToolpathPreview(extensionContext, doc);
}

function diagnosticCode(d: vscode.Diagnostic): string | undefined {
  const c = d.code;
  if (c === undefined || c === null) return undefined;
  if (typeof c === "object") return String(c.value);
  return String(c);
}

async function explainRuleCommand(code?: string): Promise<void> {
  if (!code) {
    const editor = vscode.window.activeTextEditor;
    const here = editor
      ? vscode.languages
          .getDiagnostics(editor.document.uri)
          .filter((d) => d.range.contains(editor.selection.active))
          .map(diagnosticCode)
          .filter((c): c is string => !!c)
      : [];
    const unique = [...new Set(here)];
    if (unique.length === 1) code = unique[0];
    else if (unique.length > 1) code = await vscode.window.showQuickPick(unique, { placeHolder: "Rule to explain" });
    else code = await vscode.window.showInputBox({ prompt: "Rule code to explain", placeHolder: "e.g. NGC001" });
  }
  if (!code) return;
  const text = await new Promise<string>((resolve) => {
    execFile(serverPath(), ["rule", code as string], { timeout: 10000, maxBuffer: 4 << 20 }, (err, stdout, stderr) => {
      if (err && !stdout) resolve(`# ${code}\n\n\`partscope rule ${code}\` failed:\n\n\`\`\`\n${stderr || err.message}\n\`\`\`\n`);
      else resolve(stdout);
    });
  });
  const doc = await vscode.workspace.openTextDocument({ language: "markdown", content: text });
  await vscode.window.showTextDocument(doc, { viewColumn: vscode.ViewColumn.Beside, preview: true });
}

class ExplainRuleActions implements vscode.CodeActionProvider {
  static readonly kinds = [vscode.CodeActionKind.QuickFix];

  provideCodeActions(
    _doc: vscode.TextDocument,
    _range: vscode.Range,
    context: vscode.CodeActionContext
  ): vscode.CodeAction[] {
    const codes = new Set(context.diagnostics.map(diagnosticCode).filter((c): c is string => !!c));
    return [...codes].map((code) => {
      const a = new vscode.CodeAction(`Explain rule ${code}`, vscode.CodeActionKind.QuickFix);
      a.command = { command: "partscope.explainRule", title: `Explain rule ${code}`, arguments: [code] };
      return a;
    });
  }
}

// ---- Toolpath preview -------------------------------------------------------------------

class ToolpathPreview {
  private readonly panel: vscode.WebviewPanel;
  private uri: vscode.Uri;
  private ready = false;
  private refreshTimer: NodeJS.Timeout | undefined;
  private seq = 0;
  private readonly disposables: vscode.Disposable[] = [];

  constructor(private readonly context: vscode.ExtensionContext, doc: vscode.TextDocument) {
    this.uri = doc.uri;
    const media = vscode.Uri.joinPath(context.extensionUri, "media");
    this.panel = vscode.window.createWebviewPanel(
      "partscope.toolpath",
      this.title(),
      { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true },
      { enableScripts: true, retainContextWhenHidden: true, localResourceRoots: [media] }
    );
    this.panel.webview.html = this.html(media);
    this.panel.onDidDispose(() => this.dispose(), null, this.disposables);
    this.panel.webview.onDidReceiveMessage((m) => void this.onMessage(m), null, this.disposables);
    vscode.window.onDidChangeTextEditorSelection(
      (e) => {
        if (e.textEditor.document.uri.toString() === this.uri.toString()) this.postCursor(e.textEditor);
      },
      null,
      this.disposables
    );
    vscode.window.onDidChangeActiveTextEditor(
      (e) => {
        // Follow the user to another G-code file; ignore other editors (output, settings…).
        if (e && e.document.languageId === LANGUAGE_ID && e.document.uri.toString() !== this.uri.toString()) {
          this.show(e.document);
        }
      },
      null,
      this.disposables
    );
    vscode.workspace.onDidChangeTextDocument(
      (e) => {
        if (e.document.uri.toString() === this.uri.toString()) this.scheduleRefresh(600);
      },
      null,
      this.disposables
    );
  }

  show(doc: vscode.TextDocument): void {
    this.uri = doc.uri;
    this.panel.title = this.title();
    this.panel.reveal(undefined, true);
    this.scheduleRefresh(0);
  }

  private title(): string {
    return `Toolpath: ${path.basename(this.uri.path)}`;
  }

  private html(media: vscode.Uri): string {
    const webview = this.panel.webview;
    const template = fs.readFileSync(vscode.Uri.joinPath(media, "preview.html").fsPath, "utf8");
    return webviewHtml(template, {
      cspSource: webview.cspSource,
      cssUri: webview.asWebviewUri(vscode.Uri.joinPath(media, "preview.css")).toString(),
      scriptUri: webview.asWebviewUri(vscode.Uri.joinPath(media, "preview.js")).toString(),
    });
  }

  private async onMessage(m: { type?: string; line?: number }): Promise<void> {
    if (m.type === "ready") {
      this.ready = true;
      this.scheduleRefresh(0);
    } else if (m.type === "reveal" && typeof m.line === "number") {
      const doc = await vscode.workspace.openTextDocument(this.uri);
      const line = Math.max(0, Math.min(m.line, doc.lineCount - 1));
      const visible = vscode.window.visibleTextEditors.find((e) => e.document.uri.toString() === this.uri.toString());
      const editor = await vscode.window.showTextDocument(doc, {
        viewColumn: visible?.viewColumn ?? vscode.ViewColumn.One,
        preserveFocus: false,
      });
      const range = doc.lineAt(line).range;
      editor.selection = new vscode.Selection(range.start, range.start);
      editor.revealRange(range, vscode.TextEditorRevealType.InCenterIfOutsideViewport);
    }
  }

  private postCursor(editor: vscode.TextEditor): void {
    void this.panel.webview.postMessage({ type: "cursor", line: editor.selection.active.line });
  }

  private scheduleRefresh(delayMs: number): void {
    if (this.refreshTimer) clearTimeout(this.refreshTimer);
    this.refreshTimer = setTimeout(() => void this.refresh(), delayMs);
  }

  private async refresh(): Promise<void> {
    if (!this.ready) return;
    const seq = ++this.seq;
    try {
      const data = await requestDryRun(this.uri);
      if (seq !== this.seq) return;
      await this.panel.webview.postMessage({ type: "data", data, title: path.basename(this.uri.path) });
      const editor = vscode.window.visibleTextEditors.find((e) => e.document.uri.toString() === this.uri.toString());
      if (editor) this.postCursor(editor);
    } catch (err) {
      if (seq !== this.seq || isSuperseded(err)) return;
      void this.panel.webview.postMessage({
        type: "error",
        message: `Dry run failed: ${err instanceof Error ? err.message : String(err)}`,
      });
    }
  }

  dispose(): void {
    if (this.refreshTimer) clearTimeout(this.refreshTimer);
    for (const d of this.disposables.splice(0)) d.dispose();
    if (preview === this) preview = undefined;
    this.panel.dispose();
  }
}

function showToolpathCommand(): void {
  const editor = activeGcodeEditor();
  if (!editor) {
    void vscode.window.showWarningMessage("Partscope: open a G-code file first.");
    return;
  }
  if (preview) preview.show(editor.document);
  else preview = new ToolpathPreview(extensionContext, editor.document);
}

// ---- Activation -------------------------------------------------------------------------

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  extensionContext = context;
  statusItem = vscode.window.createStatusBarItem(vscode.StatusBarAlignment.Right, 100);
  statusItem.name = "Partscope cycle time";
  statusItem.command = "partscope.showToolpath";
  context.subscriptions.push(
    statusItem,
    vscode.commands.registerCommand("partscope.runDryRun", runDryRunCommand),
    vscode.commands.registerCommand("partscope.showToolpath", showToolpathCommand),
    vscode.commands.registerCommand("partscope.explainRule", explainRuleCommand),
    vscode.commands.registerCommand("partscope.restartServer", () => restartClient()),
    vscode.languages.registerCodeActionsProvider({ language: LANGUAGE_ID }, new ExplainRuleActions(), {
      providedCodeActionKinds: ExplainRuleActions.kinds,
    }),
    vscode.window.onDidChangeActiveTextEditor(() => scheduleStatus(0)),
    vscode.workspace.onDidSaveTextDocument((d) => {
      if (d.languageId === LANGUAGE_ID) scheduleStatus(0);
    }),
    vscode.workspace.onDidChangeTextDocument((e) => {
      if (e.document === vscode.window.activeTextEditor?.document && e.document.languageId === LANGUAGE_ID) {
        scheduleStatus(1000);
      }
    }),
    vscode.workspace.onDidChangeConfiguration((e) => {
      // The server picks up dialect/machine/select/ignore through didChangeConfiguration;
      // only a different executable needs a new process.
      if (e.affectsConfiguration("partscope.server.path")) void restartClient();
      else if (e.affectsConfiguration("partscope")) scheduleStatus(300);
    }),
    { dispose: () => preview?.dispose() }
  );
  await startClient();
  scheduleStatus(0);
}

export async function deactivate(): Promise<void> {
  const c = client;
  client = undefined;
  if (c) await c.stop();
}
