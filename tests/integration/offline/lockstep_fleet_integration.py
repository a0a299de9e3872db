#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""A fleet in lockstep, faster and slower than real time, is byte-identical
to `gnssemu batch` for every receiver (docs/daemon.md §Time). Two vehicles on
one sky: "a" with gps1 and gps2 (another seed), "b" with gps1 on another
path. Truth for both is sent paced at a speed factor of simulation time
(`fast`: 20x, the factor PX4's SITL CI runs at; `slow`: 0.1x); each
receiver's file port must equal `gnssemu batch --vehicle V --receiver R` on
its vehicle's truth, epoch by epoch, from the first packet on.

Lockstep emits an epoch once every vehicle that has sent truth has reached
it, so the first epoch waits for both only if both have sent something: b's
truth starts 0.1 s before a's (a row off the 5 Hz grid, in its CSV too), and
that packet goes first.

The serial line is simulated in simulation time: a/gps1 also has a 38400-baud
pty carrying 5 Hz NMEA (~2.9 kB/s of its 3.84 kB/s); at 20x a wall-clock
budget passes about one epoch in fourteen. Every epoch's GGA must reach the
pty reader and the daemon must count no message over the line budget.

usage: lockstep_fleet_integration.py --gnssemud P --gnssemu P --nav FILE fast|slow
"""
import argparse
import json
import os
import re
import socket
import subprocess
import sys
import struct
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
import lockstep_batch_integration as lb  # noqa: E402
from itlib import RigBase, free_port  # noqa: E402

RATE_HZ = 5.0
SPEED = {"fast": 20.0, "slow": 0.1}
DURATION_S = {"fast": 60, "slow": 6}
B_NORTH_DEG = 0.002  # vehicle b: ~220 m north of a's path
RECEIVERS = [("a", "gps1"), ("a", "gps2"), ("b", "gps1")]

CONFIG = """[origin]
lat_deg = {lat}
lon_deg = {lon}
height_m = {h}
[nav]
file = "{nav}"
[time]
mode = "lockstep"
start = "2022-01-01T07:00:00"
[receiver]
rate_hz = {rate}
seed = 11
[truth]
bind = "127.0.0.1"
port = {port}
timeout_s = {timeout}
[demo]
enabled = false

[[vehicle]]
id = "a"
[[vehicle.receiver]]
name = "gps1"
[[vehicle.receiver.output]]
{file_out}
path = "{tmp}/a_gps1.out"
[[vehicle.receiver.output]]
name = "line"
type = "pty"
path = "{tmp}/a_gps1.pty"
baud = 38400
sentences = ["RMC", "VTG", "GGA", "GSA", "GSV"]
[[vehicle.receiver]]
name = "gps2"
seed = 17
[[vehicle.receiver.output]]
{file_out}
path = "{tmp}/a_gps2.out"

[[vehicle]]
id = "b"
[[vehicle.receiver]]
name = "gps1"
[[vehicle.receiver.output]]
{file_out}
path = "{tmp}/b_gps1.out"
"""

FILE_OUT = """name = "log"
type = "file"
protocols_out = ["nmea", "ubx"]
sentences = ["RMC", "VTG", "GGA", "GSA", "GSV", "GLL", "GST", "ZDA"]
ubx_messages = ["NAV-PVT", "NAV-POSLLH", "NAV-VELNED", "NAV-STATUS", "NAV-DOP", "NAV-SOL", "NAV-TIMEUTC",
                "NAV-SAT", "NAV-SVINFO", "MON-HW", "NAV-EOE"]
rates = { NAV-SAT = 5, NAV-SVINFO = 5, GSV = 5, MON-HW = 2 }"""


def rows_of(vehicle, duration_s):
    lb.DURATION_S = duration_s
    rows = lb.trajectory()
    if vehicle == "b":
        rows = [(t, lat + B_NORTH_DEG, lon, h, ve, vn, vu) for t, lat, lon, h, ve, vn, vu in rows]
        rows.insert(0, (rows[0][0] - 0.1,) + rows[0][1:])
    return rows


def packet(vehicle, row):
    tow, lat, lon, h, ve, vn, vu = row
    return json.dumps({"version": 1, "vehicle": vehicle, "sim_time_s": tow - lb.TOW0_S,
                       "gps_week": lb.WEEK, "gps_tow_s": tow,
                       "lla": {"lat_deg": lat, "lon_deg": lon, "height_m": h},
                       "vel_enu": {"e_m_s": ve, "n_m_s": vn, "u_m_s": vu}}, allow_nan=False).encode()


class PtyReader(threading.Thread):
    def __init__(self, path):
        super().__init__(daemon=True)
        self.path, self.data, self.stop = path, bytearray(), False

    def run(self):
        fd = os.open(self.path, os.O_RDONLY | os.O_NOCTTY | os.O_NONBLOCK)
        try:
            while not self.stop:
                try:
                    chunk = os.read(fd, 65536)
                except BlockingIOError:
                    time.sleep(0.002)
                    continue
                except OSError:
                    break
                if chunk:
                    self.data += chunk
        finally:
            os.close(fd)


def gga_tows(data, week_start_s):
    """UTC seconds of day of every GGA read."""
    out = []
    for line in bytes(data).split(b"\r\n"):
        if line[3:6] == b"GGA":
            hhmmss = line.split(b",")[1]
            if hhmmss:
                out.append(round(int(hhmmss[0:2]) * 3600 + int(hhmmss[2:4]) * 60 + float(hhmmss[4:]), 2))
    return out


def run(args, rig, case):
    speed, duration = SPEED[case], DURATION_S[case]
    port = free_port(socket.SOCK_DGRAM)
    # At 0.1x a packet comes every 10 s of wall time: the timeout is wall time.
    timeout = 3.0 if speed >= 1.0 else 30.0
    cfg = os.path.join(rig.tmp, "fleet.toml")
    with open(cfg, "w") as f:
        f.write(CONFIG.format(lat=lb.LAT0_DEG, lon=lb.LON0_DEG, h=lb.H0_M, nav=args.nav, rate=RATE_HZ, port=port,
                              timeout=timeout, tmp=rig.tmp, file_out=FILE_OUT))
    rows = {v: rows_of(v, duration) for v in ("a", "b")}
    truth = {}
    for v in rows:
        truth[v] = os.path.join(rig.tmp, f"truth_{v}.csv")
        lb.write_truth_csv(truth[v], rows[v])

    batch = {}
    for v, r in RECEIVERS:
        nmea, ubx = os.path.join(rig.tmp, f"batch_{v}_{r}.nmea"), os.path.join(rig.tmp, f"batch_{v}_{r}.ubx")
        subprocess.run([args.gnssemu, "batch", "--config", cfg, "--vehicle", v, "--receiver", r, "--truth", truth[v],
                        "--nmea", nmea, "--ubx", ubx], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        batch[(v, r)] = (lb.split(open(ubx, "rb").read(), ubx), lb.split(open(nmea, "rb").read(), nmea))

    log = open(os.path.join(rig.tmp, "gnssemud.log"), "w")
    rig.daemon = rig.spawn([args.gnssemud, "-c", cfg, "--status-port", "0"], stdout=log, stderr=subprocess.STDOUT)
    outs = {(v, r): os.path.join(rig.tmp, f"{v}_{r}.out") for v, r in RECEIVERS}
    pty = os.path.join(rig.tmp, "a_gps1.pty")
    deadline = time.monotonic() + 20
    while not (all(os.path.exists(p) and os.path.getsize(p) > 0 for p in outs.values()) and os.path.exists(pty)):
        if rig.daemon.poll() is not None or time.monotonic() > deadline:
            raise SystemExit("gnssemud did not start writing its outputs")
        time.sleep(0.05)
    reader = PtyReader(pty)
    reader.start()
    time.sleep(0.3)

    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    t0 = time.monotonic()
    sock.sendto(packet("b", rows["b"][0]), ("127.0.0.1", port))
    for k in range(len(rows["a"])):
        due = t0 + k / speed
        while time.monotonic() < due:
            time.sleep(min(0.01, due - time.monotonic()))
        sock.sendto(packet("a", rows["a"][k]), ("127.0.0.1", port))
        sock.sendto(packet("b", rows["b"][k + 1]), ("127.0.0.1", port))
    wall_s = time.monotonic() - t0
    last_ms = round(rows["a"][-1][0] * 1000)
    tail = struct.pack("<BBH", 0x01, 0x61, 4) + struct.pack("<I", last_ms)
    while not all(tail in open(p, "rb").read() for p in outs.values()):
        if rig.daemon.poll() is not None or time.monotonic() > deadline + 30 + wall_s:
            raise SystemExit(f"the daemon never wrote the epoch of the last packet (iTOW {last_ms})")
        time.sleep(0.02)
    time.sleep(0.3)
    reader.stop = True
    rc = rig.stop_all()
    reader.join(2)
    log.close()
    if rc != 0:
        raise SystemExit(f"gnssemud exited {rc}")
    text = open(os.path.join(rig.tmp, "gnssemud.log")).read()

    failed = False
    for key in RECEIVERS:
        d_epochs = lb.epochs(lb.split(open(outs[key], "rb").read(), outs[key]), outs[key])
        b_ubx, b_nmea = batch[key]
        problems = lb.compare(d_epochs, b_ubx, b_nmea)
        n = len(lb.epochs(b_ubx, "batch"))
        if problems:
            failed = True
            print(f"FAIL {case} {key[0]}/{key[1]}: lockstep and batch differ in {len(problems)} place(s):")
            for p in problems[:20]:
                print("  " + p)
        else:
            print(f"{case}: {key[0]}/{key[1]}: {n} epochs identical to batch")
    # GGA of every epoch of the truth's span on the 38400-baud pty.
    utc0 = (lb.TOW0_S - 18) % 86400  # GPS - UTC = 18 s in 2022
    want = [round(utc0 + k / RATE_HZ, 2) for k in range(int(duration * RATE_HZ) + 1)]
    got = set(gga_tows(reader.data, 0))
    missing = [t for t in want if t not in got]
    over = [ln for ln in text.splitlines()
            if re.search(r"[1-9]\d* messages over the line budget", ln) or "transmit buffer is full" in ln]
    print(f"{case}: {speed:g}x real time ({len(rows['a'])} packets per vehicle in {wall_s:.1f} s); pty at 38400 baud: "
          f"{len(want) - len(missing)} of {len(want)} epochs' GGA read")
    if missing:
        failed = True
        print(f"FAIL {case}: {len(missing)} GGA missing on the pty, first {missing[:5]}")
    if over:
        failed = True
        print(f"FAIL {case}: the line budget dropped messages: {over[:3]}")
    return 1 if failed else 0


class Rig(RigBase):
    def __init__(self):
        super().__init__("gnssemu-lockfleet-")
        self.daemon = None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("case", choices=sorted(SPEED))
    args = ap.parse_args()
    args.nav = os.path.abspath(args.nav)
    rig = Rig()
    ok = False
    try:
        rc = run(args, rig, args.case)
        ok = rc == 0
        return rc
    finally:
        rig.stop_all()
        if not ok:
            rig.dump_logs()
        rig.remove_tmp()


if __name__ == "__main__":
    sys.exit(main())
