#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemu's raw data read by programs nobody here wrote (docs/raw-output.md).

`gnssemu batch` runs a raw-data chip ([receiver] raw_data = true) with
RXM-RAWX and RXM-SFRBX on; then
- RTKLIB `convbin -r ubx` turns the UBX log into RINEX 3.04 observation and
  navigation files. Every ephemeris it rebuilt from our SFRBX subframes gives
  the same satellite positions and clocks (`gnssemu satpos` on both files, at
  several times, same toe and IODE) as the nav file the run used, to the
  print resolution (0.1 mm, 1e-15 s); every system tracked has sets. Every
  observation equals the RXM-RAWX value of the same epoch and satellite to
  RINEX's resolution (pseudorange, phase, Doppler 0.001; C/N0 1 dB-Hz); the
  RAWX fields are the receiver's RawEpoch as is (R8 pseudorange and phase,
  unit-tested field by field in test_ubx).
- gpsd's `gpsdecode` decodes every RAWX and every LNAV subframe: a SUBFRAME
  report per SFRBX subframe means gpsd's IS-GPS-200 parity check passed.
Exit 77 (skip) without convbin or gpsdecode."""
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
lat_deg = {lat}
lon_deg = {lon}
height_m = 100.0
[nav]
file = "{nav}"
[receiver]
rate_hz = 1.0
seed = 5
raw_data = true
{extra}
[[output]]
name = "log"
type = "pty"
path = "/tmp/gnssemu-raw-it/gps0"
ubx_messages = ["NAV-PVT", "RXM-RAWX", "RXM-SFRBX"]
protocols_out = ["ubx"]
"""

# The RINEX code of each system's L1-band signal (core/common/gnss_signals.hpp);
# any other code of the system is its second frequency.
BAND0_CODE = {"G": "1C", "R": "1C", "E": "1C", "C": "2I", "J": "1C", "S": "1C"}

RXM_RAWX = (0x02, 0x15)
RXM_SFRBX = (0x02, 0x13)
LETTER = {0: "G", 1: "S", 2: "E", 3: "C", 5: "J", 6: "R"}


def rawx_epochs(data):
    """{(week, rcvTow): {("G05", band): (pr, cp, do, cno, trk)}} from the RXM-RAWX frames (band 0: the
    L1-band signal, UBX sigId 0 or 1; 1: the second frequency)."""
    out = {}
    for kind, m in split_stream(data)[0]:
        if kind != "ubx" or (m[2], m[3]) != RXM_RAWX:
            continue
        p = m[6:-2]
        tow, week, _, n = struct.unpack_from("<dHbB", p, 0)
        meas = {}
        for i in range(n):
            pr, cp, do, gnss, sv, sig, _, _, cno, _, _, _, trk = struct.unpack_from("<ddfBBBBHBBBBB", p, 16 + 32 * i)
            num = sv - 192 if gnss == 5 and sv > 192 else sv - 100 if gnss == 1 else sv  # RINEX J01, S20
            meas[("%s%02d" % (LETTER[gnss], num), 0 if sig <= 1 else 1)] = (pr, cp, do, cno, trk)
        out[(week, tow)] = meas
    return out


def rinex_obs(path):
    """[(seconds of GPS week, {"G05": {"C1C": v, ...}})] from a RINEX 3 observation file."""
    types, epochs, cur = {}, [], None
    with open(path) as f:
        lines = f.read().splitlines()
    i = 0
    while "END OF HEADER" not in lines[i]:
        if lines[i][60:].startswith("SYS / # / OBS TYPES") and lines[i][0] != " ":
            types[lines[i][0]] = lines[i][7:58].split()
        i += 1
    for line in lines[i + 1:]:
        if line.startswith(">"):
            y, mo, d, h, mi = (int(x) for x in line[2:18].split())
            sec = float(line[18:29])
            # Seconds since the GPS week 2190 start (2021-12-26): the runs here are short.
            t = datetime.datetime(y, mo, d, h, mi) - datetime.datetime(2021, 12, 26)
            cur = {}
            epochs.append((t.total_seconds() + sec, cur))
        elif cur is not None and len(line) > 3:
            sat = line[:3]
            vals = {}
            for k, name in enumerate(types[sat[0]]):
                field = line[3 + 16 * k:3 + 16 * k + 14].strip()
                if field:
                    vals[name] = float(field)
            cur[sat] = vals
    return epochs


def satpos(gnssemu, nav, week, tow):
    r = subprocess.run([gnssemu, "satpos", "--nav", nav, "--week", str(week), "--tow", str(tow)],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    rows = r.stdout.splitlines()
    head = rows[0].split(",")
    return {row.split(",")[0]: dict(zip(head, row.split(","))) for row in rows[1:]}


def is_beidou_geo(sat):
    return sat[0] == "C" and (int(sat[1:]) <= 5 or int(sat[1:]) >= 59)


def compare_navs(gnssemu, decoded, reference, week, tows):
    """Satellite states of the decoded nav file against the reference's at
    each tow (same toe and IODE only): {"matched", "worst_m", "worst_clk_s",
    "geo" (BeiDou GEO states), "per_system" {letter: (states, worst m)}}."""
    out = {"matched": 0, "worst_m": 0.0, "worst_clk_s": 0.0, "geo": 0, "per_system": {}}
    for tow in tows:
        a = satpos(gnssemu, decoded, week, tow)
        b = satpos(gnssemu, reference, week, tow)
        for sat, row in a.items():
            ref = b.get(sat)
            if ref is None or ref["toe_tow_s"] != row["toe_tow_s"] or ref["iode"] != row["iode"]:
                continue
            d = max(abs(float(row[c]) - float(ref[c])) for c in ("x_m", "y_m", "z_m"))
            out["worst_m"] = max(out["worst_m"], d)
            out["worst_clk_s"] = max(out["worst_clk_s"], abs(float(row["clk_bias_s"]) - float(ref["clk_bias_s"])))
            out["geo"] += is_beidou_geo(sat)
            n, w = out["per_system"].get(sat[0], (0, 0.0))
            out["per_system"][sat[0]] = (n + 1, max(w, d))
            out["matched"] += 1
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--week", type=int, default=2190)
    ap.add_argument("--tow", type=float, default=522000.0)
    ap.add_argument("--seconds", type=int, default=120)
    ap.add_argument("--systems", default="G", help="RINEX letters whose ephemerides must come back")
    ap.add_argument("--obs-systems", default="G", help="RINEX letters whose observations must come back")
    ap.add_argument("--extra", default="", help="more [receiver] lines")
    ap.add_argument("--bands", type=int, default=1, help="signals per satellite that must come back")
    ap.add_argument("--lat", type=float, default=48.8738, help="receiver latitude, deg")
    ap.add_argument("--lon", type=float, default=2.295, help="receiver longitude, deg")
    ap.add_argument("--need-geo", action="store_true", help="BeiDou GEO phases and D2 ephemerides must be among those compared")
    args = ap.parse_args()
    for tool in ("convbin", "gpsdecode"):
        if shutil.which(tool) is None:
            print("SKIP: %s not installed" % tool)
            return 77
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        cfg = os.path.join(tmp, "c.toml")
        with open(cfg, "w") as f:
            f.write(CONFIG.format(nav=os.path.abspath(args.nav), extra=args.extra.replace("\\n", "\n"),
                                  lat=args.lat, lon=args.lon))
        truth = os.path.join(tmp, "t.csv")
        with open(truth, "w") as f:
            f.write("gps_week,tow_s,lat_deg,lon_deg,height_m\n%d,%.1f,%.6f,%.6f,100\n%d,%.1f,%.6f,%.6f,100\n"
                    % (args.week, args.tow, args.lat, args.lon, args.week, args.tow + args.seconds, args.lat, args.lon))
        ubx = os.path.join(tmp, "o.ubx")
        own_obs = os.path.join(tmp, "own.obs")
        r = subprocess.run([args.gnssemu, "batch", "--config", cfg, "--truth", truth, "--ubx", ubx,
                            "--rinex-obs", own_obs],
                           capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        data = open(ubx, "rb").read()
        obs, nav = os.path.join(tmp, "o.obs"), os.path.join(tmp, "o.nav")
        r = subprocess.run(["convbin", "-r", "ubx", "-v", "3.04", "-od", "-os", "-o", obs, "-n", nav, ubx],
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 0 and os.path.exists(obs) and os.path.exists(nav), r.stderr

        # Observations: RINEX = RAWX.
        raw = rawx_epochs(data)
        by_t = {}  # by ms: RINEX prints 7 decimals of the receiver's (biased) time
        for (week, tow), meas in raw.items():
            by_t[round(((week - 2190) * 604800 + tow) * 1e3)] = (week - 2190) * 604800 + tow, meas
        compared = 0
        worst = {"C": 0.0, "L": 0.0, "D": 0.0, "S": 0.0}  # by observation kind
        systems_obs = set()
        geo_phases = 0
        signals = set()  # (system, RINEX code) decoded
        for t, sats in rinex_obs(obs):
            hit = by_t.get(round(t * 1e3))
            if hit is None or abs(hit[0] - t) > 1e-7:
                failures.append("RINEX epoch %.7f has no RAWX" % t)
                continue
            meas = hit[1]
            for sat, vals in sats.items():
                for band in (0, 1):
                    mine = {k: v for k, v in vals.items() if (k[1:3] == BAND0_CODE[sat[0]]) == (band == 0)}
                    if not mine:
                        continue
                    if (sat, band) not in meas:
                        failures.append("%s band %d at %.7f not in RAWX" % (sat, band, t))
                        continue
                    pr, cp, do, cno, trk = meas[(sat, band)]
                    if is_beidou_geo(sat) and trk & 2:
                        cp += 0.5  # RTKLIB's "half-cycle shift correction for BDS GEO" (u-blox cpMes)
                        geo_phases += 1
                    want = {"C": pr if trk & 1 else None, "L": cp if trk & 2 else None, "D": do, "S": cno}
                    for k, v in mine.items():
                        if want.get(k[0]) is not None:
                            worst[k[0]] = max(worst[k[0]], abs(v - want[k[0]]))
                        signals.add((sat[0], k[1:3]))
                    systems_obs.add(sat[0])
                    compared += 1
        tol = {"C": 0.0006, "L": 0.0006, "D": 0.0006, "S": 0.5}
        for k, w in worst.items():
            if w > tol[k]:
                failures.append("%s differs from RAWX by %.4f (> %.4f)" % (k, w, tol[k]))
        print("observations: %d signal epochs compared (systems %s; signals %s), largest |RINEX - RAWX|: %s"
              % (compared, ",".join(sorted(systems_obs)), " ".join(sorted(a + b for a, b in signals)),
                 ", ".join("%s %.5f" % kv for kv in worst.items())))
        if args.bands > 1:
            for letter in args.obs_systems:
                if not any(sys_ == letter and code != BAND0_CODE[letter] for sys_, code in signals):
                    failures.append("no second-frequency observations of %s decoded" % letter)
        if args.need_geo and geo_phases == 0:
            failures.append("no BeiDou GEO phase compared")
        # convbin's RINEX against the receiver's own (--rinex-obs): the same phases.
        own = {round(t * 1e3): sats for t, sats in rinex_obs(own_obs)}
        n_own, worst_own = 0, 0.0
        for t, sats in rinex_obs(obs):
            mine = own.get(round(t * 1e3), {})
            for sat, vals in sats.items():
                for k, v in vals.items():
                    if k[0] == "L" and v is not None and mine.get(sat, {}).get(k) is not None:
                        worst_own = max(worst_own, abs(v - mine[sat][k]))
                        n_own += 1
        print("convbin against --rinex-obs: %d phases compared (%d of them BeiDou GEO), largest difference %.4f cycles"
              % (n_own, geo_phases, worst_own))
        if n_own == 0 or worst_own > 0.0015:
            failures.append("convbin's phases differ from --rinex-obs by %.4f cycles (%d compared)" % (worst_own, n_own))
        missing_obs = set(args.obs_systems) - systems_obs
        if missing_obs:
            failures.append("no observations decoded for %s" % ",".join(sorted(missing_obs)))
        if compared < 10 * args.seconds // 2:
            failures.append("only %d satellite epochs decoded" % compared)

        # Navigation: convbin's ephemerides against the input's.
        nc = compare_navs(args.gnssemu, nav, os.path.abspath(args.nav), args.week,
                          [args.tow + dt for dt in range(0, args.seconds + 1, 30)])
        matched, worst_m, worst_clk, geo_states = nc["matched"], nc["worst_m"], nc["worst_clk_s"], nc["geo"]
        per_system = nc["per_system"]
        systems = set(per_system)
        print("navigation: %d satellite states compared (systems %s; %d BeiDou GEO states), largest position "
              "difference %.4f m, clock %.3g s" % (matched, ",".join(sorted(systems)), geo_states, worst_m, worst_clk))
        print("navigation by system: " + ", ".join("%s %d states, %.4f m" % (k, n, w)
                                                  for k, (n, w) in sorted(per_system.items())))
        if worst_m > 0.001:
            failures.append("decoded ephemerides differ by %.4f m (> 1 mm)" % worst_m)
        if worst_clk > 1e-12:
            failures.append("decoded clocks differ by %.3g s" % worst_clk)
        if args.need_geo and geo_states == 0:
            failures.append("no BeiDou GEO ephemeris decoded from the D2 pages")
        missing = set(args.systems) - systems
        if missing:
            failures.append("no ephemeris decoded for %s" % ",".join(sorted(missing)))

        # gpsd: every RAWX and every LNAV subframe decoded.
        dec = subprocess.run(["gpsdecode", "-j", "-D", "5"], input=data, capture_output=True, timeout=60)
        log = dec.stderr.decode(errors="replace")
        reports = [json.loads(l) for l in dec.stdout.decode().splitlines() if l.startswith("{")]
        n_rawx = sum(1 for kind, m in split_stream(data)[0] if kind == "ubx" and (m[2], m[3]) == RXM_RAWX)
        # gpsd 3.22 reads QZSS's LNAV subframes without a SUBFRAME report: GPS's are counted.
        n_gps_sf = sum(1 for kind, m in split_stream(data)[0]
                       if kind == "ubx" and (m[2], m[3]) == RXM_SFRBX and m[6] == 0)
        n_sub = sum(1 for j in reports if j.get("class") == "SUBFRAME")
        n_rawx_dec = log.count("UBX-RXM-RAWX")
        print("gpsd: %d of %d RAWX decoded, %d SUBFRAME reports for %d GPS SFRBX, parity failures %d"
              % (n_rawx_dec, n_rawx, n_sub, n_gps_sf, log.count("parity fail")))
        if n_rawx_dec != n_rawx:
            failures.append("gpsdecode decoded %d of %d RAWX" % (n_rawx_dec, n_rawx))
        if n_sub != n_gps_sf or n_gps_sf == 0 or "parity fail" in log:
            failures.append("gpsdecode: %d SUBFRAME reports for %d subframes" % (n_sub, n_gps_sf))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
