#!/usr/bin/env python3
"""Records runtime rules in the spec coverage ledger.

Every spec id that a runtime rule lists in `implements` and that the ledger still
marks `runtime = "..."` becomes `rule = "CODE"` (the first runtime rule that claims
it). Usage: scripts/update_ledger.py [path/to/partscope]
"""
import json, re, subprocess, sys
from pathlib import Path

root = Path(__file__).resolve().parent.parent
exe = sys.argv[1] if len(sys.argv) > 1 else str(root / "target/debug/partscope")
rules = json.loads(subprocess.run([exe, "rule", "--all", "--json"], check=True, capture_output=True, text=True).stdout)
claims = {}
for r in rules:
    if r["origin"] != "runtime":
        continue
    for i in r["implements"]:
        claims.setdefault(i, []).append(r["code"])

path = root / "analyzer/spec-coverage.toml"
text = path.read_text()
changed = 0

def repl(m):
    global changed
    ident, body = m.group(1), m.group(2)
    if body.startswith("runtime = ") and ident in claims:
        changed += 1
        return f"[{ident}]\nrule = \"{sorted(claims[ident])[0]}\"\n"
    return m.group(0)

text = re.sub(r'^\[(\w+)\]\n((?:(?!\[).*\n)*)', repl, text, flags=re.M)
path.write_text(text)
print(f"{changed} ids now recorded against runtime rules")
