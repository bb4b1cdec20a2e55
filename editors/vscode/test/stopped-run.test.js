// End to end: the real server's dry run of a program that stops early, shown in the preview
// in headless Chromium. The run must be marked partial and say where it stopped; nothing after
// the stop may be drawn. Needs PARTSCOPE_BIN (editors/ci.sh sets it).
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const { spawn } = require("node:child_process");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");
const { pathToFileURL } = require("node:url");
const { chromium } = require("playwright-core");
const { webviewHtml } = require("../out/webview.js");
const { summarize, stoppedText } = require("../out/dryrun.js");

const ROOT = path.resolve(__dirname, "..");
const PROGRAM = path.join(__dirname, "fixtures", "stopped.ngc");
const CHROMIUM = process.env.PARTSCOPE_CHROMIUM || "/usr/bin/chromium";
const BIN = process.env.PARTSCOPE_BIN;

// A JSON-RPC client over the server's stdio (Content-Length framing).
function lspClient(bin) {
  const child = spawn(bin, ["lsp"], { stdio: ["pipe", "pipe", "inherit"] });
  let buf = Buffer.alloc(0);
  let nextId = 1;
  const pending = new Map();
  child.stdout.on("data", (chunk) => {
    buf = Buffer.concat([buf, chunk]);
    for (;;) {
      const end = buf.indexOf("\r\n\r\n");
      if (end < 0) return;
      const m = /Content-Length: *(\d+)/i.exec(buf.subarray(0, end).toString("ascii"));
      assert.ok(m, "server frame has a Content-Length");
      const len = Number(m[1]);
      if (buf.length < end + 4 + len) return;
      const msg = JSON.parse(buf.subarray(end + 4, end + 4 + len).toString("utf8"));
      buf = buf.subarray(end + 4 + len);
      if (msg.id !== undefined && pending.has(msg.id) && msg.method === undefined) {
        const { resolve, reject } = pending.get(msg.id);
        pending.delete(msg.id);
        if (msg.error) reject(new Error(`${msg.error.code}: ${msg.error.message}`));
        else resolve(msg.result);
      } else if (msg.id !== undefined && msg.method !== undefined) {
        // Server-to-client requests (registrations, configuration): answer with nothing.
        send({ jsonrpc: "2.0", id: msg.id, result: null });
      }
    }
  });
  function send(msg) {
    const body = Buffer.from(JSON.stringify(msg), "utf8");
    child.stdin.write(`Content-Length: ${body.length}\r\n\r\n`);
    child.stdin.write(body);
  }
  return {
    request(method, params) {
      const id = nextId++;
      send({ jsonrpc: "2.0", id, method, params });
      return new Promise((resolve, reject) => pending.set(id, { resolve, reject }));
    },
    notify(method, params) {
      send({ jsonrpc: "2.0", method, params });
    },
    close() {
      child.kill();
    },
  };
}

test("a stopped dry run is partial in the preview", { skip: BIN ? false : "PARTSCOPE_BIN not set" }, async (t) => {
  assert.ok(fs.existsSync(CHROMIUM), `Chromium not found at ${CHROMIUM} (apt-get install chromium)`);
  const text = fs.readFileSync(PROGRAM, "utf8");
  const lines = text.split("\n");
  const stopLine = lines.findIndex((l) => l.startsWith("o100 endwhile"));
  const client = lspClient(BIN);
  t.after(() => client.close());
  await client.request("initialize", { processId: null, rootUri: null, capabilities: {} });
  client.notify("initialized", {});
  const uri = pathToFileURL(PROGRAM).href;
  client.notify("textDocument/didOpen", { textDocument: { uri, languageId: "gcode", version: 1, text } });
  const result = await client.request("partscope/dryRun", { textDocument: { uri } });

  await t.test("the server says where and why the run stopped", () => {
    assert.equal(result.complete, false);
    assert.equal(result.stopped_at.line, stopLine);
    assert.match(result.stopped_at.reason, /^undefined O-word label: 'o100 endwhile'/);
    // The status bar and the report use the same words.
    assert.equal(stoppedText(result), `stopped at line ${stopLine + 1}: ${result.stopped_at.reason}`);
    assert.match(summarize(result).split("\n")[0], /\(partial\)$/);
  });

  await t.test("only the blocks before the stop have motion", () => {
    const segs = result.toolpath.segments;
    assert.ok(segs.length > 0);
    assert.ok(segs.every((s) => s.line < stopLine), JSON.stringify(segs.map((s) => s.line)));
    assert.ok(segs.some((s) => s.line === lines.indexOf("G1 X40")), "the cut before the stop is drawn");
  });

  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-chromium-"));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"],
    viewport: { width: 1100, height: 720 },
  });
  t.after(async () => {
    await context.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  });
  const page = context.pages()[0] || (await context.newPage());
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  await page.addInitScript(() => {
    window.acquireVsCodeApi = () => ({ postMessage() {}, getState() {}, setState() {} });
  });
  // The webview page as the extension builds it, served from a file: URL directory.
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-webview-"));
  t.after(() => fs.rmSync(dir, { recursive: true, force: true }));
  for (const f of ["preview.js", "preview.css"]) fs.copyFileSync(path.join(ROOT, "media", f), path.join(dir, f));
  const origin = pathToFileURL(dir).href;
  const html = webviewHtml(fs.readFileSync(path.join(ROOT, "media", "preview.html"), "utf8"), {
    cspSource: "file:",
    cssUri: `${origin}/preview.css`,
    scriptUri: `${origin}/preview.js`,
  });
  fs.writeFileSync(path.join(dir, "webview.html"), html);
  await page.goto(`${origin}/webview.html`);
  await page.waitForFunction(() => window.partscopePreview !== undefined);
  await page.evaluate((data) => window.postMessage({ type: "data", data, title: "stopped.ngc" }, "*"), result);
  await page.waitForFunction((n) => window.partscopePreview.segments.length === n, result.toolpath.segments.length);

  await t.test("the stats say partial and name the stop", async () => {
    const rows = await page.locator("#stats tr").allInnerTexts();
    assert.match(rows[0], /^Cycle time\s+\d+:\d\d\.\d \(partial\)$/);
    assert.equal(rows[1].replace(/\s+/g, " "), `Stopped at line ${stopLine + 1}: ${result.stopped_at.reason}`);
  });

  await t.test("a narrow panel still says partial", async () => {
    await page.setViewportSize({ width: 560, height: 600 });
    await page.waitForFunction(() => document.body.classList.contains("compact"));
    const visible = await page.locator("#stats tr:visible").allInnerTexts();
    assert.equal(visible.length, 1);
    assert.match(visible[0], /\(partial\)$/);
  });

  await t.test("no script errors", () => {
    assert.deepEqual(errors, []);
  });
});
