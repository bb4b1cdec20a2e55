#!/usr/bin/env python3
"""Parse G-code programs with the Partscope tree-sitter grammar and report every
file whose tree holds an ERROR or MISSING node.

    parse-check.py [--expect FILE] [PATH ...]
    parse-check.py --manifest tests/realworld/manifest.tsv --cache /tmp/partscope-realworld

PATHs are files or folders (folders are searched for the extensions `partscope
check` reads). With --manifest, the third-party corpus programs that
scripts/realworld.py wrote into --cache are parsed too, counted per dialect of
the manifest (programs not in the cache are counted as skipped).

With --partscope BIN, each file with an error node is checked with `BIN check`
(in the manifest's dialect, else the one Partscope picks): the report says
whether Partscope's own parser finds a syntax error (an L code) on the line of
the first error node, i.e. whether the program is wrong or the grammar is.

Exit status: 0 when no file has an error node, or, with --expect, when exactly
the files listed there (paths relative to the repository, `#` comments) have
one; 1 otherwise; 2 on a usage error. Needs the `tree-sitter` CLI on PATH.
Python 3.11 standard library only.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path

GRAMMAR = Path(__file__).resolve().parent.parent
REPO = GRAMMAR.parent.parent
EXTENSIONS = {".nc", ".ngc", ".tap", ".cnc", ".gcode", ".eia", ".dat", ".min", ".mpf", ".fnc", ".sw"}


def programs_under(path: Path) -> list[Path]:
    if path.is_file():
        return [path]
    return sorted(p for p in path.rglob("*") if p.is_file() and p.suffix.lower() in EXTENSIONS)


# The Partscope dialect each manifest group is checked in (as scripts/realworld.py does).
CHECKED_AS = {"fanuc": "fanuc", "rs274ngc": "rs274ngc", "haas-mill": "fanuc", "haas-lathe": "fanuc", "other": "fanuc"}


def corpus(manifest: Path, cache: Path) -> tuple[list[tuple[str, str, Path]], dict[str, int]]:
    """The manifest's programs found in the cache, with their group and dialect."""
    found: list[tuple[str, str, Path]] = []
    skipped: dict[str, int] = defaultdict(int)
    with manifest.open(newline="") as f:
        for row in csv.DictReader(f, delimiter="\t"):
            file = cache / row["repo"].replace("/", "+") / row["commit"][:12] / row["path"]
            dialect = CHECKED_AS[row["dialect"]]
            if row["note"].startswith("[check as "):
                dialect = row["note"][len("[check as ") :].split("]", 1)[0].strip()
            if file.is_file():
                found.append((row["dialect"], dialect, file))
            else:
                skipped[row["dialect"]] += 1
    return found, skipped


def syntax_error_lines(binary: Path, file: Path, dialect: str | None) -> set[int]:
    """1-based lines where `partscope check` reports a parser diagnostic (L001-L015)."""
    cmd = [str(binary), "check", "--format", "json", "--fail-level", "error", "--ignore", "P010"]
    if dialect:
        cmd += ["--dialect", dialect]
    out = subprocess.run(cmd + [str(file)], capture_output=True, text=True, errors="replace")
    if out.returncode == 2:
        sys.exit(f"{binary} check failed on {file}:\n{out.stderr}")
    return {
        line
        for d in json.loads(out.stdout or "[]")
        if d["code"][0] == "L" and d["code"][1:].isdigit() and int(d["code"][1:]) <= 15
        for line in range(d["line"], d["end_line"] + 1)
    }


def first_error_line(place: str) -> int | None:
    """The 1-based line of `(ERROR [row, col] - …)` or `(MISSING x [row, col] - …)`."""
    try:
        return int(place.split("[", 1)[1].split(",", 1)[0]) + 1
    except (IndexError, ValueError):
        return None


def failures(files: list[Path]) -> dict[Path, str]:
    """Files whose tree has an ERROR or MISSING node, with the first one's place."""
    if not files:
        return {}
    with tempfile.NamedTemporaryFile("w", suffix=".txt", delete=False) as listing:
        listing.write("".join(f"{f}\n" for f in files))
    try:
        out = subprocess.run(
            ["tree-sitter", "parse", "--grammar-path", str(GRAMMAR), "--quiet", "--paths", listing.name],
            capture_output=True,
            text=True,
            errors="replace",
        )
    finally:
        os.unlink(listing.name)
    bad: dict[Path, str] = {}
    for line in out.stdout.splitlines():
        # `path<TAB>Parse: … ms<TAB>… bytes/ms<TAB>(ERROR [row, col] - [row, col])`
        fields = line.split("\t")
        if len(fields) >= 2 and fields[1].lstrip().startswith("Parse:"):
            bad[Path(fields[0].rstrip())] = fields[-1].strip()
    if out.returncode not in (0, 1) or (out.returncode == 1 and not bad):
        sys.exit(f"tree-sitter parse failed (exit {out.returncode}):\n{out.stderr}")
    return bad


def shown(p: Path) -> str:
    try:
        return str(p.resolve().relative_to(REPO))
    except ValueError:
        return str(p)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="*", type=Path)
    ap.add_argument("--manifest", type=Path)
    ap.add_argument("--cache", type=Path, default=Path("/tmp/partscope-realworld"))
    ap.add_argument("--expect", type=Path, help="files expected to have error nodes")
    ap.add_argument("--partscope", type=Path, help="partscope binary to cross-check files with error nodes")
    args = ap.parse_args()
    if not args.paths and not args.manifest:
        ap.error("give PATHs or --manifest")

    groups: dict[str, list[Path]] = defaultdict(list)
    for path in args.paths:
        if not path.exists():
            ap.error(f"{path}: no such file or folder")
        groups["files"].extend(programs_under(path))
    skipped: dict[str, int] = {}
    dialect_of: dict[Path, str] = {}
    if args.manifest:
        found, skipped = corpus(args.manifest, args.cache)
        for group, dialect, file in found:
            groups[f"corpus {group}"].append(file)
            dialect_of[file] = dialect

    everything = [f for fs in groups.values() for f in fs]
    bad = failures(everything)
    failing = {shown(f) for f in bad}
    agree = 0
    for f in sorted(bad, key=shown):
        note = ""
        if args.partscope:
            line = first_error_line(bad[f])
            if line is not None and line in syntax_error_lines(args.partscope, f, dialect_of.get(f)):
                agree += 1
                note = "  [partscope: syntax error on this line too]"
            else:
                note = "  [partscope: no syntax error on this line]"
        print(f"{shown(f)}: {bad[f]}{note}")
    total_bad = 0
    for name, files in sorted(groups.items()):
        n = sum(1 for f in files if f in bad)
        total_bad += n
        extra = f", {skipped[name.removeprefix('corpus ')]} skipped" if skipped.get(name.removeprefix("corpus ")) else ""
        print(f"{name}: {len(files)} parsed, {n} with ERROR or MISSING nodes{extra}")
    print(f"parse-check: {len(everything)} files, {total_bad} with ERROR or MISSING nodes")
    if args.partscope:
        print(f"of those, {agree} where partscope reports a syntax error on the same line")

    if args.expect is None:
        return 1 if bad else 0
    expected = set()
    for line in args.expect.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            expected.add(line)
    unexpected = sorted(failing - expected)
    mended = sorted(expected - failing)
    for f in unexpected:
        print(f"unexpected error nodes: {f}")
    for f in mended:
        print(f"listed in {args.expect.name} but parses without error nodes: {f}")
    return 1 if unexpected or mended else 0


if __name__ == "__main__":
    sys.exit(main())
