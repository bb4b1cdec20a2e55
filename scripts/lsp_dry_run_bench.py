#!/usr/bin/env python3
"""Measures the editor dry run over stdio, as a client sees it.

For each FILE: starts `BINARY lsp`, initializes with the file's folder as the
workspace, sends didOpen with the file's text and, right after it, a
`partscope/dryRun` request. Prints the time from the start of didOpen and from
the request to its answer, the answer's size in bytes (the JSON-RPC body), all
bytes the server sent until then, what the answer says about decimation, and
the server's peak RSS (VmHWM from /proc/PID/status, read after the answer)
and its CPU time until then (user + system, all threads).

Usage:
    python3 scripts/lsp_dry_run_bench.py BINARY FILE... [--tolerance MM] [--init JSON] [--json] [--stderr]

Generate inputs with scripts/gen_programs.py, e.g.
    python3 scripts/gen_programs.py surfacing --dialect rs274ngc --lines 1000000 > surf1m.ngc
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import threading
import time


class Server:
    def __init__(self, binary, env=None):
        self.p = subprocess.Popen(
            [binary, "lsp"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=env,
        )
        self.bytes_in = 0
        self.answers = {}
        self.cond = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()
        self.stderr = []
        threading.Thread(
            target=lambda: [self.stderr.append(l.decode(errors="replace").rstrip()) for l in self.p.stderr],
            daemon=True,
        ).start()

    def send(self, obj):
        body = json.dumps(obj).encode()
        self.p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.p.stdin.flush()

    def _read(self):
        out = self.p.stdout
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    return
                if line in (b"\r\n", b"\n"):
                    break
                if line.lower().startswith(b"content-length:"):
                    length = int(line.split(b":")[1])
            if length is None:
                continue
            body = out.read(length)
            msg = json.loads(body)
            with self.cond:
                self.bytes_in += length
                if "id" in msg and "method" not in msg:
                    self.answers[msg["id"]] = (time.monotonic(), length, msg, self.bytes_in)
                    self.cond.notify_all()
                elif "id" in msg:
                    # A request from the server (configuration, registration): answer it empty.
                    self.send({"jsonrpc": "2.0", "id": msg["id"], "result": None})

    def wait(self, id, timeout=600):
        with self.cond:
            self.cond.wait_for(lambda: id in self.answers, timeout)
            return self.answers.get(id)

    def vm_hwm_kb(self):
        with open(f"/proc/{self.p.pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
        return None

    def cpu_s(self):
        """User + system CPU seconds of the server so far (all threads)."""
        with open(f"/proc/{self.p.pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")

    def close(self):
        try:
            self.send({"jsonrpc": "2.0", "id": 999, "method": "shutdown", "params": None})
            self.wait(999, 10)
            self.send({"jsonrpc": "2.0", "method": "exit", "params": None})
            self.p.wait(10)
        except Exception:
            self.p.kill()


def measure(binary, path, tolerance=None, show_stderr=False, init=None):
    path = os.path.abspath(path)
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    uri = "file://" + path
    root = "file://" + os.path.dirname(path)
    s = Server(binary)
    s.send({"jsonrpc": "2.0", "id": 1, "method": "initialize",
            "params": {"processId": None, "rootUri": root, "capabilities": {},
                       "initializationOptions": init or {}}})
    s.wait(1)
    s.send({"jsonrpc": "2.0", "method": "initialized", "params": {}})
    t_open = time.monotonic()
    s.send({"jsonrpc": "2.0", "method": "textDocument/didOpen",
            "params": {"textDocument": {"uri": uri, "languageId": "gcode", "version": 1, "text": text}}})
    params = {"textDocument": {"uri": uri}}
    if tolerance is not None:
        params["tolerance"] = tolerance
    t_req = time.monotonic()
    s.send({"jsonrpc": "2.0", "id": 2, "method": "partscope/dryRun", "params": params})
    got = s.wait(2)
    if got is None:
        s.p.kill()
        return {"file": path, "error": "no answer within 600 s"}
    t_answer, length, msg, bytes_in = got
    hwm = s.vm_hwm_kb()
    cpu = s.cpu_s()
    s.close()
    if show_stderr:
        for line in s.stderr:
            print("  server:", line, file=sys.stderr)
    row = {
        "file": os.path.basename(path),
        "file_mb": round(len(text.encode()) / 1e6, 1),
        "lines": text.count("\n"),
        "open_to_answer_s": round(t_answer - t_open, 3),
        "request_to_answer_s": round(t_answer - t_req, 3),
        "answer_bytes": length,
        "server_bytes_until_answer": bytes_in,
        "peak_rss_mb": round(hwm / 1024, 1) if hwm else None,
        "server_cpu_s": round(cpu, 2),
        # Equal hashes: two binaries gave the same answer (key order as sent).
        "answer_sha256": hashlib.sha256(json.dumps(msg.get("result")).encode()).hexdigest()[:16],
    }
    if "error" in msg:
        row["error"] = msg["error"].get("message")
        return row
    r = msg["result"]
    segs = r["toolpath"]["segments"]
    row.update({
        "segments": len(segs),
        "points": sum(len(g["points"]) for g in segs),
        "cycle_time_s": r.get("cycle_time_s"),
        "complete": r.get("complete"),
        "decimation": r.get("decimation"),
    })
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binary")
    ap.add_argument("files", nargs="+")
    ap.add_argument("--tolerance", type=float, default=None, help="mm; default: the server's")
    ap.add_argument("--json", action="store_true", help="one JSON object per file")
    ap.add_argument("--init", type=json.loads, default=None,
                    help='initializationOptions, e.g. \'{"maxToolpathPoints": 50000}\'')
    ap.add_argument("--stderr", action="store_true", help="print the server's stderr (set PARTSCOPE_LSP_TIMING=1 for its timings)")
    a = ap.parse_args()
    with open("/proc/loadavg") as f:
        print("load average:", " ".join(f.read().split()[:3]), file=sys.stderr)
    for path in a.files:
        row = measure(a.binary, path, a.tolerance, a.stderr, a.init)
        if a.json:
            print(json.dumps(row))
            continue
        print(f"{row['file']}: {row.get('lines')} lines, {row.get('file_mb')} MB")
        for k, v in row.items():
            if k not in ("file", "lines", "file_mb"):
                print(f"  {k}: {v}")


if __name__ == "__main__":
    main()
