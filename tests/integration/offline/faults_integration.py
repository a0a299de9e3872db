#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemu batch --scenario, decoded by real programs: gpsdecode reads the
UBX stream of a scripted outage, jammer and takeover (TPV mode falls to 1 and
comes back), and the M8's own indicators are read from the frames: MON-HW
aStatus/agcCnt/jamInd/jammingState, NAV-STATUS spoofDetState (docs/faults.md).
Exit 77 (skip) without gpsdecode."""
import argparse
import datetime
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from ubx_host import split_stream  # noqa: E402

CONFIG = """[origin]
lat_deg = 48.8738
lon_deg = 2.295
height_m = 100.0
[nav]
file = "{nav}"
[receiver]
rate_hz = 1.0
seed = 3
[[output]]
name = "log"
type = "pty"
path = "/tmp/gnssemu-faults-it/gps0"
ubx_messages = ["NAV-PVT", "NAV-STATUS", "NAV-DOP", "NAV-SAT", "NAV-TIMEUTC", "MON-HW", "NAV-EOE"]
protocols_out = ["ubx"]
"""

# t 0-29 clean, 30-39 antenna open, 40-59 clean, 60-79 jammer 45 dB (CW),
# 80-99 clean, 100-119 takeover (+10 us, 300 m north), then clean.
SCENARIO = """[[event]]
type = "outage"
antenna = "open"
start_s = 30
duration_s = 10

[[event]]
type = "jammer"
kind = "cw"
start_s = 60
duration_s = 20
js_db = 45

[[event]]
type = "spoofer"
mode = "takeover"
start_s = 100
duration_s = 20
clock_jump_us = 10
offset_north_m = 300
power_advantage_db = 10
"""


def frames(data):
    """(class, id, payload) of every UBX frame in data."""
    for kind, m in split_stream(data)[0]:
        if kind == "ubx":
            yield m[2], m[3], m[6:-2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    args = ap.parse_args()
    if shutil.which("gpsdecode") is None:
        print("SKIP: gpsdecode not installed")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        cfg = os.path.join(tmp, "c.toml")
        with open(cfg, "w") as f:
            f.write(CONFIG.format(nav=os.path.abspath(args.nav)))
        scen = os.path.join(tmp, "s.toml")
        with open(scen, "w") as f:
            f.write(SCENARIO)
        truth = os.path.join(tmp, "t.csv")
        with open(truth, "w") as f:
            f.write("gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,522000,48.8738,2.295,100\n"
                    "2190,522140,48.8738,2.295,100\n")
        ubx = os.path.join(tmp, "o.ubx")
        r = subprocess.run([args.gnssemu, "batch", "--config", cfg, "--truth", truth, "--scenario", scen,
                            "--ubx", ubx], capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, r.stderr
        data = open(ubx, "rb").read()
        dec = subprocess.run(["gpsdecode", "-j"], input=data, capture_output=True, timeout=30)
        tpv = [json.loads(l) for l in dec.stdout.decode().splitlines() if '"class":"TPV"' in l]
        # Several TPVs per epoch (one per message with time): the last mode of each second.
        by_s = {}
        t0 = None
        for t in tpv:
            if "time" not in t:
                continue
            s = datetime.datetime.fromisoformat(t["time"].replace("Z", "+00:00")).timestamp()
            t0 = s if t0 is None else t0
            by_s[round(s - t0)] = t.get("mode", 0)
        modes = [by_s.get(k, 0) for k in range(max(by_s) + 1)]
        print(f"  gpsdecode: TPV mode per second {''.join(str(m) for m in modes)}")
        assert len(modes) >= 130, f"only {len(modes)} seconds decoded"

        def mode_at(a, b):
            return set(modes[a:b])

        # The receiver extrapolates for its coast limit but reports no fix
        # ([receiver.nav] coast_report = "no_fix").
        assert mode_at(5, 29) == {3}, mode_at(5, 29)
        assert max(mode_at(31, 40)) <= 1, f"antenna open: modes {mode_at(31, 40)}"
        assert 3 in mode_at(45, 59), "no 3D fix after the antenna came back"
        assert max(mode_at(61, 80)) <= 1, f"45 dB jammer: modes {mode_at(61, 80)}"
        assert 3 in mode_at(85, 99), "no 3D fix after the jammer stopped"
        # The M8's indicators in the same stream, epoch by epoch.
        hw, status = [], []
        for cls, mid, p in frames(data):
            if (cls, mid) == (0x0A, 0x09):
                hw.append((p[20], struct.unpack_from("<H", p, 18)[0], p[45], (p[22] >> 2) & 3))
            elif (cls, mid) == (0x01, 0x03):
                status.append((p[7] >> 3) & 3)
        print(f"  MON-HW (aStatus, agcCnt, jamInd, jamState) at 10/35/70 s: {hw[10]} {hw[35]} {hw[70]}")
        print(f"  NAV-STATUS spoofDetState 95-110 s: {status[95:111]}")
        assert hw[10][0] == 2 and hw[35][0] == 4, "aStatus OK, then OPEN"
        assert hw[70][1] < hw[10][1] and hw[70][2] > hw[10][2] + 50, "AGC down and jamInd up under the jammer"
        # The takeover breaks lock; once the spoofed signals are acquired (a few s) it is flagged.
        assert status[90] == 1 and min(status[105:120]) >= 2, "spoofDetState set by the takeover"
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
