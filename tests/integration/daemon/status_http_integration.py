#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemud's status page against hostile and slow HTTP clients
(docs/status.md §Tests): while junk, huge headers, a slow sender, a stream
that is never read and more connections than the limit hit the server, the
epoch loop keeps its rate and /api/status keeps answering. Also: loopback by
default, `--status-port 0` and `[status] port = 0` turn the page off, a taken
port moves it, the [status] keys reach the daemon.

Usage: status_http_integration.py --gnssemud PATH CASE   (CASE: abuse, ports)
Every socket is on 127.0.0.1; each case stops by itself within 60 s."""
import argparse
import json
import os
import random
import re
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port  # noqa: E402


class Rig(RigBase):
    def __init__(self, gnssemud):
        super().__init__("gnssemu-status-http-")
        self.gnssemud = gnssemud
        self.daemon = None

    def start(self, *extra):
        out = open(os.path.join(self.tmp, "gnssemud.out"), "w")
        err = open(os.path.join(self.tmp, "gnssemud.log"), "w")
        self.daemon = self.spawn([self.gnssemud, "--pty", os.path.join(self.tmp, "gps0"), "--truth-port", "0", *extra],
                                 stdout=out, stderr=err)
        deadline = time.time() + 20
        while time.time() < deadline:
            text = open(os.path.join(self.tmp, "gnssemud.out")).read()
            if "truth input udp" in text:
                m = re.search(r"status page http://([\d.]+):(\d+)/", text)
                return (m.group(1), int(m.group(2))) if m else None
            if self.daemon.poll() is not None:
                raise AssertionError(f"gnssemud exited with {self.daemon.returncode}")
            time.sleep(0.05)
        raise AssertionError("gnssemud did not start")

    def config(self, status_toml):
        """A config file with the given [status] table (the rest minimal)."""
        nav = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "nav", "brdc0010.22n")
        path = os.path.join(self.tmp, "status.toml")
        with open(path, "w") as f:
            f.write(f"""[origin]
lat_deg = 48.8738
lon_deg = 2.2950
height_m = 100.0
[nav]
file = "{os.path.abspath(nav)}"
[status]
{status_toml}
""")
        return path

    def log(self):
        return open(os.path.join(self.tmp, "gnssemud.log")).read()


def http_get(host, port, path, timeout=5.0):
    with socket.create_connection((host, port), timeout=timeout) as s:
        s.sendall(f"GET {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n".encode())
        data = b""
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    return head.decode(errors="replace"), body


def status(host, port):
    head, body = http_get(host, port, "/api/status?history=0")
    assert head.startswith("HTTP/1.1 200"), head
    return json.loads(body)


def case_abuse(rig):
    host, port = rig.start("--status-port", "free")
    assert host == "127.0.0.1", f"status page on {host}, not loopback"
    time.sleep(2.5)
    s0 = status(host, port)
    t0 = time.monotonic()

    # A slow sender: one byte every 0.5 s never completes a request.
    slow = socket.create_connection((host, port))
    slow.setblocking(False)
    slow_started = time.monotonic()
    # A stream nobody reads, with a tiny receive window.
    stuck = socket.socket()
    stuck.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 2048)
    stuck.connect((host, port))
    stuck.sendall(b"GET /api/events HTTP/1.1\r\nHost: x\r\n\r\n")

    rng = random.Random(14)
    bad = 0
    for k in range(60):
        junk = bytes(rng.randrange(256) for _ in range(rng.choice([1, 40, 700, 9000]))) + b"\r\n\r\n"
        try:
            with socket.create_connection((host, port), timeout=3) as j:
                j.sendall(junk)
                j.settimeout(3)
                reply = j.recv(64)
                bad += reply.startswith(b"HTTP/1.1 4")
        except OSError:
            pass
        try:
            slow.send(b"G")
        except OSError:
            pass
    head, _ = http_get(host, port, "/index.html")
    assert head.startswith("HTTP/1.1 200"), head
    with socket.create_connection((host, port), timeout=5) as h:
        h.sendall(b"GET / HTTP/1.1\r\nX-Big: " + b"a" * 200000 + b"\r\n\r\n")
        assert h.recv(64).startswith(b"HTTP/1.1 431"), "huge header not refused"

    # More connections than the server serves at once; they go away again.
    crowd = [socket.create_connection((host, port)) for _ in range(150)]
    time.sleep(0.5)
    for c in crowd:
        c.close()
    time.sleep(0.5)

    # The slow sender is cut off after the request timeout.
    while time.monotonic() - slow_started < 12.5:
        try:
            slow.send(b"E")
        except OSError:
            break
        time.sleep(0.5)
    closed = False
    try:
        closed = slow.recv(1) == b""
    except BlockingIOError:
        closed = False
    except OSError:
        closed = True
    assert closed, "a request that never completes was not closed"

    s1 = status(host, port)
    elapsed = time.monotonic() - t0
    epochs = s1["epoch"]["count"] - s0["epoch"]["count"]
    print(f"{bad} junk requests answered 4xx; {epochs} epochs in {elapsed:.1f} s while abused")
    assert abs(epochs - elapsed) <= 1.5, f"epoch loop fell behind: {epochs} epochs in {elapsed:.1f} s"
    assert bad >= 30, f"only {bad} of 60 junk requests got a 4xx"
    assert rig.daemon.poll() is None, "gnssemud died"
    stuck.close()


def case_ports(rig):
    # Off.
    assert rig.start("--status-port", "0") is None, "status page served with --status-port 0"
    rig.stop_all()
    rig.procs.clear()
    # A taken port moves the page to a free one.
    taken = socket.socket()
    taken.bind(("127.0.0.1", free_port(socket.SOCK_STREAM)))
    taken.listen(1)
    busy = taken.getsockname()[1]
    host, port = rig.start("--status-port", str(busy))
    assert port != busy, "status page on a taken port"
    assert "serving the status page on a free port instead" in rig.log(), rig.log()
    status(host, port)
    taken.close()
    rig.stop_all()
    rig.procs.clear()
    # --check-config names the page.
    out = subprocess.run([rig.gnssemud, "--check-config", "--status-port", "8123"], capture_output=True, text=True)
    assert "status:  http://127.0.0.1:8123/" in out.stdout, out.stdout + out.stderr
    # The [status] keys: another loopback address on a free port ...
    host, port = rig.start("--config", rig.config('bind = "127.0.0.2"\nfree_port = true'))
    assert host == "127.0.0.2", f"status page on {host}"
    status(host, port)
    rig.stop_all()
    rig.procs.clear()
    # ... an address outside loopback is named as such (checked, not bound:
    # the tests stay on loopback) ...
    out = subprocess.run([rig.gnssemud, "--check-config", "--config", rig.config('bind = "0.0.0.0"\nport = 8124')],
                         capture_output=True, text=True)
    assert "status:  http://0.0.0.0:8124/ (not loopback: reachable from other machines)" in out.stdout, out.stdout
    # ... a bad value is an error naming file:line ...
    bad = rig.config('bind = "localhost"')
    out = subprocess.run([rig.gnssemud, "--check-config", "--config", bad], capture_output=True, text=True)
    assert out.returncode != 0 and f"{bad}:8: status.bind: 'localhost' is not an IPv4 or IPv6 address" in out.stderr, \
        out.stdout + out.stderr
    # ... and port = 0 turns it off.
    assert rig.start("--config", rig.config("port = 0")) is None, "status page served with port = 0"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("case", choices=["abuse", "ports"])
    a = ap.parse_args()
    rig = Rig(a.gnssemud)
    try:
        {"abuse": case_abuse, "ports": case_ports}[a.case](rig)
        rc = rig.stop_all()
        assert rc == 0, f"gnssemud exit status {rc}"
        print("1 passed, 0 failed")
    except Exception:
        rig.stop_all()
        rig.dump_logs()
        raise
    finally:
        rig.remove_tmp()


if __name__ == "__main__":
    main()
