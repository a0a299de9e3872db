#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Three autopilot SITL instances' truth through tools/senders/mavlink_truth.py
into one gnssemud fleet (docs/sitl.md), each receiver on its own pty.

Each "instance" here is a stand-in that speaks MAVLink 2 as ArduPilot SITL
does: HEARTBEAT at 1 Hz, and SIM_STATE (lat/lon as degE7 in the float fields
and in lat_int/lon_int, alt above mean sea level, NED velocity) only after
the bridge asked for it with SET_MESSAGE_INTERVAL (a SITL whose stream rate
is 0 sends none). The three fly apart (300 m) at different heights. Each
pty's GGA must put its receiver within 15 m of its own instance and at its
height above sea level within 15 m, and every instance must have been asked
for SIM_STATE at the bridge's rate. Loopback only, free ports, temp dir.

usage: sitl_bridge_integration.py --gnssemud PATH --bridge PATH --nav FILE
"""
import argparse
import math
import os
import select
import socket
import struct
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, parse_gga, run_rig, enu_to_latlon  # noqa: E402

ORIGIN = (48.8738, 2.2950, 100.0)
GEOID_M = 46.5  # EGM2008 at the origin (the GGA geoid separation gnssemud prints there)
INSTANCES = {"v0": (0.0, 0.0, 40.0), "v1": (300.0, 0.0, 60.0), "v2": (0.0, 300.0, 80.0)}  # e, n, alt MSL
TOLERANCE_M = 15.0

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools", "senders"))


class FakeSitl(threading.Thread):
    """One SITL's MAVLink on UDP: heartbeats, and SIM_STATE at the interval asked."""

    def __init__(self, mt, bridge_port, e, n, alt_msl):
        super().__init__(daemon=True)
        self.mt, self.dest = mt, ("127.0.0.1", bridge_port)
        self.lat, self.lon = enu_to_latlon(ORIGIN, e, n)
        self.alt = alt_msl
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.interval_s = None
        self.stop = False

    def run(self):
        seq, next_hb, next_state = 0, 0.0, 0.0
        while not self.stop:
            now = time.monotonic()
            if now >= next_hb:
                hb = struct.pack("<IBBBBB", 0, 2, 3, 0x81, 3, 3)  # custom_mode, quadrotor, ArduPilot, armed
                self.sock.sendto(self.mt.encode_v2(self.mt.MSG_HEARTBEAT, hb, seq, 1, 1), self.dest)
                seq, next_hb = seq + 1, now + 1.0
            if self.interval_s and now >= next_state:
                f = [1, 0, 0, 0, 0, 0, 0, 0, 0, -9.81, 0, 0, 0, self.lat * 1e7, self.lon * 1e7, self.alt, 0, 0,
                     0.0, 0.0, 0.0]
                p = struct.pack("<21f", *f) + struct.pack("<ii", round(self.lat * 1e7), round(self.lon * 1e7))
                self.sock.sendto(self.mt.encode_v2(self.mt.MSG_SIM_STATE, p, seq, 1, 1), self.dest)
                seq, next_state = seq + 1, now + self.interval_s
            r, _, _ = select.select([self.sock], [], [], 0.02)
            if r:
                data = self.sock.recv(4096)
                for msgid, _, _, payload in self.mt.frames(data):
                    if msgid == self.mt.MSG_COMMAND_LONG:
                        p = struct.unpack("<7fHBBB", payload.ljust(33, b"\0"))
                        if p[7] == self.mt.MAV_CMD_SET_MESSAGE_INTERVAL and p[0] == 108.0 and p[1] > 0:
                            self.interval_s = p[1] * 1e-6


def body(rig):
    import mavlink_truth as mt
    a = rig.args
    truth_port = free_port(socket.SOCK_DGRAM)
    ports = {v: free_port(socket.SOCK_DGRAM) for v in INSTANCES}
    cfg = os.path.join(rig.tmp, "sitl.toml")
    with open(cfg, "w") as f:
        f.write(f'[origin]\nlat_deg = {ORIGIN[0]}\nlon_deg = {ORIGIN[1]}\nheight_m = {ORIGIN[2]}\n'
                f'[nav]\nfile = "{os.path.abspath(a.nav)}"\n[truth]\nport = {truth_port}\n'
                f'[fleet]\ncount = 3\n[[fleet.output]]\nname = "gps"\ntype = "pty"\n'
                f'path = "{rig.tmp}/{{vehicle}}"\n')
    log = open(os.path.join(rig.tmp, "gnssemud.log"), "w")
    rig.daemon = rig.spawn([a.gnssemud, "--config", cfg], stdout=subprocess.PIPE, stderr=log, text=True)
    blog = open(os.path.join(rig.tmp, "bridge.log"), "w")
    rig.spawn([sys.executable, a.bridge, "--port", str(truth_port), "--geoid-m", str(GEOID_M), "--rate", "10"] +
              [x for v, p in ports.items() for x in ("--sitl", f"{v}={p}")], stdout=blog, stderr=subprocess.STDOUT)
    fakes = {v: FakeSitl(mt, ports[v], *INSTANCES[v]) for v in INSTANCES}
    for s in fakes.values():
        s.start()
    deadline = time.monotonic() + 10
    while not all(os.path.exists(os.path.join(rig.tmp, v)) for v in INSTANCES):
        if time.monotonic() > deadline:
            raise AssertionError("the three ptys did not appear")
        time.sleep(0.1)
    fds = {v: os.open(os.path.join(rig.tmp, v), os.O_RDONLY | os.O_NOCTTY | os.O_NONBLOCK) for v in INSTANCES}
    bufs = {v: b"" for v in INSTANCES}
    good = {}
    deadline = time.monotonic() + 40
    try:
        while len(good) < len(INSTANCES):
            if time.monotonic() > deadline:
                raise AssertionError(f"no GGA at its instance within 40 s for {sorted(set(INSTANCES) - set(good))}"
                                     f"; asked for SIM_STATE: {[v for v, s in fakes.items() if s.interval_s]}")
            r, _, _ = select.select(list(fds.values()), [], [], 0.5)
            for v, fd in fds.items():
                if fd not in r:
                    continue
                try:
                    bufs[v] += os.read(fd, 4096)
                except BlockingIOError:
                    continue
                *lines, bufs[v] = bufs[v].split(b"\n")
                for line in lines:
                    g = parse_gga(line.decode("ascii", "replace").strip())
                    if g is None or g[0] == 0 or g[3] is None:
                        continue
                    lat, lon = enu_to_latlon(ORIGIN, *INSTANCES[v][:2])
                    dn = math.radians(g[1] - lat) * 6371000.0
                    de = math.radians(g[2] - lon) * 6371000.0 * math.cos(math.radians(lat))
                    if math.hypot(de, dn) < TOLERANCE_M and abs(g[3] - INSTANCES[v][2]) < TOLERANCE_M:
                        good.setdefault(v, (math.hypot(de, dn), g[3]))
    finally:
        for fd in fds.values():
            os.close(fd)
        for s in fakes.values():
            s.stop = True
    for v, s in fakes.items():
        assert s.interval_s is not None and abs(s.interval_s - 0.1) < 1e-9, f"{v}: SIM_STATE interval {s.interval_s}"
    for v, (h, alt) in sorted(good.items()):
        print(f"  {v}: GGA {h:.1f} m from its instance, {alt:.1f} m MSL (instance {INSTANCES[v][2]:.0f} m); "
              f"SIM_STATE asked at {1 / fakes[v].interval_s:.0f} Hz")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--bridge", required=True)
    ap.add_argument("--nav", required=True)
    args = ap.parse_args()
    rig = RigBase("gnssemu-sitl-")
    rig.args = args
    return run_rig(rig, body, 90)


if __name__ == "__main__":
    sys.exit(main())
