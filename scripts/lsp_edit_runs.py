"""Drives `partscope lsp` over stdio: opens a generated surfacing program of N
lines, then makes 8 two-block edits 2.5 s apart, and prints the server's
interpreter timing lines (PARTSCOPE_LSP_TIMING=1): full run at open, rerun
from a checkpoint after each edit.

Usage: python3 scripts/lsp_edit_runs.py target/release/partscope 100000
"""
import json, subprocess, sys, time, os, threading
binary, lines = sys.argv[1], int(sys.argv[2])
env = dict(os.environ, PARTSCOPE_LSP_TIMING="1")
p = subprocess.Popen([binary, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
def send(obj):
    b = json.dumps(obj).encode()
    p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(b) + b); p.stdin.flush()
def reader():
    while True:
        h = p.stdout.readline()
        if not h: return
        if h.startswith(b"Content-Length"):
            n = int(h.split(b":")[1]); p.stdout.readline(); p.stdout.read(n)
threading.Thread(target=reader, daemon=True).start()
errs = []
threading.Thread(target=lambda: [errs.append(l.decode().strip()) for l in p.stderr], daemon=True).start()
import math
s = ["(generated)", "G21 G90 G17", "T1 M6", "S12000 M3", "G0 X0 Y0 Z5"]
for i in range(5, lines - 1):
    x = (i % 500) * 0.1; y = (i // 500) * 0.1; z = -(math.sin(x*0.3) + math.cos(y*0.2)) * 0.5
    s.append("G1 X%.3f Y%.3f Z%.4f F1200" % (x, y, z))
s.append("M2")
text = "\n".join(s) + "\n"
send({"jsonrpc":"2.0","id":1,"method":"initialize","params":{"processId":None,"rootUri":None,"capabilities":{}}})
time.sleep(0.5)
send({"jsonrpc":"2.0","method":"initialized","params":{}})
uri = "file:///m/big.ngc"
send({"jsonrpc":"2.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":uri,"languageId":"ngc","version":1,"text":text}}})
time.sleep(4)
for k in range(8):
    line = lines // 10 * (k + 1)
    send({"jsonrpc":"2.0","method":"textDocument/didChange","params":{"textDocument":{"uri":uri,"version":2+k},"contentChanges":[{"range":{"start":{"line":line,"character":0},"end":{"line":line,"character":0}},"text":"G0 Z5\nG0 Z0\n"}]}})
    time.sleep(2.5)
send({"jsonrpc":"2.0","id":2,"method":"shutdown","params":None}); time.sleep(0.3)
send({"jsonrpc":"2.0","method":"exit","params":None}); time.sleep(0.3)
for l in errs:
    if "interpreter" in l or "run " in l: print(l)
