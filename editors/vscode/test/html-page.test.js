// Browser test of the page `partscope run FILE --html OUT` writes: the preview's viewer with the
// dry run inside, opened from file:// in headless Chromium. It must fetch nothing, and draw the
// program's known geometry (a 40 x 20 mm rectangle at Z0) where and as large as the fit puts it.
// Needs PARTSCOPE_BIN (editors/ci.sh sets it).
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const { execFileSync } = require("node:child_process");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");
const { pathToFileURL } = require("node:url");
const { chromium } = require("playwright-core");

const CHROMIUM = process.env.PARTSCOPE_CHROMIUM || "/usr/bin/chromium";
const BIN = process.env.PARTSCOPE_BIN;
const OUT = path.join(__dirname, "out");
const PROGRAM = [
  "G21 G90 G17",
  "G0 X0 Y0 Z5",
  "G1 Z0 F600",
  "G1 X40 F1200",
  "G1 Y20",
  "G1 X0",
  "G1 Y0",
  "G0 Z5",
  "M2",
  "",
].join("\n");
// The viewer's colour of the fastest feed (RAMP's last stop in media/preview.js).
const FAST = [240, 60, 40];
const BACKGROUND = [0x1e, 0x1e, 0x1e];

function colourDistance(a, b) {
  return Math.abs(a[0] - b[0]) + Math.abs(a[1] - b[1]) + Math.abs(a[2] - b[2]);
}

test("the --html page in headless Chromium", { skip: BIN ? false : "PARTSCOPE_BIN not set" }, async (t) => {
  assert.ok(fs.existsSync(CHROMIUM), `Chromium not found at ${CHROMIUM} (apt-get install chromium)`);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-html-"));
  const program = path.join(dir, "rect.ngc");
  const html = path.join(dir, "rect.html");
  fs.writeFileSync(program, PROGRAM);
  execFileSync(BIN, ["run", program, "--html", html], { stdio: ["ignore", "ignore", "inherit"] });
  const summary = JSON.parse(execFileSync(BIN, ["run", program, "--format", "json"]).toString("utf8"));

  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-chromium-"));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
      "--disable-component-update", "--disable-sync"],
    viewport: { width: 1100, height: 720 },
    deviceScaleFactor: 1,
  });
  t.after(async () => {
    await context.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
    fs.rmSync(dir, { recursive: true, force: true });
  });
  const page = context.pages()[0] || (await context.newPage());
  const errors = [];
  const requests = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("request", (r) => requests.push(r.url()));
  await page.addInitScript(() => {
    window.__violations = [];
    document.addEventListener("securitypolicyviolation", (e) => window.__violations.push(e.violatedDirective + " " + e.blockedURI));
  });
  const url = pathToFileURL(html).href;
  await page.goto(url);
  await page.waitForFunction(() => window.partscopePreview && window.partscopePreview.segments.length === 7, null, {
    timeout: 10000,
  });

  await t.test("loads nothing but itself", async () => {
    assert.deepEqual(requests, [url]);
    assert.deepEqual(await page.evaluate(() => window.__violations), []);
    assert.equal(await page.locator("#title").innerText(), "rect.ngc");
  });

  await t.test("shows the run's figures", async () => {
    const rows = await page.locator("#stats tr").allInnerTexts();
    const s = summary.cycle_time_s;
    const expected = `${Math.floor(s / 60)}:${(s % 60).toFixed(1).padStart(4, "0")}`;
    assert.match(rows[0], new RegExp(`^Cycle time\\s+${expected}$`));
    // Rapid up 5, plunge 5, the 120 mm rectangle, rapid up 5.
    assert.ok(rows.some((r) => /^Distance\s+135\.0 mm$/.test(r)), rows.join(" | "));
    assert.ok(rows.some((r) => /^X range\s+0\.000 … 40\.000$/.test(r)), rows.join(" | "));
    assert.ok(rows.some((r) => /^Y range\s+0\.000 … 20\.000$/.test(r)), rows.join(" | "));
    assert.ok(rows.some((r) => /^Z range\s+0\.000 … 5\.000$/.test(r)), rows.join(" | "));
  });

  await t.test("the top view draws the rectangle, fitted, where the viewer maps it", async () => {
    await page.click('button[data-view="top"]');
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r()))));
    fs.mkdirSync(OUT, { recursive: true });
    await page.screenshot({ path: path.join(OUT, "html-page-top.png") });
    // The pixels in the fast feed's colour: only the rectangle's four sides have it.
    const drawn = await page.evaluate(
      ({ fast }) => {
        const c = document.getElementById("partscope-canvas");
        const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
        let box = null;
        for (let y = 0; y < c.height; y++) {
          for (let x = 0; x < c.width; x++) {
            const i = 4 * (y * c.width + x);
            if (Math.abs(d[i] - fast[0]) + Math.abs(d[i + 1] - fast[1]) + Math.abs(d[i + 2] - fast[2]) > 40) continue;
            if (!box) box = { x0: x, y0: y, x1: x, y1: y };
            box.x0 = Math.min(box.x0, x);
            box.x1 = Math.max(box.x1, x);
            box.y0 = Math.min(box.y0, y);
            box.y1 = Math.max(box.y1, y);
          }
        }
        const p = window.partscopePreview;
        return { box, width: c.clientWidth, height: c.clientHeight, origin: p.project([0, 0, 0]), far: p.project([40, 20, 0]) };
      },
      { fast: FAST }
    );
    const { box, width, height } = drawn;
    assert.ok(box, "the rectangle is drawn");
    // The fit leaves room for the statistics (250 px left) and legend (40 px right), 24 px above
    // and 40 below, and scales the 40 x 20 mm bounds to fill what is left.
    const scale = Math.min((width - 290) / 40, (height - 64) / 20);
    const w = box.x1 - box.x0;
    const h = box.y1 - box.y0;
    // A 1.6 px stroke adds up to two pixels to each extent.
    assert.ok(Math.abs(w - 40 * scale) <= 3, `drawn width ${w} px, expected ${40 * scale}`);
    assert.ok(Math.abs(h - 20 * scale) <= 3, `drawn height ${h} px, expected ${20 * scale}`);
    // X to the right, Y up: X0 Y0 is the lower left corner, X40 Y20 the upper right.
    assert.ok(Math.abs(drawn.origin[0] - (box.x0 + 1)) <= 2 && Math.abs(drawn.origin[1] - (box.y1 - 1)) <= 2, JSON.stringify(drawn));
    assert.ok(Math.abs(drawn.far[0] - (box.x1 - 1)) <= 2 && Math.abs(drawn.far[1] - (box.y0 + 1)) <= 2, JSON.stringify(drawn));
    // Every side is drawn along its length; the inside is empty. A pixel is the one nearest the
    // fast feed's colour within two pixels of (x, y): a thin stroke covers a pixel row partly.
    const pixel = (x, y) =>
      page.evaluate(
        ({ x, y, fast }) => {
          const d = document.getElementById("partscope-canvas").getContext("2d").getImageData(x - 2, y - 2, 5, 5).data;
          let best = null;
          for (let i = 0; i < d.length; i += 4) {
            const px = [d[i], d[i + 1], d[i + 2]];
            const dist = Math.abs(px[0] - fast[0]) + Math.abs(px[1] - fast[1]) + Math.abs(px[2] - fast[2]);
            if (!best || dist < best.dist) best = { px, dist };
          }
          return best.px;
        },
        { x: Math.round(x), y: Math.round(y), fast: FAST }
      );
    const [x0, y0, x1, y1] = [box.x0 + 1, box.y1 - 1, box.x1 - 1, box.y0 + 1];
    for (const f of [0.25, 0.5, 0.75]) {
      for (const [x, y] of [[x0 + f * (x1 - x0), y0], [x0 + f * (x1 - x0), y1], [x0, y0 + f * (y1 - y0)], [x1, y0 + f * (y1 - y0)]]) {
        const px = await pixel(x, y);
        assert.ok(colourDistance(px, FAST) < 80, `side at (${x}, ${y}) drawn, got ${px}`);
      }
    }
    const inside = await pixel((x0 + x1) / 2, (y0 + y1) / 2);
    assert.ok(colourDistance(inside, BACKGROUND) < 6, `inside is background, got ${inside}`);
  });

  await t.test("no script errors", () => {
    assert.deepEqual(errors, []);
  });
});
