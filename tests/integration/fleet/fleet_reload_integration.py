#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""SIGHUP on a fleet (docs/daemon.md §Reload): gnssemud runs vehicles "a"
and "b" at 2 Hz, truth for both at 10 Hz; a host turns GSV off on a's pty
(CFG-MSG). A reload with a broken file keeps all running and logs
file:line. Then the file drops "b" and adds "c", and a SIGHUP applies it:
a's pty keeps emitting with no gap in its GGA times, no loss of its fix and
GSV still off; b's pty disappears and b's packets count as unknown_vehicle;
c's pty appears and gets a fix. A last reload changes c's seed (applied
live) and its output's baud (logged as needing a restart). Prints the largest GGA gap on "a" across the
reload and c's time to first fix from the signal. Loopback only, free
ports, temp dir; stops itself in 120 s.

usage: fleet_reload_integration.py --gnssemud PATH --nav FILE
"""
import argparse
import json
import math
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, run_rig, enu_to_latlon as itlib_enu_to_latlon, daemon_toml  # noqa: E402
from ubx_host import frame  # noqa: E402

ORIGIN = (48.8738, 2.2950, 100.0)
RATE_HZ = 2.0
POS = {"a": (120.0, -80.0), "b": (120.0, 920.0), "c": (-400.0, 300.0)}  # m east/north of the origin
FIX_TOLERANCE_M = 15.0


def enu_to_latlon(e, n):
    return itlib_enu_to_latlon(ORIGIN, e, n)


def nmea_deg(v, hemi):
    """ddmm.mmmm / dddmm.mmmm with N/S/E/W to signed degrees."""
    d = int(float(v) / 100)
    x = d + (float(v) - 100 * d) / 60
    return -x if hemi in ("S", "W") else x


class PtyReader(threading.Thread):
    """Every NMEA line of a pty with its arrival time; ends when the pty goes."""

    def __init__(self, path):
        super().__init__(daemon=True)
        self.path = path
        self.lines = []  # (monotonic, text)
        self.closed_at = None
        self.stop = False
        self.fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)

    def run(self):
        buf = b""
        try:
            while not self.stop:
                try:
                    chunk = os.read(self.fd, 65536)
                except BlockingIOError:
                    time.sleep(0.005)
                    continue
                except OSError:
                    break
                if not chunk:
                    break
                buf += chunk
                now = time.monotonic()
                *done, buf = buf.split(b"\r\n")
                for line in done:
                    i = line.find(b"$")
                    if i >= 0:
                        self.lines.append((now, line[i:].decode(errors="replace")))
        finally:
            self.closed_at = time.monotonic()
            os.close(self.fd)

    def ggas(self, since=0.0):
        """(monotonic, utc s of day, quality, lat, lon) of every GGA read after since."""
        out = []
        for t, line in list(self.lines):
            f = line.split(",")
            if t < since or len(f) < 7 or f[0][3:6] != "GGA" or not f[1]:
                continue
            utc = int(f[1][0:2]) * 3600 + int(f[1][2:4]) * 60 + float(f[1][4:])
            q = int(f[6] or 0)
            lat = nmea_deg(f[2], f[3]) if q else None
            lon = nmea_deg(f[4], f[5]) if q else None
            out.append((t, utc, q, lat, lon))
        return out

    def count(self, kind, since):
        return sum(1 for t, line in list(self.lines) if t >= since and line[3:6] == kind)


def horizontal_m(lat_a, lon_a, lat_b, lon_b):
    dn = math.radians(lat_a - lat_b) * 6371000.0
    de = math.radians(lon_a - lon_b) * 6371000.0 * math.cos(math.radians(ORIGIN[0]))
    return math.hypot(de, dn)


class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-reload-")
        self.args = args
        self.udp_port = free_port(socket.SOCK_DGRAM)
        self.cfg = os.path.join(self.tmp, "fleet.toml")
        self.stop_sending = threading.Event()
        self.vehicles = ["a", "b"]

    def pty(self, v):
        return os.path.join(self.tmp, f"{v}-gps1")

    def write_config(self, vehicles, extra="", receiver_keys=None):
        text = f"""{daemon_toml(ORIGIN, self.args.nav, "2022-01-01T01:00:00", RATE_HZ, self.udp_port)}[status]
port = 0
"""
        for v in vehicles:
            text += f"""[[vehicle]]
id = "{v}"
[[vehicle.receiver]]
name = "gps1"
{(receiver_keys or {}).get(v, "")}
[[vehicle.receiver.output]]
name = "{v}-gps1"
type = "pty"
path = "{self.pty(v)}"
{(receiver_keys or {}).get(v + "-output", "")}
"""
        # Written whole and renamed: the daemon never reads half a file.
        tmp = self.cfg + ".new"
        with open(tmp, "w") as f:
            f.write(text + extra)
        os.replace(tmp, self.cfg)

    def start(self):
        self.write_config(self.vehicles)
        self.daemon_log_path = os.path.join(self.tmp, "gnssemud.log")
        self.daemon_log = open(self.daemon_log_path, "w")
        self.daemon = self.spawn([self.args.gnssemud, "--config", self.cfg], stdout=subprocess.DEVNULL,
                                 stderr=self.daemon_log)
        deadline = time.monotonic() + 20
        while not all(os.path.exists(self.pty(v)) for v in self.vehicles):
            if time.monotonic() > deadline or self.daemon.poll() is not None:
                raise AssertionError("the two ptys did not appear")
            time.sleep(0.1)
        threading.Thread(target=self.send, daemon=True).start()

    def send(self):
        """10 Hz truth for a, b and c (c's is dropped until c exists; b's after it goes)."""
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        t = 0.0
        while not self.stop_sending.is_set():
            for v, (e, n) in POS.items():
                lat, lon = enu_to_latlon(e, n)
                msg = {"version": 1, "vehicle": v, "sim_time_s": t,
                       "lla": {"lat_deg": lat, "lon_deg": lon, "height_m": ORIGIN[2]}}
                s.sendto(json.dumps(msg).encode(), ("127.0.0.1", self.udp_port))
            t += 0.1
            time.sleep(0.1)
        s.close()

    def log(self):
        self.daemon_log.flush()
        return open(self.daemon_log_path, errors="replace").read()

    def wait_log(self, pattern, start, limit_s=10):
        deadline = time.monotonic() + limit_s
        while time.monotonic() < deadline:
            m = re.search(pattern, self.log()[start:])
            if m:
                return m
            time.sleep(0.05)
        raise AssertionError(f"no log line {pattern!r} within {limit_s} s")


def wait_fix(reader, v, since, limit_s):
    """monotonic time of the first GGA with a fix within FIX_TOLERANCE_M of v after since."""
    want = enu_to_latlon(*POS[v])
    deadline = time.monotonic() + limit_s
    while time.monotonic() < deadline:
        for t, _, q, lat, lon in reader.ggas(since):
            if q >= 1 and horizontal_m(lat, lon, *want) < FIX_TOLERANCE_M:
                return t
        time.sleep(0.05)
    raise AssertionError(f"{v}: no fix within {FIX_TOLERANCE_M} m of its truth in {limit_s} s")


def body(rig):
    rig.start()
    readers = {v: PtyReader(rig.pty(v)) for v in rig.vehicles}
    for r in readers.values():
        r.start()
    t0 = time.monotonic()
    first_fix = {v: wait_fix(readers[v], v, t0, 60) for v in rig.vehicles}
    print(f"  a and b: fixes at their truth {time.monotonic() - t0:.1f} s after start")

    # A host configures a's chip: GSV off (CFG-MSG NMEA-GSV rate 0 on this port).
    os.write(readers["a"].fd, frame(0x06, 0x01, bytes([0xF0, 0x03, 0x00])))
    time.sleep(1.5)
    gsv_off_at = time.monotonic()

    # A broken file: nothing changes, the error names file:line.
    mark = len(rig.log())
    rig.write_config(["a", "c"], extra="[[vehicle]]\nid = \"a\"\n")
    rig.daemon.send_signal(signal.SIGHUP)
    m = rig.wait_log(r"reload failed, keeping the running configuration: (\S+fleet\.toml:\d+: .*)", mark)
    print(f"  bad file refused: {m.group(1)}")
    time.sleep(1.5)
    assert os.path.exists(rig.pty("b")) and not os.path.exists(rig.pty("c")), "a failed reload changed the ptys"
    assert readers["b"].count("GGA", time.monotonic() - 1.0) >= 1, "b stopped after a failed reload"

    # Drop b, add c.
    rig.write_config(["a", "c"])
    mark = len(rig.log())
    hup = time.monotonic()
    rig.daemon.send_signal(signal.SIGHUP)
    m = rig.wait_log(r"reload: \S+ applied in ([\d.]+) ms \((.*)\)", mark)
    print(f"  reload applied in {m.group(1)} ms ({m.group(2)})")
    assert "vehicles added: c; removed: b; changed: none; unchanged: a" in m.group(2), m.group(2)
    deadline = time.monotonic() + 5
    while not os.path.exists(rig.pty("c")):
        assert time.monotonic() < deadline, "c's pty did not appear"
        time.sleep(0.02)
    c_seen = time.monotonic()
    readers["c"] = PtyReader(rig.pty("c"))
    readers["c"].start()
    assert not os.path.exists(rig.pty("b")), "b's pty symlink is still there"
    readers["b"].join(5)
    assert readers["b"].closed_at is not None, "b's pty still open"
    c_fix = wait_fix(readers["c"], "c", hup, 60)
    print(f"  c: pty after {1e3 * (c_seen - hup):.0f} ms, first fix at its truth {c_fix - hup:.2f} s after SIGHUP; "
          f"b: pty gone {1e3 * (readers['b'].closed_at - hup):.0f} ms after SIGHUP")
    time.sleep(5)

    # a across the reload: every epoch, its fix, GSV still off.
    after = time.monotonic()
    since = first_fix["a"]
    ggas = readers["a"].ggas(since)
    assert ggas and ggas[0][0] < hup - 2 and ggas[-1][0] > after - 1, "a's GGAs do not span the reload"
    utc_gap = max(b[1] - a[1] for a, b in zip(ggas, ggas[1:]))
    wall_gap = max(b[0] - a[0] for a, b in zip(ggas, ggas[1:]))
    lost = [g for g in ggas if g[2] == 0]
    print(f"  a: {len(ggas)} GGAs from its first fix ({hup - since:.1f} s before SIGHUP) to {after - hup:.1f} s after: "
          f"largest gap in GGA time "
          f"{utc_gap:.2f} s (period {1 / RATE_HZ:.2f} s), between arrivals {1e3 * wall_gap:.0f} ms; "
          f"{len(lost)} without a fix")
    assert abs(utc_gap - 1 / RATE_HZ) < 0.01, f"a lost epochs across the reload: GGA gap {utc_gap:.2f} s"
    assert wall_gap < 3 / RATE_HZ, f"a's output stalled {wall_gap:.2f} s"
    assert not lost, "a lost its fix across the reload"
    gsv = readers["a"].count("GSV", gsv_off_at)
    assert gsv == 0, f"a sent {gsv} GSV after its host turned GSV off: its chip was reset"
    assert readers["c"].count("GSV", 0) > 0, "c (factory settings) sends no GSV"

    # A changed vehicle: c's models apply live, its output's baud at a restart; a stays untouched.
    rig.write_config(["a", "c"], receiver_keys={"c": "seed = 5", "c-output": "baud = 115200"})
    mark2 = len(rig.log())
    rig.daemon.send_signal(signal.SIGHUP)
    live = rig.wait_log(r"reload: vehicle 'c' changed: applied live: (.*)", mark2)
    later = rig.wait_log(r"reload: vehicle 'c' changed: needs a restart, running on the old values: (.*)", mark2)
    assert live.group(1) == "gps1: receiver models (receiver restarted, hot)", live.group(1)
    assert later.group(1) == "gps1: output c-gps1 protocols/messages/baud", later.group(1)
    rig.wait_log(r"applied in [\d.]+ ms \(nothing; vehicles added: none; removed: none; changed: c; unchanged: a\)",
                 mark2)
    print(f"  c changed: live: {live.group(1)}; at a restart: {later.group(1)}")

    # b's packets are unknown now; the drops say so.
    rig.wait_log(r"unknown_vehicle \(vehicle 'b' is not configured\)", mark, limit_s=15)
    rig.stop_sending.set()
    rc = rig.stop_all()
    log = rig.log()
    assert rc == 0, f"gnssemud exit {rc}"
    for needle in ["reload: vehicle 'b' removed", "reload: vehicle 'c' added: c/gps1",
                   "reload: vehicle(s) unchanged, running on untouched: a", "truth: vehicle 'c':"]:
        assert needle in log, f"the log lacks {needle!r}"
    print("  b's later packets dropped as unknown_vehicle; exit summary has a and c")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--nav", required=True)
    args = ap.parse_args()
    return run_rig(Rig(args), body, 120)


if __name__ == "__main__":
    sys.exit(main())
