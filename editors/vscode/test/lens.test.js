// The cycle-time lens's click in the extension: the executeCommand middleware (out/lens.js),
// first with a stub server, then against the real one (PARTSCOPE_BIN, set by editors/ci.sh)
// on editors/test/loop.ngc, whose cycle time must be the one `partscope run --format json` gives.
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const { spawn, execFileSync } = require("node:child_process");
const path = require("node:path");
const fs = require("node:fs");
const { pathToFileURL } = require("node:url");
const { executeCommand, BREAKDOWN_COMMAND } = require("../out/lens.js");

const BIN = process.env.PARTSCOPE_BIN;
const PROGRAM = path.resolve(__dirname, "..", "..", "test", "loop.ngc");

test("the lens's command asks for no server message, reports and opens the preview", async () => {
  const sent = [];
  const shown = [];
  const previews = [];
  const answer = { uri: "file:///w/a.ngc", version: 3, cycle_time_s: 5, complete: true, text: "a.ngc: cycle time 0:05.0 (5.000 s)" };
  const r = await executeCommand(
    BREAKDOWN_COMMAND,
    ["file:///w/a.ngc"],
    (command, args) => {
      sent.push([command, args]);
      return Promise.resolve(answer);
    },
    { report: (x) => shown.push(x), preview: (uri) => previews.push(uri) }
  );
  assert.deepEqual(sent, [[BREAKDOWN_COMMAND, ["file:///w/a.ngc", { show: false }]]]);
  assert.equal(r, answer);
  assert.deepEqual(shown, [answer]);
  assert.deepEqual(previews, ["file:///w/a.ngc"]);
});

test("other commands reach the server unchanged", async () => {
  const sent = [];
  const r = await executeCommand(
    "partscope.dryRun",
    ["file:///w/a.ngc"],
    (command, args) => {
      sent.push([command, args]);
      return 42;
    },
    { report: () => assert.fail("no report"), preview: () => assert.fail("no preview") }
  );
  assert.equal(r, 42);
  assert.deepEqual(sent, [["partscope.dryRun", ["file:///w/a.ngc"]]]);
});

// A JSON-RPC client over the server's stdio that records the server's notifications.
function lspClient(bin) {
  const child = spawn(bin, ["lsp"], { stdio: ["pipe", "pipe", "inherit"] });
  let buf = Buffer.alloc(0);
  let nextId = 1;
  const pending = new Map();
  const notifications = [];
  const send = (msg) => {
    const body = Buffer.from(JSON.stringify(msg), "utf8");
    child.stdin.write(`Content-Length: ${body.length}\r\n\r\n`);
    child.stdin.write(body);
  };
  child.stdout.on("data", (chunk) => {
    buf = Buffer.concat([buf, chunk]);
    for (;;) {
      const end = buf.indexOf("\r\n\r\n");
      if (end < 0) return;
      const len = Number(/Content-Length: *(\d+)/i.exec(buf.subarray(0, end).toString("ascii"))[1]);
      if (buf.length < end + 4 + len) return;
      const msg = JSON.parse(buf.subarray(end + 4, end + 4 + len).toString("utf8"));
      buf = buf.subarray(end + 4 + len);
      if (msg.method === undefined && pending.has(msg.id)) {
        const { resolve, reject } = pending.get(msg.id);
        pending.delete(msg.id);
        if (msg.error) reject(new Error(`${msg.error.code}: ${msg.error.message}`));
        else resolve(msg.result);
      } else if (msg.method !== undefined && msg.id !== undefined) {
        send({ jsonrpc: "2.0", id: msg.id, result: null });
      } else if (msg.method !== undefined) {
        notifications.push(msg);
      }
    }
  });
  return {
    notifications,
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

test("a click on the real server's lens shows the CLI's cycle time", { skip: BIN ? false : "PARTSCOPE_BIN not set" }, async (t) => {
  const cli = JSON.parse(execFileSync(BIN, ["run", PROGRAM, "--format", "json", "--what-if", "off"], { encoding: "utf8" }));
  const client = lspClient(BIN);
  t.after(() => client.close());
  await client.request("initialize", { processId: null, rootUri: null, capabilities: {} });
  client.notify("initialized", {});
  const uri = pathToFileURL(PROGRAM).href;
  client.notify("textDocument/didOpen", {
    textDocument: { uri, languageId: "gcode", version: 1, text: fs.readFileSync(PROGRAM, "utf8") },
  });
  const lenses = await client.request("textDocument/codeLens", { textDocument: { uri } });
  const lens = lenses[0].command;
  assert.equal(lens.command, BREAKDOWN_COMMAND);
  const shown = [];
  const previews = [];
  const r = await executeCommand(
    lens.command,
    lens.arguments,
    (command, args) => client.request("workspace/executeCommand", { command, arguments: args }),
    { report: (x) => shown.push(x.text), preview: (u) => previews.push(u) }
  );
  assert.equal(r.cycle_time_s, cli.cycle_time_s);
  assert.equal(shown.length, 1);
  assert.equal(shown[0].split("\n")[0], `loop.ngc: cycle time 0:05.1 (${cli.cycle_time_s.toFixed(3)} s)`);
  assert.deepEqual(previews, [uri]);
  // The report is the only place the breakdown appears: the server sent no message.
  await client.request("shutdown", null);
  assert.deepEqual(
    client.notifications.filter((n) => n.method === "window/showMessage"),
    []
  );
});
