#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemud's raw data on its ports, read by programs nobody here wrote
(docs/raw-output.md).

gnssemud runs a raw-data NEO-M9N (`[receiver] raw_data = true`) in Tokyo,
where BeiDou's GEOs are up, at 1 Hz on its demo truth, with RXM-RAWX and
RXM-SFRBX on two ports: a file and a pty that a private gpsd reads.
- RTKLIB `convbin -r ubx` turns the file into RINEX 3.04: an observation
  epoch per RAWX with the same satellites, and ephemerides of GPS, GLONASS,
  Galileo, BeiDou (MEO/IGSO from D1, a GEO from D2) and QZSS that give the
  input nav file's satellite positions within 1 mm (`gnssemu satpos`).
- gpsd decodes the pty's RAWX: each of its RAW reports holds the
  satellites and pseudoranges (to 1 mm) of one of the file's RAWX epochs,
  and its log has no UBX complaint; it reports the fix (TPV mode 3).
Exit 77 (skip) without gpsd, gpspipe or convbin."""
import argparse
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, run_rig  # noqa: E402
from raw_convbin_integration import compare_navs, rawx_epochs, rinex_obs  # noqa: E402
from ubx_host import split_stream  # noqa: E402

ORIGIN = (35.6812, 139.7671, 40.0)  # Tokyo: BeiDou GEOs in view
START = "2024-01-10T02:00:00"       # inside the IGS cut's coverage
WEEK, TOW0 = 2296, 266400.0         # the same instant, GPS week and tow
RUN_S = 48                          # from 02:00 GPST the GEOs' first whole D2 page cycle ends at +44.6 s
RXM_RAWX, RXM_SFRBX = (0x02, 0x15), (0x02, 0x13)
MESSAGES = '["NAV-PVT", "RXM-RAWX", "RXM-SFRBX"]'

CONFIG = """[origin]
lat_deg = {lat}
lon_deg = {lon}
height_m = {h}
[time]
start = "{start}"
[nav]
file = "{nav}"
[receiver]
generation = "m9"
rate_hz = 1.0
seed = 9
raw_data = true
[truth]
port = {udp}
[[output]]
name = "raw"
type = "file"
path = "{dir}/raw.ubx"
protocols_out = ["ubx"]
ubx_messages = {msgs}
[[output]]
name = "gpsd"
type = "pty"
path = "{dir}/gps0"
baud = 115200
ubx_messages = {msgs}
"""


class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-rawd-")
        self.args = args
        self.others = []  # gpspipe JSON objects other than TPV

    def start(self):
        cfg = os.path.join(self.tmp, "c.toml")
        with open(cfg, "w") as f:
            f.write(CONFIG.format(lat=ORIGIN[0], lon=ORIGIN[1], h=ORIGIN[2], start=START,
                                  nav=os.path.abspath(self.args.nav), udp=free_port(socket.SOCK_DGRAM),
                                  dir=self.tmp, msgs=MESSAGES))
        self.daemon_log = open(os.path.join(self.tmp, "gnssemud.log"), "w")
        self.daemon = self.spawn([self.args.gnssemud, "--config", cfg], stdout=subprocess.DEVNULL,
                                 stderr=self.daemon_log)
        pty = os.path.join(self.tmp, "gps0")
        deadline = time.monotonic() + 15
        while not os.path.exists(pty) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert os.path.exists(pty), "no pty"
        self.watch_gpsd(self.spawn_gpsd(pty).stdout, lambda _t, m: self.others.append(m))


def body(rig):
    rig.start()
    rig.wait_mode(lambda mode: mode == 3, 30, "3D fix from gpsd")
    time.sleep(RUN_S)
    rc = rig.stop_all()
    assert rc == 0, f"gnssemud exit {rc}"
    failures = []
    data = open(os.path.join(rig.tmp, "raw.ubx"), "rb").read()
    frames = [m for kind, m in split_stream(data)[0] if kind == "ubx"]
    n_rawx = sum(1 for m in frames if (m[2], m[3]) == RXM_RAWX)
    sfrbx_geo = sum(1 for m in frames if (m[2], m[3]) == RXM_SFRBX and m[6] == 3 and (m[7] <= 5 or m[7] >= 59))
    print(f"file: {len(data)} bytes, {n_rawx} RAWX, {sfrbx_geo} SFRBX of BeiDou GEOs")

    # convbin: observations per RAWX, ephemerides against the input's.
    obs, nav = os.path.join(rig.tmp, "o.obs"), os.path.join(rig.tmp, "o.nav")
    r = subprocess.run(["convbin", "-r", "ubx", "-v", "3.04", "-od", "-os", "-o", obs, "-n", nav,
                        os.path.join(rig.tmp, "raw.ubx")], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and os.path.exists(obs) and os.path.exists(nav), r.stderr
    raw = {t: meas for t, meas in rawx_epochs(data).items() if meas}  # convbin writes no empty epoch
    epochs = rinex_obs(obs)
    sats_raw = {round(((w - 2190) * 604800 + tow) * 1e3): {s for s, _b in meas} for (w, tow), meas in raw.items()}
    mismatched = 0
    for t, sats in epochs:
        if set(sats) != sats_raw.get(round(t * 1e3), set()):
            mismatched += 1
    print(f"convbin: {len(epochs)} observation epochs for {len(raw)} RAWX epochs, {mismatched} with other satellites")
    if len(epochs) != len(raw) or len(raw) < RUN_S or mismatched:
        failures.append(f"convbin: {len(epochs)} epochs for {len(raw)} RAWX, {mismatched} mismatched")
    t_first = min(raw)  # (week, tow) of the first RAWX
    nc = compare_navs(rig.args.gnssemu, nav, os.path.abspath(rig.args.nav), t_first[0],
                      [t_first[1] + dt for dt in range(10, RUN_S + 10, 10)])
    matched, worst, geo, systems = nc["matched"], nc["worst_m"], nc["geo"], set(nc["per_system"])
    print(f"navigation: {matched} states compared (systems {','.join(sorted(systems))}; {geo} BeiDou GEO), "
          f"largest position difference {worst:.4f} m")
    if worst > 0.001 or matched == 0:
        failures.append(f"decoded ephemerides differ by {worst:.4f} m ({matched} compared)")
    if not set("GRECJ") <= systems:
        failures.append("no ephemeris decoded for " + ",".join(sorted(set("GRECJ") - systems)))
    if geo == 0:
        failures.append("no BeiDou GEO ephemeris decoded")

    # gpsd on the pty: RAW reports from RAWX, no UBX complaints.
    raws = [m for m in rig.others if m.get("class") == "RAW"]
    n_meas = [len(m.get("rawdata", [])) for m in raws]
    # Every RAW report is one of the RAWX epochs the file holds (the same
    # epochs go to both ports): gpsd's pseudoranges by (gnssId, svId, sigId).
    by_epoch = []
    for m in frames:
        if (m[2], m[3]) != RXM_RAWX:
            continue
        pl = m[6:-2]
        by_epoch.append({(pl[16 + 32 * i + 20], pl[16 + 32 * i + 21], pl[16 + 32 * i + 22]):
                         struct.unpack_from("<d", pl, 16 + 32 * i)[0] for i in range(pl[11])})
    unmatched = 0
    for m in raws:
        # gpsd numbers SBAS (gnssid 1) PRN 120-158 as svid 20-58 (seen in its RAW reports).
        got = {(x["gnssid"], x["svid"] + (100 if x["gnssid"] == 1 and x["svid"] < 100 else 0), x.get("sigid", 0)):
               x["pseudorange"] for x in m.get("rawdata", [])}
        if not any(e.keys() == got.keys() and all(abs(e[k] - v) < 1e-3 for k, v in got.items()) for e in by_epoch):
            unmatched += 1
    log = open(os.path.join(rig.tmp, "gpsd.log"), errors="replace").read()
    complaints = [l for l in log.splitlines() if "UBX" in l and ("error" in l.lower() or "bad" in l.lower()
                                                                   or "unknown" in l.lower())]
    print(f"gpsd: {len(raws)} RAW reports, measurements per report {min(n_meas, default=0)}-{max(n_meas, default=0)}, "
          f"{unmatched} not equal to a RAWX epoch, {len(complaints)} UBX complaints in its log")
    if len(raws) < RUN_S // 2 or min(n_meas, default=0) < 20:
        failures.append(f"gpsd: {len(raws)} RAW reports, {min(n_meas, default=0)} measurements at least")
    if unmatched:
        failures.append(f"gpsd: {unmatched} RAW reports whose pseudoranges are no RAWX epoch's")
    if complaints:
        failures.append("gpsd complained: " + complaints[0])
    assert not failures, "; ".join(failures)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    args = ap.parse_args()
    for tool in ("gpsd", "gpspipe", "convbin"):
        if shutil.which(tool) is None:
            print(f"SKIP: {tool} not installed")
            return 77
    return run_rig(Rig(args), body, 120)


if __name__ == "__main__":
    sys.exit(main())
