// Unit tests of the status-bar / report formatting (out/dryrun.js is built by `npm run compile`).
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const { formatDuration, summarize } = require("../out/dryrun.js");
const fixture = require("./fixtures/sample-dryrun.json");

test("formatDuration", () => {
  assert.equal(formatDuration(63.927), "1:03.9");
  assert.equal(formatDuration(0), "0:00.0");
  assert.equal(formatDuration(59.96), "1:00.0");
  assert.equal(formatDuration(3600 * 2 + 61.4), "2:01:01");
  assert.equal(formatDuration(3599.6), "59:59.6");
  assert.equal(formatDuration(3599.97), "1:00:00");
  assert.equal(formatDuration(7199.6), "2:00:00");
  assert.equal(formatDuration(NaN), "–");
});

test("summarize", () => {
  const lines = summarize(fixture).split("\n");
  assert.equal(lines[0], "cycle time" + " ".repeat(4) + "1:03.9".padStart(22));
  assert.ok(lines.some((l) => /^distance\s+1067\.9 mm$/.test(l)), lines.join("\n"));
  assert.ok(lines.some((l) => /^segments\s+38$/.test(l)));
  assert.ok(lines.some((l) => /^Z range\s+-14\.000 … 50\.000$/.test(l)));
});

test("a stopped run is marked partial and says where it stopped", () => {
  const r = { ...fixture, complete: false, stopped_at: { line: 3, reason: "dwell time P word missing with G4" } };
  const text = summarize(r);
  assert.match(text.split("\n")[0], /\(partial\)$/);
  assert.equal(text.split("\n").pop(), "stopped at line 4: dwell time P word missing with G4");
  assert.doesNotMatch(summarize({ ...fixture, complete: true, stopped_at: null }), /partial|stopped/);
});

test("a decimated toolpath says how far", () => {
  const decimation = {
    tolerance_mm: 0.5, requested_tolerance_mm: 0.5, max_points: 100000, motions: 20002,
    points_in: 40004, points_out: 328, points_dropped: 39676, segments_out: 2,
    decimated: true, capped: false, truncated_at_line: null,
  };
  const lines = summarize({ ...fixture, decimation }).split("\n");
  assert.ok(lines.some((l) => /^toolpath\s+328 of 40004 points$/.test(l)), lines.join("\n"));
  assert.ok(lines.some((l) => /^  within\s+0\.500 mm$/.test(l)), lines.join("\n"));
  const cut = summarize({ ...fixture, decimation: { ...decimation, capped: true, truncated_at_line: 99 } });
  assert.match(cut, /0\.500 mm \(capped\)/);
  assert.equal(cut.split("\n").pop(), "toolpath cut at line 100 (size cap)");
  assert.doesNotMatch(summarize(fixture), /toolpath/);
});
