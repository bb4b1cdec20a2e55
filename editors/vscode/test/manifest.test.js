// Consistency of package.json with the code and files it points at.
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const fs = require("node:fs");
const path = require("node:path");

const ROOT = path.join(__dirname, "..");
const pkg = require("../package.json");
const source = fs.readFileSync(path.join(ROOT, "src", "extension.ts"), "utf8");

test("every contributed command is registered, and none collides with the server's", () => {
  const contributed = pkg.contributes.commands.map((c) => c.command).sort();
  const registered = [...source.matchAll(/registerCommand\("([^"]+)"/g)].map((m) => m[1]).sort();
  assert.deepEqual(contributed, registered);
  // vscode-languageclient registers the server's executeCommand ids itself.
  assert.ok(!contributed.includes("partscope.dryRun"));
});

test("the G-code language covers the issue's file extensions and has its grammar", () => {
  const lang = pkg.contributes.languages.find((l) => l.id === "gcode");
  assert.deepEqual(lang.extensions, [
    ".nc", ".ngc", ".tap", ".cnc", ".gcode", ".eia", ".dat", ".min", ".mpf", ".fnc", ".sw",
  ]);
  const grammar = pkg.contributes.grammars.find((g) => g.language === "gcode");
  assert.ok(fs.existsSync(path.join(ROOT, grammar.path)));
  assert.ok(fs.existsSync(path.join(ROOT, lang.configuration)));
});

test("settings match the server's initializationOptions", () => {
  const props = Object.keys(pkg.contributes.configuration.properties).sort();
  assert.deepEqual(props, [
    "partscope.blockTimes",
    "partscope.dialect",
    "partscope.ignore",
    "partscope.machine",
    "partscope.maxFileSize",
    "partscope.maxRunFileSize",
    "partscope.maxToolpathPoints",
    "partscope.select",
    "partscope.server.path",
    "partscope.trace.server",
  ]);
  assert.deepEqual(pkg.contributes.configuration.properties["partscope.dialect"].enum, [null, "servoworks", "rs274ngc", "fanuc"]);
});

test("Toggle Line Comment writes ( ), never `;`, which ends the block in FANUC and ServoWorks", () => {
  // Without a line-comment token VS Code's Ctrl+/ wraps the line in the block comment;
  // ( ) is a comment in every dialect, while a `;` in front of a FANUC line is executed.
  for (const lang of pkg.contributes.languages) {
    const config = JSON.parse(fs.readFileSync(path.join(ROOT, lang.configuration), "utf8"));
    assert.equal(config.comments.lineComment, undefined, lang.id);
    assert.deepEqual(config.comments.blockComment, ["(", ")"], lang.id);
  }
});
