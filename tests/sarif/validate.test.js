// `partscope check --format sarif` against the OASIS SARIF 2.1.0 JSON schema, on every rule
// fixture of every dialect at once, on a subprogram's diagnostic, on awkward file names and on
// files that cannot be read; plus what the schema does not say but code-scanning hosts need
// (repository-relative, percent-encoded URIs under %SRCROOT%, columnKind). Needs PARTSCOPE_BIN.
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const { execFileSync } = require("node:child_process");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");
const Ajv = require("ajv-draft-04");
const addFormats = require("ajv-formats");

const BIN = process.env.PARTSCOPE_BIN;
const ROOT = path.resolve(__dirname, "..", "..");
const SCHEMA = require.resolve("@microsoft/jest-sarif/lib/schemas/sarif-2.1.0-rtm.5.json");

function validator() {
  // The schema's `language` pattern is not valid with the `u` flag (a stray `]`).
  const ajv = new Ajv({ allErrors: true, strict: false, unicodeRegExp: false });
  addFormats(ajv);
  return ajv.compile(JSON.parse(fs.readFileSync(SCHEMA, "utf8")));
}

// Runs check in `cwd`; exit 1 (findings) is a normal outcome, exit 2 one for unreadable files.
function sarif(args, cwd, status = 1) {
  let out;
  try {
    out = execFileSync(BIN, ["check", "--format", "sarif", ...args], { cwd, maxBuffer: 256 << 20 });
  } catch (e) {
    assert.equal(e.status, status, `exit ${e.status}: ${e.stderr}`);
    out = e.stdout;
  }
  return JSON.parse(out.toString("utf8"));
}

function assertValid(log, what) {
  const validate = validator();
  const ok = validate(log);
  assert.ok(ok, `${what}: ${JSON.stringify(validate.errors && validate.errors.slice(0, 5), null, 1)}`);
}

function uris(log) {
  return log.runs.flatMap((r) =>
    r.results.flatMap((res) => (res.locations || []).map((l) => l.physicalLocation.artifactLocation))
  );
}

const skip = BIN ? false : "PARTSCOPE_BIN not set";

test("every rule fixture of every dialect in one log is valid SARIF 2.1.0", { skip }, () => {
  const rules = path.join(ROOT, "analyzer", "tests", "rules");
  const files = fs
    .readdirSync(rules)
    .flatMap((code) => fs.readdirSync(path.join(rules, code)).map((f) => path.join("analyzer", "tests", "rules", code, f)))
    .filter((f) => /\.(ngc|fnc|sw|nc)$/.test(f));
  assert.ok(files.length > 100, `${files.length} fixtures`);
  const log = sarif(files, ROOT);
  assertValid(log, "rule fixtures");
  assert.equal(log.version, "2.1.0");
  const run = log.runs[0];
  assert.equal(run.columnKind, "unicodeCodePoints");
  assert.ok(run.results.length > 100, `${run.results.length} results`);
  for (const loc of uris(log)) {
    assert.equal(loc.uriBaseId, "%SRCROOT%");
    assert.ok(!path.isAbsolute(loc.uri) && !loc.uri.includes("\\"), loc.uri);
    assert.ok(loc.uri.startsWith("analyzer/tests/rules/"), loc.uri);
  }
  // Every result names a rule the driver lists.
  const ids = new Set(run.tool.driver.rules.map((r) => r.id));
  for (const r of run.results) assert.ok(ids.has(r.ruleId), r.ruleId);
});

test("awkward names, a subprogram's diagnostic and unreadable files stay valid", { skip }, () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-sarif-"));
  try {
    fs.mkdirSync(path.join(dir, "jobs 2026", "Ü#1"), { recursive: true });
    const odd = path.join("jobs 2026", "Ü#1", "part 50%.ngc");
    fs.writeFileSync(path.join(dir, odd), "G21 G90\nG1 X10\nM2\n");
    fs.writeFileSync(path.join(dir, "main.ngc"), "G21 G90 F100\no<sub1> call\nM2\n");
    fs.writeFileSync(path.join(dir, "sub1.ngc"), "o<sub1> sub\nG2 X10 Y0\no<sub1> endsub\nM2\n");
    fs.writeFileSync(path.join(dir, "binary.nc"), Buffer.from([0x7f, 0x45, 0x4c, 0x46, 0, 1, 2, 0]));
    const log = sarif([odd, "main.ngc", "binary.nc", "missing.ngc"], dir, 2);
    assertValid(log, "awkward inputs");
    const all = uris(log).map((l) => l.uri);
    assert.ok(all.includes("jobs%202026/%C3%9C%231/part%2050%25.ngc"), all.join(" "));
    assert.ok(all.includes("binary.nc"), all.join(" "));
    // The call gets the subprogram's fault, with a repository-relative location.
    assert.ok(all.every((u) => !u.startsWith("/") && !u.startsWith("file:")), all.join(" "));
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
});

test("a clean program gives a valid log with no results", { skip }, () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "partscope-sarif-"));
  try {
    fs.writeFileSync(path.join(dir, "ok.ngc"), "G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nG0 Z5\nM2\n");
    const log = sarif(["ok.ngc"], dir);
    assertValid(log, "clean");
    assert.deepEqual(log.runs[0].results, []);
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
