#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""RTK against gnssemu's base with RTKLIB (docs/base-station.md "RTK with RTKLIB").

gnssemud runs a [base] from a fixed start time; str2str pulls its RTCM 3 MSM7
from the NTRIP caster on loopback, convbin decodes it into RINEX. `gnssemu
batch` runs the rover over the same span under the same sky (same top-level
seed and start: the shared orbit, clock and atmosphere errors are the base's)
and writes its RINEX. rnx2rtkp in kinematic RTK mode on the two must fix
ambiguities on >= --min-fix of the rover's epochs, and the fixed positions
must lie within --max-median-m (horizontal median) of the truth. --systems
chooses the constellations (with GLONASS the base adds 1087, 1020 and 1230),
--gloarmode rnx2rtkp's GLONASS ambiguity resolution.

Exit 77 (CTest skip) when str2str, convbin or rnx2rtkp is not installed.
"""
import argparse
import math
import os
import shutil
import socket
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port  # noqa: E402

START = "2024-01-10T06:00:00"  # GPS time inside the nav file's day (week 2296)
START_WEEK, START_TOW = 2296, 3 * 86400 + 6 * 3600.0
ROVER = (48.8738, 2.2950, 100.0)
BASE = (48.8790, 2.3010, 95.0)  # about 700 m away


def ecef(lat_deg, lon_deg, h_m):
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    return ((n + h_m) * math.cos(lat) * math.cos(lon), (n + h_m) * math.cos(lat) * math.sin(lon),
            (n * (1 - e2) + h_m) * math.sin(lat))


def rinex_span(path):
    """(first, last) epoch of a RINEX 3 observation file as seconds of GPS week START_WEEK."""
    times = []
    with open(path) as f:
        body = False
        for line in f:
            if "END OF HEADER" in line:
                body = True
            elif body and line.startswith(">"):
                y, mo, d, h, mi = (int(x) for x in line[2:18].split())
                sec = float(line[18:29])
                # 2024-01-10 is day 3 of the week.
                times.append((d - 7) * 86400 + h * 3600 + mi * 60 + sec)
    return (times[0], times[-1]) if times else (None, None)


def obs_types(path):
    types = {}
    with open(path) as f:
        for line in f:
            if "END OF HEADER" in line:
                break
            if line[60:].startswith("SYS / # / OBS TYPES") and line[0] != " ":
                types[line[0]] = line[7:58].split()
    return types


NAVSYS = {"G": 1, "R": 4, "E": 8, "C": 32}  # rnx2rtkp pos1-navsys bits


def solve(tmp, freq, base_xyz, rover_obs, base_obs, nav, first, systems, gloarmode):
    """rnx2rtkp kinematic on freq ("l1", "l1+l2") of systems with RTKLIB's default AR settings
    (continuous, ratio 3, no lock count) and GLONASS AR gloarmode: (epochs the base covers, fixed
    fraction, median horizontal error of the fixes, median satellites in the solution)."""
    tag = f"{freq}_{''.join(systems)}"
    conf = os.path.join(tmp, f"rtk_{tag}.conf")
    with open(conf, "w") as f:
        f.write(f"""pos1-posmode=kinematic
pos1-frequency={freq}
pos1-soltype=forward
pos1-elmask=15
pos1-navsys={sum(NAVSYS[x] for x in systems)}
pos1-ionoopt=brdc
pos1-tropopt=saas
pos2-armode=continuous
pos2-gloarmode={gloarmode}
pos2-arthres=3
pos2-elmaskar=15
out-solformat=llh
""")
    pos = os.path.join(tmp, f"rover_{tag}.pos")
    rtk = ["rnx2rtkp", "-k", conf, "-r"] + [f"{v:.4f}" for v in base_xyz] + ["-o", pos, rover_obs, base_obs, nav]
    print(" ".join(rtk))
    subprocess.run(rtk, capture_output=True, text=True, timeout=300)
    rows = []
    with open(pos) as f:
        for line in f:
            if line.startswith("%") or not line.strip():
                continue
            v = line.split()
            h, mi, sec = v[1].split(":")
            tow = 3 * 86400 + int(h) * 3600 + int(mi) * 60 + float(sec)
            if tow >= first - 0.5:  # the epochs the base covers
                rows.append((float(v[2]), float(v[3]), int(v[5]), int(v[6])))
    lat0 = math.radians(ROVER[0])
    horiz = []
    for lat, lon, q, _ in rows:
        if q != 1:
            continue
        dn = math.radians(lat - ROVER[0]) * 6378137.0
        de = math.radians(lon - ROVER[1]) * 6378137.0 * math.cos(lat0)
        horiz.append(math.hypot(dn, de))
    n = len(rows)
    sats = statistics.median(r[3] for r in rows) if rows else 0
    return n, (len(horiz) / n if n else 0.0), (statistics.median(horiz) if horiz else float("inf")), sats


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--bands", type=int, default=2, help="signals per satellite of base and rover (1 or 2)")
    ap.add_argument("--seconds", type=int, default=90, help="how long str2str pulls the base's RTCM")
    ap.add_argument("--profile", help="[receiver] profile of base and rover (docs/models.md \"Receiver profiles\")")
    ap.add_argument("--systems", default="G,E,C", help="constellations of base, rover and rnx2rtkp (of G, R, E, C)")
    ap.add_argument("--gloarmode", default="off", choices=("off", "on", "autocal", "fix-and-hold"),
                    help="rnx2rtkp pos2-gloarmode: GLONASS ambiguity resolution")
    ap.add_argument("--min-fix", type=float, default=0.95)
    ap.add_argument("--max-median-m", type=float, default=0.02)
    a = ap.parse_args()
    systems = a.systems.split(",")
    if not systems or any(x not in NAVSYS for x in systems):
        ap.error(f"--systems {a.systems}: a comma-separated list of G, R, E, C")
    # GLONASS: its observations (MSM7 1087), ephemerides (1020) and code-phase biases (1230).
    glonass_msgs = ",1087(1),1020(10),1230(5)" if "R" in systems else ""
    for tool in ("str2str", "convbin", "rnx2rtkp"):
        if shutil.which(tool) is None:
            print(f"{tool} not installed (Debian rtklib)")
            return 77
    rig = RigBase("gnssemu-rtk-")
    port = free_port(socket.SOCK_STREAM)
    cfg = os.path.join(rig.tmp, "rtk.toml")
    with open(cfg, "w") as f:
        f.write(f"""
[origin]
lat_deg = {ROVER[0]}
lon_deg = {ROVER[1]}
height_m = {ROVER[2]}
[nav]
file = "{os.path.abspath(a.nav)}"
[time]
start = "{START}"
[receiver]
{f'profile = "{a.profile}"' if a.profile else ""}
constellations = [{", ".join(f'"{x}"' for x in systems)}]
generation = "{"f9p" if a.bands > 1 else "m9"}"
raw_data = true
bands = {a.bands}
seed = 3
[truth]
port = {free_port(socket.SOCK_DGRAM)}
[demo]
enabled = true
[base]
lat_deg = {BASE[0]}
lon_deg = {BASE[1]}
height_m = {BASE[2]}
station_id = 7
messages = "1006(5),1077(1),1097(1),1127(1),1019(10),1042(10),1046(10){glonass_msgs}"
seed = 11
[base.ntrip]
port = {port}
mountpoint = "RTK"
""")
    log = open(os.path.join(rig.tmp, "gnssemud.log"), "w")
    ok = True
    try:
        rig.daemon = rig.spawn([a.gnssemud, "--config", cfg], stdout=subprocess.DEVNULL, stderr=log)
        deadline = time.monotonic() + 20
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                if time.monotonic() > deadline or rig.daemon.poll() is not None:
                    raise AssertionError("the caster did not open its port")
                time.sleep(0.2)
        base_rtcm = os.path.join(rig.tmp, "base.rtcm3")
        pull = ["str2str", "-in", f"ntrip://127.0.0.1:{port}/RTK", "-out", f"file://{base_rtcm}"]
        print(" ".join(pull))
        p = rig.spawn(pull, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(a.seconds)
        rig.stop(p)
        rig.stop(rig.daemon)
        base_obs, base_nav = base_rtcm + ".obs", base_rtcm + ".nav"
        conv = ["convbin", "-r", "rtcm3", "-tr", START.replace("-", "/").replace("T", " "), "-v", "3.04", "-od", "-os",
                "-o", base_obs, "-n", base_nav, base_rtcm]
        print(" ".join(conv))
        subprocess.run(conv, capture_output=True, text=True, timeout=60)
        first, last = rinex_span(base_obs) if os.path.exists(base_obs) else (None, None)
        if first is None:
            raise AssertionError("convbin decoded no base observations")
        print(f"base: epochs {first:.1f} .. {last:.1f} s of week {START_WEEK}; types {obs_types(base_obs)}")

        # The rover over the same span, from the base's start (the sky's first epoch).
        truth = os.path.join(rig.tmp, "truth.csv")
        with open(truth, "w") as f:
            f.write("gps_week,tow_s,lat_deg,lon_deg,height_m\n")
            for tow in (START_TOW, math.ceil(last) + 1.0):
                f.write(f"{START_WEEK},{tow:.1f},{ROVER[0]},{ROVER[1]},{ROVER[2]}\n")
        rover_obs, rover_nav = os.path.join(rig.tmp, "rover.obs"), os.path.join(rig.tmp, "rover.nav")
        batch = [a.gnssemu, "batch", "--config", cfg, "--truth", truth, "--rinex-obs", rover_obs,
                 "--rinex-nav", rover_nav]
        print(" ".join(batch))
        r = subprocess.run(batch, capture_output=True, text=True, timeout=300)
        if r.returncode != 0:
            raise AssertionError("gnssemu batch failed: " + r.stderr)
        print(f"rover: types {obs_types(rover_obs)}")

        bx, by, bz = ecef(*BASE)
        freqs = ["l1+l2", "l1"] if a.bands > 1 else ["l1"]
        for k, freq in enumerate(freqs):
            n, fix_rate, median, sats = solve(rig.tmp, freq, (bx, by, bz), rover_obs, base_obs, rover_nav, first,
                                              systems, a.gloarmode)
            print(f"rnx2rtkp ({freq}, {a.systems}, gloarmode {a.gloarmode}): {n} epochs, fixed {100 * fix_rate:.1f} %, "
                  f"fixed horizontal error median {100 * median:.2f} cm, median {sats} satellites"
                  f"{'' if k == 0 else ' (same data, L1 only: reported)'}")
            if k == 0:
                sats_with_all = sats
                ok &= n >= a.seconds // 2 and fix_rate >= a.min_fix and median <= a.max_median_m
        if "R" in systems:
            # GLONASS is used: the solution without it has fewer satellites.
            others = [x for x in systems if x != "R"]
            _, _, _, sats_without = solve(rig.tmp, freqs[0], (bx, by, bz), rover_obs, base_obs, rover_nav, first,
                                          others, a.gloarmode)
            print(f"rnx2rtkp ({freqs[0]}, {','.join(others)}): median {sats_without} satellites")
            ok &= sats_with_all >= sats_without + 4
    except AssertionError as e:
        print(e)
        ok = False
    finally:
        rig.stop_all()
        log.close()
        if ok:
            shutil.rmtree(rig.tmp, ignore_errors=True)
        else:
            print(f"kept {rig.tmp}")
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
