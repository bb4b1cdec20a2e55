#!/usr/bin/env python3
"""Measure partscope on the third-party corpus listed in tests/realworld/manifest.tsv.

The programs are never committed: this script reads them out of the bare git
mirrors the `fetch` tool leaves under /work/.mirror/<owner>+<name>/, writes them
into a cache directory outside the repository, runs `partscope check --format
json` on each (once with the dialect the manifest gives and once without
`--dialect`, to see which dialect the sniffer picks) and prints a verdict table
using tests/realworld/verdicts.tsv.

Python 3.11 standard library only.  Programs whose mirror is absent are skipped
(and counted as skipped), so the script runs on a machine without the mirrors.
"""

from __future__ import annotations

import argparse
import csv
import json
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent
DEFAULT_MANIFEST = REPO_ROOT / "tests" / "realworld" / "manifest.tsv"
DEFAULT_VERDICTS = REPO_ROOT / "tests" / "realworld" / "verdicts.tsv"
DEFAULT_MIRRORS = Path("/work/.mirror")
DEFAULT_CACHE = Path("/tmp/partscope-realworld")
DEFAULT_BIN = REPO_ROOT / "target" / "release" / "partscope"

# The partscope dialect each manifest dialect is checked as.  Controls we do not
# model are checked as the nearest modelled one; their findings are classified
# `mismatch` when they come from the control difference.
CHECK_AS = {
    "fanuc": "fanuc",
    "fanuc-lathe": "fanuc",
    "haas-mill": "fanuc",
    "haas-lathe": "fanuc",
    "other": "fanuc",
    "rs274ngc": "rs274ngc",
    "servoworks": "servoworks",
}
DIALECTS = ("servoworks", "rs274ngc", "fanuc")
# Severities that count as "the program is flagged".
FLAGGING = ("error", "warning")
# Sibling files copied next to a program so that its subprogram calls resolve.
# The extensions `partscope check` takes for G code (server/src/cli/workspace.rs
# EXTENSIONS), plus what FANUC and ServoWorks resolvers look for.
SIBLING_SUFFIXES = ("", ".ngc", ".nc", ".fnc", ".txt", ".dat", ".cnc", ".tap", ".gcode", ".eia", ".min", ".mpf", ".sw")
MAX_SIBLINGS = 300
RUN_TIMEOUT_S = 300


@dataclass
class Program:
    id: str
    dialect: str
    repo: str
    commit: str
    path: str
    kind: str
    note: str


def check_dialect(p: "Program") -> str:
    """The partscope dialect a program is checked as: by its manifest dialect,
    unless the note starts with `[check as <dialect>]` (a derivative of a
    modelled control, e.g. PathPilot for LinuxCNC)."""
    if p.note.startswith("[check as "):
        d = p.note[len("[check as "):].split("]", 1)[0].strip()
        if d in DIALECTS:
            return d
    return CHECK_AS[p.dialect]


@dataclass
class Outcome:
    program: Program
    status: str = "ok"  # ok | skipped | failed
    reason: str = ""
    diags: list[dict] = field(default_factory=list)
    detected: str | None = None


def read_tsv(path: Path) -> list[dict[str, str]]:
    if not path.exists():
        return []
    with path.open(newline="", encoding="utf-8") as f:
        rows = csv.DictReader(f, delimiter="\t", quoting=csv.QUOTE_NONE)
        return [dict(r) for r in rows if r and not (r.get("id") or "").startswith("#")]


def read_manifest(path: Path) -> list[Program]:
    out = []
    for r in read_tsv(path):
        if r["dialect"] not in CHECK_AS:
            raise SystemExit(f"{path}: {r['id']}: unknown dialect {r['dialect']!r}")
        out.append(Program(**{k: r[k] for k in Program.__dataclass_fields__}))
    return out


def git_dir(mirrors: Path, repo: str) -> Path | None:
    base = mirrors / repo.replace("/", "+") / "repo"
    for cand in (base / ".git", base):
        if (cand / "objects").is_dir():
            return cand
    return None


def git(gd: Path, *args: str) -> bytes | None:
    res = subprocess.run(["git", "--git-dir", str(gd), *args], capture_output=True)
    return res.stdout if res.returncode == 0 else None


def materialise(p: Program, mirrors: Path, cache: Path) -> tuple[Path | None, str]:
    """Writes the program and its same-directory siblings into the cache."""
    root = cache / p.repo.replace("/", "+") / p.commit[:12]
    target = root / p.path
    if target.exists():
        return target, ""
    gd = git_dir(mirrors, p.repo)
    if gd is None:
        return None, f"mirror of {p.repo} absent"
    data = git(gd, "show", f"{p.commit}:{p.path}")
    if data is None:
        return None, f"{p.commit[:12]}:{p.path} not in the mirror"
    target.parent.mkdir(parents=True, exist_ok=True)
    # Siblings first, so that the program itself is written last and its
    # presence means the whole directory is there.
    folder = str(Path(p.path).parent)
    listing = git(gd, "ls-tree", "-z", f"{p.commit}:{folder}" if folder != "." else p.commit)
    # Entries are "<mode> <type> <sha>\t<name>"; only blobs are files.
    names = [e.split(b"\t", 1)[1].decode("utf-8", "replace")
             for e in (listing or b"").split(b"\0") if b"\t" in e and e.split(b" ")[1] == b"blob"]
    copied = 0
    for name in names:
        if copied >= MAX_SIBLINGS:
            break
        if Path(name).suffix.lower() not in SIBLING_SUFFIXES or name == Path(p.path).name:
            continue
        rel = name if folder == "." else f"{folder}/{name}"
        blob = git(gd, "show", f"{p.commit}:{rel}")
        if blob is None or len(blob) > 4 << 20 or b"\0" in blob[:4096]:
            continue
        (root / rel).write_bytes(blob)
        copied += 1
    target.write_bytes(data)
    return target, ""


def run_check(binary: Path, file: Path, dialect: str | None) -> tuple[list[dict] | None, str | None, str]:
    """Returns (diagnostics, dialect named by the output if any, error text)."""
    cmd = [str(binary), "check", "--format", "json"]
    if dialect:
        cmd += ["--dialect", dialect]
    cmd.append(str(file))
    try:
        res = subprocess.run(cmd, capture_output=True, timeout=RUN_TIMEOUT_S, cwd=file.parent)
    except subprocess.TimeoutExpired:
        return None, None, f"timeout after {RUN_TIMEOUT_S} s"
    try:
        doc = json.loads(res.stdout.decode("utf-8", "replace") or "null")
    except json.JSONDecodeError:
        return None, None, f"exit {res.returncode}, no JSON: {res.stderr.decode('utf-8', 'replace')[:200]}"
    named = None
    if isinstance(doc, dict):
        # A future output format may wrap the list and name the chosen dialect.
        named = doc.get("dialect") or (doc.get("files") or [{}])[0].get("dialect")
        doc = doc.get("diagnostics", [])
    if not isinstance(doc, list):
        return None, None, "unexpected JSON shape"
    return doc, named, ""


def dry_run(binary: Path, file: Path, dialect: str | None) -> tuple[str | None, str | None]:
    """The whole `run --format json` document as a canonical string, and the
    dialect it names if any: equal strings mean the same analysis."""
    cmd = [str(binary), "run", "--format", "json"]
    if dialect:
        cmd += ["--dialect", dialect]
    cmd.append(str(file))
    try:
        res = subprocess.run(cmd, capture_output=True, timeout=RUN_TIMEOUT_S, cwd=file.parent)
    except subprocess.TimeoutExpired:
        return None, None
    try:
        doc = json.loads(res.stdout.decode("utf-8", "replace") or "null")
    except json.JSONDecodeError:
        return None, None
    named = doc.pop("dialect", None) if isinstance(doc, dict) else None
    if isinstance(doc, dict):
        doc.pop("dialect_reason", None)
    return json.dumps(doc, sort_keys=True), named


def measure(p: Program, binary: Path, mirrors: Path, cache: Path) -> Outcome:
    out = Outcome(p)
    file, why = materialise(p, mirrors, cache)
    if file is None:
        out.status, out.reason = "skipped", why
        return out
    check_as = check_dialect(p)
    diags, named, err = run_check(binary, file, check_as)
    if diags is None:
        out.status, out.reason = "failed", err
        return out
    out.diags = diags
    _, sniffed_named, _ = run_check(binary, file, None)
    if sniffed_named:
        out.detected = str(sniffed_named)
        return out
    # `run --format json` names the dialect it chose (`dialect`); older binaries
    # do not, and then the dry run without --dialect is identical (findings,
    # cycle time, distances) to the run of one forced dialect.
    sniffed, sniffed_named = dry_run(binary, file, None)
    if sniffed_named:
        out.detected = str(sniffed_named)
        return out
    if sniffed is None:
        out.detected = "run failed"
        return out
    for d in (check_as, *[d for d in DIALECTS if d != check_as]):
        forced, _ = dry_run(binary, file, d)
        if forced == sniffed:
            out.detected = d
            break
    else:
        out.detected = "?"
    return out


# rs274 messages that depend on the machine or on the caller, not on the
# program: a user M code file, the tool table, a caller's named parameters or
# arguments, a subroutine found only through the machine's search path.
RS274_CONTEXT = ("Unknown m code used: M1", "Requested tool", "Named parameter", "seeking o-word",
                 "Probe was not tripped", "must be > 0", "Failed to find sub")
# Failures of a subroutine run without its caller's arguments and modes.
RS274_SUB_CONTEXT = ("zero feed rate", "divide by zero", "zero spindle speed")


def rs274_check(o: Outcome, script: Path, cache: Path) -> tuple[str, str, list[int]] | None:
    """Runs LinuxCNC's interpreter on an RS274/NGC program (a subroutine file
    through `o<name> call`) and returns (kind, message, lines of the offending
    text) when it rejects it; kind is `program`, `context` or `callee` (the offending line is in a file it calls)."""
    p = o.program
    file = cache / p.repo.replace("/", "+") / p.commit[:12] / p.path
    text = file.read_text(encoding="utf-8", errors="replace")
    work = Path(tempfile.mkdtemp(prefix="realworld-rs274-"))
    try:
        ini = work / "sub.ini"
        ini.write_text(f"[RS274NGC]\nSUBROUTINE_PATH = {file.parent}:{file.parent.parent}\n", encoding="utf-8")
        target = file
        head = re.search(r"^\s*o<\s*([^>]+?)\s*>\s*sub\b", text, re.I | re.M)
        in_sub = bool(head and head.group(1).lower() == file.stem.lower())
        if in_sub:
            target = work / "call.ngc"
            target.write_text(f"o<{file.stem}> call\nM2\n", encoding="utf-8")
        res = subprocess.run([str(script), "-i", str(ini), str(target)], capture_output=True,
                             text=True, errors="replace", timeout=RUN_TIMEOUT_S)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if res.returncode == 0:
        return None
    err = [ln for ln in res.stderr.splitlines() if ln.strip()]
    msg = err[0] if err else f"exit {res.returncode}"
    src = err[1].strip() if len(err) > 1 else ""
    lines = [i for i, ln in enumerate(text.splitlines(), 1) if src and ln.strip() == src]
    context = any(k in msg for k in RS274_CONTEXT) or (in_sub and any(k in msg for k in RS274_SUB_CONTEXT))
    if not context and in_sub and src and not lines:
        # The offending line is in a file the subroutine calls: that file's fault,
        # found (or missed) where the corpus checks it.
        return "callee", msg, lines
    return ("context" if context else "program"), msg, lines


def flagged(diags: list[dict]) -> list[dict]:
    return [d for d in diags if d.get("severity") in FLAGGING]


def verdict_of(verdicts: dict, pid: str, d: dict) -> str:
    """The verdict for one finding: by id, code and line, or by id and code with
    line `*` (one verdict for every line of a repeated finding)."""
    code, line = str(d.get("code")), str(d.get("line"))
    v = verdicts.get((pid, code, line)) or verdicts.get((pid, code, "*"))
    return v["verdict"] if v else "unclassified"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", type=Path, default=DEFAULT_BIN, help="partscope binary (default: %(default)s)")
    ap.add_argument("--cache", type=Path, default=DEFAULT_CACHE, help="where programs are written (default: %(default)s)")
    ap.add_argument("--mirrors", type=Path, default=DEFAULT_MIRRORS, help="fetch mirrors (default: %(default)s)")
    ap.add_argument("--manifest", type=Path, default=DEFAULT_MANIFEST)
    ap.add_argument("--verdicts", type=Path, default=DEFAULT_VERDICTS)
    ap.add_argument("--only", nargs="*", default=[], help="corpus ids to run (default: all)")
    ap.add_argument("--findings", type=Path, help="write every error/warning as TSV (id code line severity message verdict)")
    ap.add_argument("--details", action="store_true", help="list programs with false or unclassified findings")
    ap.add_argument("--rs274", type=Path, nargs="?", const=Path("/work/shared/oracle/run_rs274.sh"),
                    help="also run LinuxCNC's rs274 (through run_rs274.sh) on the RS274/NGC programs and check "
                         "that partscope reports an error on the line of every rejection")
    args = ap.parse_args()

    binary = args.bin if args.bin.is_absolute() else Path.cwd() / args.bin
    if not binary.exists():
        print(f"realworld: no binary at {binary} (build with `cargo build --release` or pass --bin)", file=sys.stderr)
        return 2
    programs = read_manifest(args.manifest)
    if args.only:
        wanted = set(args.only)
        programs = [p for p in programs if p.id in wanted]
    verdicts: dict[tuple[str, str, str], dict[str, str]] = {}
    for v in read_tsv(args.verdicts):
        verdicts[(v["id"], v["code"], v["line"])] = v
    args.cache.mkdir(parents=True, exist_ok=True)

    outcomes = []
    for i, p in enumerate(programs, 1):
        if sys.stderr.isatty():
            print(f"\r[{i}/{len(programs)}] {p.id} {p.path[:60]:<60}", end="", file=sys.stderr, flush=True)
        outcomes.append(measure(p, binary, args.mirrors, args.cache))
    print(file=sys.stderr)

    rows = []
    if args.findings:
        args.findings.parent.mkdir(parents=True, exist_ok=True)
    for o in outcomes:
        for d in flagged(o.diags):
            v = verdict_of(verdicts, o.program.id, d)
            rows.append((o.program.id, str(d.get("code")), str(d.get("line")), d.get("severity"), v, d.get("message", "")))
    if args.findings:
        with args.findings.open("w", encoding="utf-8") as f:
            f.write("id\tcode\tline\tseverity\tverdict\tmessage\n")
            for r in rows:
                f.write("\t".join(str(x).replace("\t", " ").replace("\n", " ") for x in r) + "\n")

    order = list(CHECK_AS)
    table: dict[str, dict[str, int]] = {}
    wrong_dialect: list[Outcome] = []
    for o in outcomes:
        t = table.setdefault(o.program.dialect, dict.fromkeys(
            ("programs", "skipped", "failed", "flagged", "false", "true", "mismatch", "unclassified", "misdetected"), 0))
        t["programs"] += 1
        if o.status != "ok":
            t[o.status] += 1
            continue
        f = flagged(o.diags)
        if f:
            t["flagged"] += 1
        kinds = {verdict_of(verdicts, o.program.id, d) for d in f}
        for k in ("false", "true", "mismatch", "unclassified"):
            if k in kinds:
                t[k] += 1
        if o.detected != check_dialect(o.program):
            t["misdetected"] += 1
            wrong_dialect.append(o)

    head = ("dialect", "programs", "skipped", "failed", "≥1 err/warn", "≥1 false", "≥1 true", "≥1 mismatch", "≥1 unclassified", "false %", "sniffed wrong")
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    total = dict.fromkeys(("programs", "skipped", "failed", "flagged", "false", "true", "mismatch", "unclassified", "misdetected"), 0)
    for d in sorted(table, key=order.index):
        t = table[d]
        for k in total:
            total[k] += t[k]
        run = t["programs"] - t["skipped"] - t["failed"]
        pct = f"{100.0 * t['false'] / run:.1f}" if run else "-"
        print(f"| {d} | {t['programs']} | {t['skipped']} | {t['failed']} | {t['flagged']} | {t['false']} | {t['true']} "
              f"| {t['mismatch']} | {t['unclassified']} | {pct} | {t['misdetected']} |")
    run = total["programs"] - total["skipped"] - total["failed"]
    pct = f"{100.0 * total['false'] / run:.1f}" if run else "-"
    print(f"| all | {total['programs']} | {total['skipped']} | {total['failed']} | {total['flagged']} | {total['false']} "
          f"| {total['true']} | {total['mismatch']} | {total['unclassified']} | {pct} | {total['misdetected']} |")
    print(f"\nfindings (error/warning): {len(rows)}; by verdict: " + ", ".join(
        f"{k} {sum(1 for r in rows if r[4] == k)}" for k in ("true", "false", "mismatch", "unclassified")))
    skipped = [o for o in outcomes if o.status == "skipped"]
    if skipped:
        print(f"skipped {len(skipped)} program(s): " + "; ".join(sorted({o.reason for o in skipped})))
    for o in outcomes:
        if o.status == "failed":
            print(f"failed: {o.program.id} {o.program.path}: {o.reason}")
    if wrong_dialect:
        print("\nsniffed as the wrong dialect (without --dialect):")
        for o in wrong_dialect:
            print(f"  {o.program.id} ({o.program.dialect}, checked as {check_dialect(o.program)}) -> {o.detected}: {o.program.path}")
    if args.rs274:
        if not args.rs274.exists():
            print(f"\nrs274 wrapper {args.rs274} not found: skipping the rs274 comparison")
        else:
            print("\nrs274 rejections (RS274/NGC programs; `context` = depends on the machine or the caller; `callee` = in a called file):")
            found = missed = 0
            for o in outcomes:
                if o.status != "ok" or check_dialect(o.program) != "rs274ngc":
                    continue
                got = rs274_check(o, args.rs274, args.cache)
                if got is None:
                    continue
                kind, msg, lines = got
                ours = sorted({d.get("line") for d in o.diags if d.get("severity") == "error"})
                hit = [ln for ln in lines if ln in ours]
                if kind == "program":
                    found += bool(hit)
                    missed += not hit
                mark = "found" if hit else ("MISSED" if kind == "program" else "-")
                print(f"  {o.program.id} {kind:<7} {mark:<6} line {lines[:3]} {msg[:90]}")
            print(f"rs274 program rejections found by partscope on their line: {found} of {found + missed}")
    if args.details:
        print("\nprograms with false or unclassified findings:")
        for o in outcomes:
            bad = [r for r in rows if r[0] == o.program.id and r[4] in ("false", "unclassified")]
            if bad:
                codes = sorted({f"{r[1]}:{r[4]}" for r in bad})
                print(f"  {o.program.id} {o.program.path}: {', '.join(codes)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
