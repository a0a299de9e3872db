#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Issue 11: in batch and lockstep the same scenario, seed and truth give
byte-identical output. One config (a `file` output carrying NMEA and UBX),
one truth trajectory with GPS time, one scenario; `gnssemu batch` writes its
NMEA and UBX logs, `gnssemud --scenario` in lockstep mode gets the same truth
as UDP JSON packets as fast as it takes them, and the daemon's epochs for the
truth's GPS times must equal batch's byte for byte: every UBX frame (NAV-STATUS
msss and ttff included: in lockstep the chip's clock is the epoch time, see
docs/daemon.md §Time) and every NMEA sentence, in order.

The daemon's file also holds epochs before the first packet (the config's
start, an hour earlier) and after the simulator stopped; they are told apart
by NAV-EOE iTOW and not compared. As a check that the comparison can fail,
batch is run again with another seed and must differ.

Cases: `scenario` (jammer ramp, satellite bias step, spoofer drag; demo off),
`plain` (no scenario, demo on before the first packet, 5 Hz epochs on 1 Hz
truth: interpolation, rates > 1)."""
import argparse
import json
import math
import os
import socket
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port  # noqa: E402

WEEK = 2190
TOW0_S = 547200.0  # 2022-01-01 08:00:00 GPST, inside brdc0010.22n
DURATION_S = 100
LAT0_DEG, LON0_DEG, H0_M = 48.8738, 2.2950, 100.0

CONFIG = """[origin]
lat_deg = {lat}
lon_deg = {lon}
height_m = {h}
[nav]
file = "{nav}"
[time]
mode = "lockstep"
start = "2022-01-01T07:00:00"  # an hour before the truth: epochs before the first packet have other iTOWs
[receiver]
rate_hz = {rate}
seed = {seed}
[truth]
bind = "127.0.0.1"
port = {port}
timeout_s = 3.0
[demo]
enabled = {demo}
[[output]]
name = "log"
type = "file"
path = "{out}"
protocols_out = ["nmea", "ubx"]
sentences = ["RMC", "VTG", "GGA", "GSA", "GSV", "GLL", "GST", "ZDA"]
ubx_messages = ["NAV-PVT", "NAV-POSLLH", "NAV-VELNED", "NAV-STATUS", "NAV-DOP", "NAV-SOL", "NAV-TIMEUTC",
                "NAV-SAT", "NAV-SVINFO", "MON-HW", "NAV-EOE"]
{rates}
"""

# t 10-40 s: wideband jammer ramping 20 -> 45 dB J/S (3D, 2D, then no fix,
# back after it stops); 45-65 s: PRN 08 +40 m (FDE); 70-95 s: drag-off
# spoofer 3 m/s toward 045.
SCENARIO = """[[event]]
type = "jammer"
start_s = 10
duration_s = 30
js_db = [20, 45]

[[event]]
type = "satellite"
prn = {prn}
start_s = 45
duration_s = 20
bias_m = 40

[[event]]
type = "spoofer"
mode = "drag"
start_s = 70
duration_s = 25
power_advantage_db = 6
drag_speed_m_s = 3
drag_heading_deg = 45
"""

UBX_NAMES = {(0x01, 0x07): "NAV-PVT", (0x01, 0x02): "NAV-POSLLH", (0x01, 0x12): "NAV-VELNED",
             (0x01, 0x03): "NAV-STATUS", (0x01, 0x04): "NAV-DOP", (0x01, 0x06): "NAV-SOL",
             (0x01, 0x21): "NAV-TIMEUTC", (0x01, 0x35): "NAV-SAT", (0x01, 0x30): "NAV-SVINFO",
             (0x0A, 0x09): "MON-HW", (0x01, 0x61): "NAV-EOE"}
EOE = (0x01, 0x61)
PVT = (0x01, 0x07)


def trajectory():
    """(tow_s, lat, lon, h, ve, vn, vu) at 1 Hz: 10 s parked, then a car
    accelerating east at 1 m/s^2 to 15 m/s, turning north on a 200 m arc."""
    m_per_deg_lat = 111_200.0
    m_per_deg_lon = m_per_deg_lat * 0.6578  # cos(48.87 deg)
    e = n = 0.0
    out = []
    for k in range(DURATION_S + 1):
        t = float(k)
        speed = min(max(t - 10.0, 0.0), 15.0)
        heading = 90.0 - min(max(t - 40.0, 0.0) * speed / 200.0 * 57.2958, 90.0)  # deg from north
        ve = speed * math.sin(math.radians(heading))
        vn = speed * math.cos(math.radians(heading))
        out.append((TOW0_S + t, LAT0_DEG + n / m_per_deg_lat, LON0_DEG + e / m_per_deg_lon, H0_M, ve, vn, 0.0))
        e += ve
        n += vn
    return out


def write_truth_csv(path, rows):
    with open(path, "w") as f:
        f.write("gps_week,tow_s,lat_deg,lon_deg,height_m,ve_m_s,vn_m_s,vu_m_s\n")
        for tow, lat, lon, h, ve, vn, vu in rows:
            # repr: the shortest text that reads back as the same double, in CSV and JSON alike
            f.write(f"{WEEK},{tow!r},{lat!r},{lon!r},{h!r},{ve!r},{vn!r},{vu!r}\n")


def packets(rows):
    for tow, lat, lon, h, ve, vn, vu in rows:
        yield json.dumps({"version": 1, "vehicle": "ego", "sim_time_s": tow - TOW0_S,
                          "gps_week": WEEK, "gps_tow_s": tow,
                          "lla": {"lat_deg": lat, "lon_deg": lon, "height_m": h},
                          "vel_enu": {"e_m_s": ve, "n_m_s": vn, "u_m_s": vu}}, allow_nan=False).encode()


def split(data, what):
    """Messages of a NMEA+UBX byte stream in order: (kind, key, bytes); kind
    'ubx' (key (class, id)) or 'nmea' (key the sentence's address)."""
    out = []
    i = 0
    while i < len(data):
        if data[i:i + 2] == b"\xb5\x62":
            if i + 8 > len(data):
                raise SystemExit(f"{what}: truncated UBX frame at byte {i}")
            n = struct.unpack_from("<H", data, i + 4)[0]
            out.append(("ubx", (data[i + 2], data[i + 3]), data[i:i + 8 + n]))
            i += 8 + n
        elif data[i:i + 1] == b"$":
            j = data.find(b"\r\n", i)
            if j < 0:
                raise SystemExit(f"{what}: unterminated NMEA sentence at byte {i}")
            out.append(("nmea", data[i + 1:data.find(b",", i)].decode(), data[i:j + 2]))
            i = j + 2
        else:
            raise SystemExit(f"{what}: byte {i} (0x{data[i]:02x}) starts neither a UBX frame nor an NMEA sentence")
    return out


def epochs(messages, what):
    """Messages grouped into epochs, each closed by NAV-EOE: [(iTOW ms, [messages])]."""
    out, cur = [], []
    for m in messages:
        cur.append(m)
        if m[0] == "ubx" and m[1] == EOE:
            out.append((struct.unpack_from("<I", m[2], 6)[0], cur))
            cur = []
    if cur and any(m[0] == "ubx" for m in cur):
        raise SystemExit(f"{what}: {len(cur)} message(s) after the last NAV-EOE")
    return out


def ubx_diff(a, b):
    """Where two frames of one message differ: payload offsets and values."""
    pa, pb = a[6:-2], b[6:-2]
    if len(pa) != len(pb):
        return f"payload {len(pa)} B against {len(pb)} B"
    offs = [k for k in range(len(pa)) if pa[k] != pb[k]]
    return f"payload offsets {offs[:12]}{' ...' if len(offs) > 12 else ''}: {pa.hex()} against {pb.hex()}"


def compare(daemon_epochs, batch_ubx, batch_nmea):
    """Problems (empty: identical). batch_* are the batch logs' messages."""
    problems = []
    b_epochs = epochs(batch_ubx, "batch UBX")
    b_tows = [t for t, _ in b_epochs]
    d_by_tow = {}
    for tow, msgs in daemon_epochs:
        if b_tows[0] <= tow <= b_tows[-1]:
            if tow in d_by_tow:
                problems.append(f"daemon: two epochs with iTOW {tow}")
            d_by_tow[tow] = msgs
    if sorted(d_by_tow) != b_tows:
        missing = sorted(set(b_tows) - set(d_by_tow))
        extra = sorted(set(d_by_tow) - set(b_tows))
        problems.append(f"epochs differ: daemon lacks iTOW {missing[:10]}, has extra {extra[:10]}")
        return problems
    # Batch's NMEA log is one stream: walk it with the daemon's epochs.
    b_nmea = [m for m in batch_nmea if m[0] == "nmea"]
    pos = 0
    for tow, b_msgs in b_epochs:
        d_msgs = d_by_tow[tow]
        d_ubx = [m for m in d_msgs if m[0] == "ubx"]
        d_nmea = [m for m in d_msgs if m[0] == "nmea"]
        if [m[1] for m in d_ubx] != [m[1] for m in b_msgs]:
            problems.append(f"iTOW {tow}: UBX messages {[UBX_NAMES.get(m[1]) for m in d_ubx]} "
                            f"against batch {[UBX_NAMES.get(m[1]) for m in b_msgs]}")
        for d, b in zip(d_ubx, b_msgs):
            if d[2] != b[2]:
                problems.append(f"iTOW {tow}: {UBX_NAMES.get(d[1], d[1])} differs: {ubx_diff(d[2], b[2])}")
        b_part = b_nmea[pos:pos + len(d_nmea)]
        pos += len(d_nmea)
        for d, b in zip(d_nmea, b_part):
            if d[2] != b[2]:
                problems.append(f"iTOW {tow}: NMEA {d[2]!r} against batch {b[2]!r}")
        if len(b_part) != len(d_nmea):
            problems.append(f"iTOW {tow}: batch's NMEA log ends inside this epoch")
    if pos != len(b_nmea):
        problems.append(f"batch's NMEA log has {len(b_nmea) - pos} sentence(s) after the compared epochs")
    return problems


def visible_prn(gnssemu, nav):
    """A satellite high in the sky at the start, for the bias step."""
    out = subprocess.run([gnssemu, "sky", "--nav", nav, "--week", str(WEEK), "--tow", str(TOW0_S + 45),
                          "--lat", str(LAT0_DEG), "--lon", str(LON0_DEG), "--height", str(H0_M), "--mask", "30"],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    rows = [dict(zip(out[0].split(","), r.split(","))) for r in out[1:]]
    return int(max(rows, key=lambda r: float(r["el_deg"]))["prn"])


class Rig(RigBase):
    def __init__(self):
        super().__init__("gnssemu-lockstep-")
        self.daemon = None


def run(args, rig, case):
    rate = 1.0 if case == "scenario" else 5.0
    rates = "" if case == "scenario" else "rates = { NAV-SAT = 5, NAV-SVINFO = 5, GSV = 5, MON-HW = 2 }"
    demo = "false" if case == "scenario" else "true"
    rows = trajectory()
    truth = os.path.join(rig.tmp, "truth.csv")
    write_truth_csv(truth, rows)
    scen = None
    if case == "scenario":
        scen = os.path.join(rig.tmp, "scenario.toml")
        with open(scen, "w") as f:
            f.write(SCENARIO.format(prn=visible_prn(args.gnssemu, args.nav)))

    def config(name, seed, port, out):
        path = os.path.join(rig.tmp, name)
        with open(path, "w") as f:
            f.write(CONFIG.format(lat=LAT0_DEG, lon=LON0_DEG, h=H0_M, nav=args.nav, rate=rate, seed=seed, port=port,
                                  demo=demo, out=out, rates=rates))
        return path

    def batch(cfg, tag):
        nmea, ubx = os.path.join(rig.tmp, tag + ".nmea"), os.path.join(rig.tmp, tag + ".ubx")
        argv = [args.gnssemu, "batch", "--config", cfg, "--truth", truth, "--nmea", nmea, "--ubx", ubx]
        if scen:
            argv += ["--scenario", scen]
        subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
        return split(open(ubx, "rb").read(), tag + ".ubx"), split(open(nmea, "rb").read(), tag + ".nmea")

    port = free_port(socket.SOCK_DGRAM)
    out = os.path.join(rig.tmp, "daemon.out")
    cfg = config("c.toml", args.seed, port, out)
    t_batch = time.monotonic()
    b_ubx, b_nmea = batch(cfg, "batch")
    t_batch = time.monotonic() - t_batch
    if args.daemon_seed_offset:  # by hand: the comparison must fail
        cfg = config("d.toml", args.seed + args.daemon_seed_offset, port, out)

    argv = [args.gnssemud, "-c", cfg, "--status-port", "0"]
    if scen:
        argv += ["--scenario", scen]
    log = open(os.path.join(rig.tmp, "gnssemud.log"), "w")
    rig.daemon = rig.spawn(argv, stdout=log, stderr=subprocess.STDOUT)
    last_tow_ms = round(rows[-1][0] * 1000)
    # Ready once the file port is open and the no-truth epochs run; with the
    # demo, once it has a fix: the first packet must restart the chip's ttff.
    deadline = time.monotonic() + 20

    def ready():
        if not (os.path.exists(out) and os.path.getsize(out) > 0):
            return False
        if demo == "false":
            return True
        data = open(out, "rb").read()
        data = data[:data.rfind(b"\xb5\x62\x01\x61")]  # whole epochs only
        return any(m[1] == PVT and m[2][6 + 20] == 3 for m in split(data, "daemon output"))

    while not ready():
        if rig.daemon.poll() is not None or time.monotonic() > deadline:
            raise SystemExit("gnssemud did not start writing its output" + (" with a demo fix" if demo == "true" else ""))
        time.sleep(0.05)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    t_send = time.monotonic()
    for i, p in enumerate(packets(rows)):
        sock.sendto(p, ("127.0.0.1", port))
        if i % 20 == 19:
            time.sleep(0.005)  # keep within the socket buffer; lockstep emits as packets arrive
    # Until the epoch of the last packet is in the file.
    tail = struct.pack("<BBH", 0x01, 0x61, 4) + struct.pack("<I", last_tow_ms)
    while tail not in open(out, "rb").read():
        if rig.daemon.poll() is not None or time.monotonic() > deadline + 30:
            raise SystemExit(f"the daemon never wrote the epoch of the last packet (iTOW {last_tow_ms})")
        time.sleep(0.02)
    t_send = time.monotonic() - t_send
    rc = rig.stop_all()
    log.close()
    if rc != 0:
        raise SystemExit(f"gnssemud exited {rc}")
    text = open(os.path.join(rig.tmp, "gnssemud.log")).read()
    if f"truth: {len(rows)} packets accepted, 0 dropped" not in text:
        raise SystemExit(f"gnssemud did not take all {len(rows)} packets (see its log)")

    d_epochs = epochs(split(open(out, "rb").read(), "daemon output"), "daemon output")
    problems = compare(d_epochs, b_ubx, b_nmea)
    n_epochs = len(epochs(b_ubx, "batch UBX"))
    if problems:
        print(f"FAIL {case}: lockstep and batch differ in {len(problems)} place(s):")
        for p in problems[:40]:
            print("  " + p)
        return 1
    types = "".join(str(m[2][6 + 20]) for m in b_ubx if m[1] == PVT)
    runs = []
    for ch in types:
        if runs and runs[-1][0] == ch:
            runs[-1][1] += 1
        else:
            runs.append([ch, 1])
    print(f"{case}: {n_epochs} epochs at {rate:g} Hz identical ({sum(len(m[2]) for m in b_ubx)} UBX + "
          f"{sum(len(m[2]) for m in b_nmea)} NMEA bytes; NAV-PVT fixType x epochs: "
          f"{' '.join(f'{c}x{n}' for c, n in runs)}); batch {t_batch:.2f} s, lockstep {t_send:.2f} s "
          f"for {len(rows)} packets")

    # The comparison can fail: another seed must show up.
    cfg2 = config("c2.toml", args.seed + 1, port, out)
    o_ubx, o_nmea = batch(cfg2, "other")
    if not compare(d_epochs, o_ubx, o_nmea):
        print(f"FAIL {case}: seed {args.seed + 1} gave the same bytes as seed {args.seed}: the comparison sees nothing")
        return 1
    print(f"{case}: seed {args.seed + 1} in batch differs, as it must")
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--seed", type=int, default=11)
    ap.add_argument("--daemon-seed-offset", type=int, default=0, help="run the daemon on another seed (must fail)")
    ap.add_argument("case", choices=["scenario", "plain"])
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
