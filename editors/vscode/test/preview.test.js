// Browser test of media/preview.{html,js}: loads the page in the system Chromium through
// playwright-core (no downloaded browsers), feeds it the sample dry-run fixture and checks
// what a user would see and do: drawn segments, click-to-reveal, cursor-line highlight.
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const fs = require("node:fs");
const http = require("node:http");
const os = require("node:os");
const path = require("node:path");
const { chromium } = require("playwright-core");
const { webviewHtml } = require("../out/webview.js");

const ROOT = path.resolve(__dirname, "..");
const FIXTURE = path.join(__dirname, "fixtures", "sample-dryrun.json");
const OUT = path.join(__dirname, "out");
const CHROMIUM = process.env.PARTSCOPE_CHROMIUM || "/usr/bin/chromium";
const ARGS = [
  "--headless",
  "--no-sandbox",
  "--disable-gpu",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
];
const HIGHLIGHT = [0xff, 0x3d, 0xf5];
const BACKGROUND = [0x1e, 0x1e, 0x1e];

const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".json": "application/json" };

// Serves media/ at / and the fixtures at /fixtures/, on loopback only.
function serve() {
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, "http://127.0.0.1");
    if (url.pathname === "/favicon.ico") {
      res.writeHead(204);
      res.end();
      return;
    }
    if (url.pathname === "/webview.html") {
      // What the extension puts into the webview (src/webview.ts), with this server as the
      // webview resource origin.
      const origin = `http://127.0.0.1:${server.address().port}`;
      const template = fs.readFileSync(path.join(ROOT, "media", "preview.html"), "utf8");
      const html = webviewHtml(template, {
        cspSource: origin,
        cssUri: `${origin}/preview.css`,
        scriptUri: `${origin}/preview.js`,
      });
      res.writeHead(200, { "content-type": "text/html" });
      res.end(html);
      return;
    }
    let file;
    if (url.pathname.startsWith("/fixtures/")) file = path.join(__dirname, "fixtures", path.basename(url.pathname));
    else file = path.join(ROOT, "media", path.basename(url.pathname));
    fs.readFile(file, (err, body) => {
      if (err) {
        res.writeHead(404);
        res.end();
        return;
      }
      res.writeHead(200, { "content-type": TYPES[path.extname(file)] || "application/octet-stream" });
      res.end(body);
    });
  });
  return new Promise((resolve) => server.listen(0, "127.0.0.1", () => resolve(server)));
}

function colourDistance(a, b) {
  return Math.abs(a[0] - b[0]) + Math.abs(a[1] - b[1]) + Math.abs(a[2] - b[2]);
}

// The pixel in a 5x5 neighbourhood of (x, y) that differs most from the background.
async function strongestPixel(page, x, y) {
  return page.evaluate(
    ({ x, y, bg }) => {
      const c = document.getElementById("partscope-canvas");
      const dpr = window.devicePixelRatio || 1;
      const ctx = c.getContext("2d");
      const px = Math.round(x * dpr) - 2;
      const py = Math.round(y * dpr) - 2;
      const d = ctx.getImageData(px, py, 5, 5).data;
      let best = [d[0], d[1], d[2]];
      let bestD = -1;
      for (let i = 0; i < d.length; i += 4) {
        const dd = Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]);
        if (dd > bestD) {
          bestD = dd;
          best = [d[i], d[i + 1], d[i + 2]];
        }
      }
      return best;
    },
    { x, y, bg: BACKGROUND }
  );
}

async function nextFrames(page) {
  await page.evaluate(
    () => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r())))
  );
}

test("toolpath preview in headless Chromium", async (t) => {
  assert.ok(fs.existsSync(CHROMIUM), `Chromium not found at ${CHROMIUM} (apt-get install chromium)`);
  const fixture = JSON.parse(fs.readFileSync(FIXTURE, "utf8"));
  const server = await serve();
  const port = server.address().port;
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-chromium-"));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: ARGS,
    viewport: { width: 1100, height: 720 },
  });
  t.after(async () => {
    await context.close();
    server.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  });
  const page = context.pages()[0] || (await context.newPage());
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));

  await page.goto(`http://127.0.0.1:${port}/preview.html?sample=/fixtures/sample-dryrun.json`);
  await page.waitForFunction(
    (n) => window.partscopePreview && window.partscopePreview.segments.length === n,
    fixture.toolpath.segments.length,
    { timeout: 10000 }
  );
  await nextFrames(page);
  const canvasBox = await page.locator("#partscope-canvas").boundingBox();
  assert.ok(canvasBox && canvasBox.width > 500 && canvasBox.height > 400, "canvas fills the page");

  await t.test("announces itself to the host", async () => {
    const outbox = await page.evaluate(() => window.partscopeOutbox);
    assert.deepEqual(outbox[0], { type: "ready" });
  });

  await t.test("shows the cycle time from the result", async () => {
    const first = await page.locator("#stats tr").first().innerText();
    // 63.927 s from the fixture, shown as m:ss.s.
    assert.match(first, /Cycle time\s+1:03\.9/);
  });

  await t.test("draws every segment and leaves empty space as background", async () => {
    const corner = await strongestPixel(page, canvasBox.width - 20, canvasBox.height - 60);
    assert.ok(colourDistance(corner, BACKGROUND) < 6, `empty corner is background, got ${corner}`);
    for (let i = 0; i < fixture.toolpath.segments.length; i++) {
      const p = await page.evaluate((i) => window.partscopePreview.segmentScreenPoint(i), i);
      assert.ok(p, `segment ${i} has a screen point`);
      assert.ok(p.x > 0 && p.y > 0 && p.x < canvasBox.width && p.y < canvasBox.height, `segment ${i} is in view`);
      const px = await strongestPixel(page, p.x, p.y);
      assert.ok(colourDistance(px, BACKGROUND) > 60, `segment ${i} (line ${fixture.toolpath.segments[i].line}) is drawn, got ${px}`);
    }
  });

  // The second drill plunge ("G1 Z-14 F180" at X60 Y15) stands alone in the iso view.
  const plungeIndex = fixture.toolpath.segments.findIndex(
    (s, i) => s.kind === "feed" && s.feed === 180 && s.points[0][0] === 60 && s.points[0][1] === 15 && i > 0
  );
  const plunge = fixture.toolpath.segments[plungeIndex];

  await t.test("click on a segment posts a reveal of its line and highlights it", async () => {
    assert.ok(plungeIndex > 0);
    const p = await page.evaluate((i) => window.partscopePreview.segmentScreenPoint(i), plungeIndex);
    const before = await strongestPixel(page, p.x, p.y);
    assert.ok(colourDistance(before, HIGHLIGHT) > 60, `not highlighted before the click, got ${before}`);
    await page.mouse.click(canvasBox.x + p.x, canvasBox.y + p.y);
    const reveal = await page.evaluate(() => window.partscopeOutbox.filter((m) => m.type === "reveal"));
    assert.deepEqual(reveal, [{ type: "reveal", line: plunge.line }]);
    await nextFrames(page);
    const after = await strongestPixel(page, p.x, p.y);
    assert.ok(colourDistance(after, HIGHLIGHT) < 40, `highlight colour after the click, got ${after}`);
  });

  await t.test("hovering a segment shows its 1-based line, kind, feed and tool", async () => {
    const p = await page.evaluate((i) => window.partscopePreview.segmentScreenPoint(i), plungeIndex);
    await page.mouse.move(canvasBox.x + p.x + 1, canvasBox.y + p.y);
    await page.waitForFunction(() => getComputedStyle(document.getElementById("tooltip")).display === "block");
    assert.equal(await page.locator("#tooltip").innerText(), `line ${plunge.line + 1} · feed · 180 mm/min · T2`);
    await page.mouse.move(canvasBox.x + canvasBox.width - 20, canvasBox.y + canvasBox.height - 60);
    await page.waitForFunction(() => getComputedStyle(document.getElementById("tooltip")).display === "none");
  });

  await t.test("cursor messages from the host move the highlight", async () => {
    const contour = fixture.toolpath.segments.findIndex((s) => s.kind === "arc");
    const line = fixture.toolpath.segments[contour].line;
    const p = await page.evaluate((i) => window.partscopePreview.segmentScreenPoint(i), contour);
    const q = await page.evaluate((i) => window.partscopePreview.segmentScreenPoint(i), plungeIndex);
    const before = await strongestPixel(page, p.x, p.y);
    assert.ok(colourDistance(before, HIGHLIGHT) > 60, `arc not highlighted yet, got ${before}`);
    await page.evaluate((line) => window.postMessage({ type: "cursor", line }, "*"), line);
    await page.waitForFunction((line) => window.partscopePreview.cursorLine === line, line);
    await nextFrames(page);
    const after = await strongestPixel(page, p.x, p.y);
    assert.ok(colourDistance(after, HIGHLIGHT) < 40, `arc highlighted, got ${after}`);
    const old = await strongestPixel(page, q.x, q.y);
    assert.ok(colourDistance(old, HIGHLIGHT) > 60, `plunge no longer highlighted, got ${old}`);
    fs.mkdirSync(OUT, { recursive: true });
    await page.screenshot({ path: path.join(OUT, "preview-iso.png") });
  });

  await t.test("top view projects X right and Y up", async () => {
    await page.click('button[data-view="top"]');
    await nextFrames(page);
    const o = await page.evaluate(() => window.partscopePreview.project([0, 0, 0]));
    const x = await page.evaluate(() => window.partscopePreview.project([80, 0, 0]));
    const y = await page.evaluate(() => window.partscopePreview.project([0, 50, 0]));
    assert.ok(x[0] > o[0] + 100 && Math.abs(x[1] - o[1]) < 1e-6);
    assert.ok(y[1] < o[1] - 100 && Math.abs(y[0] - o[0]) < 1e-6);
    // Drill plunges look end-on from the top: each hole gets a ring in the plunge's feed colour.
    const hole = await page.evaluate(() => window.partscopePreview.project([60, 35, 0]));
    const ring = await strongestPixel(page, hole[0] + 4, hole[1]);
    assert.ok(colourDistance(ring, BACKGROUND) > 60, `ring drawn around the hole at X60 Y35, got ${ring}`);
    await page.screenshot({ path: path.join(OUT, "preview-top.png") });
  });

  await t.test("a narrow panel keeps only the cycle time over the drawing", async () => {
    await page.setViewportSize({ width: 560, height: 600 });
    await page.waitForFunction(() => document.body.classList.contains("compact"));
    assert.equal(await page.locator("#stats tr:visible").count(), 1);
    await page.setViewportSize({ width: 1100, height: 720 });
    await page.waitForFunction(() => !document.body.classList.contains("compact"));
    assert.ok((await page.locator("#stats tr:visible").count()) > 5);
  });

  await t.test("a decimated segment is drawn, hovered and highlighted line by line", async () => {
    const decimated = {
      ...fixture,
      toolpath: {
        bounds: { min: [0, 0, 0], max: [10, 10, 0] },
        segments: [
          { kind: "feed", line: 5, feed: 500, tool: 1, points: [[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]], lines: [5, 5, 7, 9] },
        ],
      },
      decimation: {
        tolerance_mm: 0.5, requested_tolerance_mm: 0.5, max_points: 100000, motions: 20, points_in: 40,
        points_out: 4, points_dropped: 36, segments_out: 1, decimated: true, capped: false, truncated_at_line: null,
      },
    };
    await page.evaluate((data) => window.postMessage({ type: "data", data }, "*"), decimated);
    await page.waitForFunction(() => window.partscopePreview.segments.length === 3);
    const pieces = await page.evaluate(() => window.partscopePreview.segments.map((s) => [s.line, s.points.length]));
    assert.deepEqual(pieces, [[5, 2], [7, 2], [9, 2]]);
    const rows = await page.locator("#stats").innerText();
    assert.match(rows, /Toolpath\s+4 of 40 points, within 0\.500 mm/);
    await page.evaluate(() => window.postMessage({ type: "cursor", line: 7 }, "*"));
    await page.waitForFunction(() => window.partscopePreview.cursorLine === 7);
    assert.deepEqual(await page.evaluate(() => window.partscopePreview.highlightedSegments()), [1]);
  });

  await t.test("no script errors", () => {
    assert.deepEqual(errors, []);
  });
});

test("webview HTML runs under its Content-Security-Policy and talks to the VS Code API", async (t) => {
  const server = await serve();
  const port = server.address().port;
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-chromium-"));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: ARGS,
    viewport: { width: 800, height: 600 },
  });
  t.after(async () => {
    await context.close();
    server.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  });
  const page = context.pages()[0] || (await context.newPage());
  const consoleErrors = [];
  page.on("console", (m) => {
    if (m.type() === "error") consoleErrors.push(m.text());
  });
  await page.addInitScript(() => {
    window.__violations = [];
    document.addEventListener("securitypolicyviolation", (e) => window.__violations.push(e.violatedDirective + " " + e.blockedURI));
    window.__sent = [];
    window.acquireVsCodeApi = () => ({
      postMessage: (m) => window.__sent.push(m),
      getState: () => undefined,
      setState: () => undefined,
    });
  });
  await page.goto(`http://127.0.0.1:${port}/webview.html`);
  const csp = await page.locator('meta[http-equiv="Content-Security-Policy"]').getAttribute("content");
  assert.match(csp, /script-src http:\/\/127\.0\.0\.1:\d+;/);
  await page.waitForFunction(() => window.__sent.length > 0);
  assert.deepEqual(await page.evaluate(() => window.__sent), [{ type: "ready" }]);
  const fixture = JSON.parse(fs.readFileSync(FIXTURE, "utf8"));
  await page.evaluate((data) => window.postMessage({ type: "data", data, title: "sample.ngc" }, "*"), fixture);
  await page.waitForFunction((n) => window.partscopePreview.segments.length === n, fixture.toolpath.segments.length);
  assert.equal(await page.locator("#title").innerText(), "sample.ngc");
  // The legend's gradient is an inline style; the CSP must let it through.
  const gradient = await page.locator(".legend-bar").evaluate((el) => getComputedStyle(el).backgroundImage);
  assert.match(gradient, /linear-gradient/);
  assert.deepEqual(await page.evaluate(() => window.__violations), []);
  assert.deepEqual(consoleErrors, []);
  // An injected inline script must be refused, or the policy is not in force at all.
  await page.evaluate(() => {
    const s = document.createElement("script");
    s.textContent = "window.__inline = 1";
    document.body.appendChild(s);
  });
  assert.equal(await page.evaluate(() => window.__inline), undefined);
});
