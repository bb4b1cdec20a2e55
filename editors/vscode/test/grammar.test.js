// Tokenises dialect samples with the real TextMate engine VS Code uses (vscode-textmate +
// oniguruma) and checks the scope of each interesting token.
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const fs = require("node:fs");
const path = require("node:path");
const vsctm = require("vscode-textmate");
const oniguruma = require("vscode-oniguruma");

const GRAMMAR = path.join(__dirname, "..", "syntaxes", "gcode.tmLanguage.json");

async function loadGrammar() {
  const wasm = fs.readFileSync(require.resolve("vscode-oniguruma/release/onig.wasm"));
  await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
  const registry = new vsctm.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (sources) => new oniguruma.OnigScanner(sources),
      createOnigString: (s) => new oniguruma.OnigString(s),
    }),
    loadGrammar: async (scopeName) =>
      scopeName === "source.gcode" ? vsctm.parseRawGrammar(fs.readFileSync(GRAMMAR, "utf8"), GRAMMAR) : null,
  });
  return registry.loadGrammar("source.gcode");
}

// Returns [text, innermost scope] for every token of every line.
function tokenize(grammar, text) {
  let state = vsctm.INITIAL;
  const out = [];
  for (const line of text.split("\n")) {
    const r = grammar.tokenizeLine(line, state);
    for (const t of r.tokens) out.push([line.slice(t.startIndex, t.endIndex), t.scopes[t.scopes.length - 1]]);
    state = r.ruleStack;
  }
  return out;
}

function scopeOf(tokens, text) {
  const hit = tokens.find(([t]) => t.trim() === text);
  assert.ok(hit, `token ${JSON.stringify(text)} not found in ${JSON.stringify(tokens)}`);
  return hit[1];
}

test("grammar scopes", async (t) => {
  const grammar = await loadGrammar();

  await t.test("words, comments and numbers", () => {
    const tk = tokenize(grammar, "N10 G01 X-1.5 Y.25 F600 (rough pass) ; trailing note");
    assert.equal(scopeOf(tk, "N10"), "constant.other.sequence-number.gcode");
    assert.equal(scopeOf(tk, "G01"), "keyword.control.g.gcode");
    assert.equal(scopeOf(tk, "X"), "variable.parameter.axis.gcode");
    assert.equal(scopeOf(tk, "-1.5"), "constant.numeric.gcode");
    assert.equal(scopeOf(tk, ".25"), "constant.numeric.gcode");
    assert.equal(scopeOf(tk, "F"), "support.constant.feed.gcode");
    assert.equal(scopeOf(tk, "rough pass"), "comment.block.paren.gcode");
    assert.equal(scopeOf(tk, "; trailing note"), "comment.line.semicolon.gcode");
  });

  await t.test("M codes, tools and program end", () => {
    const tk = tokenize(grammar, "T2 M06 H2\nM30");
    assert.equal(scopeOf(tk, "T2"), "entity.name.type.tool.gcode");
    assert.equal(scopeOf(tk, "M06"), "keyword.other.m.gcode");
    assert.equal(scopeOf(tk, "H"), "entity.name.type.tool-offset.gcode");
    assert.equal(scopeOf(tk, "M30"), "keyword.control.program-end.gcode");
  });

  await t.test("RS274/NGC o-words, named parameters and expressions", () => {
    const tk = tokenize(grammar, "o100 sub\n#<depth> = [#1 * SIN[30] + 2]\no100 endsub\n(MSG, hello)");
    assert.equal(scopeOf(tk, "sub"), "keyword.control.oword.rs274ngc.gcode");
    assert.equal(scopeOf(tk, "endsub"), "keyword.control.oword.rs274ngc.gcode");
    assert.equal(scopeOf(tk, "100"), "entity.name.function.oword.gcode");
    assert.equal(scopeOf(tk, "#<depth>"), "variable.other.named.rs274ngc.gcode");
    assert.equal(scopeOf(tk, "SIN"), "support.function.math.gcode");
    assert.equal(scopeOf(tk, "#1"), "variable.other.numbered.gcode");
    assert.equal(scopeOf(tk, "MSG"), "keyword.other.message.rs274ngc.gcode");
  });

  await t.test("FANUC Custom Macro B", () => {
    const tk = tokenize(grammar, "WHILE[#1LE10]DO1;\nIF[#2EQ0]GOTO100;\nEND1;\nO9010");
    assert.equal(scopeOf(tk, "WHILE"), "keyword.control.loop.fanuc.gcode");
    assert.equal(scopeOf(tk, "LE"), "keyword.operator.word.gcode");
    assert.equal(scopeOf(tk, "DO"), "keyword.control.loop.fanuc.gcode");
    assert.equal(scopeOf(tk, "IF"), "keyword.control.conditional.fanuc.gcode");
    assert.equal(scopeOf(tk, "EQ"), "keyword.operator.word.gcode");
    assert.equal(scopeOf(tk, "GOTO"), "keyword.control.goto.fanuc.gcode");
    assert.equal(scopeOf(tk, "END"), "keyword.control.loop.fanuc.gcode");
    assert.equal(scopeOf(tk, ";"), "punctuation.terminator.end-of-block.fanuc.gcode");
    assert.equal(scopeOf(tk, "9010"), "entity.name.function.program.gcode");
  });

  await t.test("ServoWorks line comment, subprogram names and block skip", () => {
    const tk = tokenize(grammar, "%G01 X10 (whole line skipped)\nOMoveXY\n/N20 G00 X0");
    assert.equal(scopeOf(tk, "%G01 X10 (whole line skipped)"), "comment.line.percentage.servoworks.gcode");
    assert.equal(scopeOf(tk, "MoveXY"), "entity.name.function.program.gcode");
    assert.equal(scopeOf(tk, "/"), "keyword.control.block-delete.gcode");
    const pct = tokenize(grammar, "%");
    assert.equal(scopeOf(pct, "%"), "punctuation.definition.program.gcode");
  });

  await t.test("partscope directive in the first-line comment", () => {
    const tk = tokenize(grammar, "(partscope: dialect=fanuc)");
    assert.equal(scopeOf(tk, "partscope"), "keyword.other.directive.partscope.gcode");
  });
});
