#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The base station's RTCM 3 decoded by RTKLIB (docs/base-station.md).

`gnssemu base` runs the reference receiver for a minute and writes its RTCM
stream (MSM4 or MSM7, 1005, 1230, ephemerides), the raw observations it
encoded and the ephemerides it sent. RTKLIB's convbin decodes the stream to
RINEX; every observation must equal the RawEpoch value moved to the
millisecond epoch, within the MSM field resolution (carrier phase up to a
whole-cycle offset constant per satellite), and the navigation file must hold
the ephemerides sent, within the RTCM scale factors.

Exit 77 (CTest skip) when convbin is not installed.
"""
import argparse
import collections
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile

C = 299792458.0
CARRIER = {("G", "1C"): 1575.42e6, ("E", "1C"): 1575.42e6, ("J", "1C"): 1575.42e6, ("C", "2I"): 1561.098e6,
           ("G", "2L"): 1227.60e6, ("E", "7Q"): 1207.14e6, ("C", "7I"): 1207.14e6, ("J", "2L"): 1227.60e6}
# MSM field resolutions (rtk-raw.md §2.4): pseudorange, phase-range (m), rate (m/s), C/N0 (dB-Hz).
RES = {7: (C * 1e-3 * 2**-29, C * 1e-3 * 2**-31, 1e-4, 2**-4), 4: (C * 1e-3 * 2**-24, C * 1e-3 * 2**-29, None, 1.0)}


def read_rinex_obs(path):
    """{(tow_ms, sat, type): value} and the types per system."""
    types, obs = {}, {}
    with open(path) as f:
        for line in f:
            if "SYS / # / OBS TYPES" in line:
                types[line[0]] = line[7:58].split()
            if "END OF HEADER" in line:
                break
        tow_ms = None
        for line in f:
            if line.startswith(">"):
                p = line[1:].split()
                h, m, s = int(p[3]), int(p[4]), float(p[5])
                day = (int(p[2]) - 7) % 7  # 2024-01-07 was a Sunday; enough within one week
                tow_ms = round(((day * 24 + h) * 60 + m) * 60000 + s * 1000)
                continue
            sat = line[:3]
            for i, t in enumerate(types.get(sat[0], [])):
                field = line[3 + 16 * i: 3 + 16 * i + 14]
                if field.strip():
                    obs[(tow_ms, sat, t)] = float(field)
    return obs, types


def read_rinex_nav(path):
    """{(sat, toe_tow or tb): [values]} of the Kepler sets and GLONASS states."""
    sets = {}
    with open(path) as f:
        for line in f:
            if "END OF HEADER" in line:
                break
        lines = f.read().splitlines()
    i = 0
    while i < len(lines):
        sat = lines[i][:3]
        n = {"R": 4, "S": 4}.get(sat[0], 8)
        block = lines[i:i + n]
        i += n
        vals = []
        for k, l in enumerate(block):
            text = l[23:] if k == 0 else l[4:]
            for j in range(0, len(text), 19):
                v = text[j:j + 19].strip()
                if v:
                    vals.append(float(v.replace("D", "E")))
        sets.setdefault(sat, []).append(vals)
    return sets


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--msm", type=int, choices=(4, 7), default=7)
    ap.add_argument("--keep", help="keep the files in this folder")
    ap.add_argument("--bands", type=int, choices=(1, 2), default=1, help="[receiver] bands of the base")
    a = ap.parse_args()
    if shutil.which("convbin") is None:
        print("convbin not installed (Debian rtklib)")
        return 77
    d = a.keep or tempfile.mkdtemp()
    os.makedirs(d, exist_ok=True)
    m = a.msm
    # The configuration with every system the MSMs carry (an M8 tracks GPS and GLONASS by default);
    # two bands: a ZED-F9P (the M8 and M9 track L1 only).
    with open(a.config) as f:
        text = f.read()
    cfg = f"{d}/base.toml"
    chip = 'generation = "f9p"\n' if a.bands > 1 else ""
    with open(cfg, "w") as f:
        f.write(text.replace("[receiver]\n", f'[receiver]\nconstellations = ["G", "R", "E", "C"]\n{chip}bands = {a.bands}\n', 1)
                .replace('file = "nav/', f'file = "{os.path.dirname(os.path.abspath(a.config))}/nav/'))
    msgs = f"1005(10),107{m}(1),108{m}(1),109{m}(1),112{m}(1),1230(10),1019(30),1020(30),1042(30),1046(30)"
    run = [a.gnssemu, "base", "--config", cfg, "--lat", "48.88", "--lon", "2.30", "--height", "100",
           "--station-id", "42", "--messages", msgs, "--week", "2296", "--tow", "302400", "--duration", "60",
           "--out", f"{d}/b.rtcm3", "--raw-csv", f"{d}/raw.csv", "--eph-csv", f"{d}/eph.csv"]
    print(" ".join(run))
    r = subprocess.run(run, capture_output=True, text=True)
    print(r.stderr.strip())
    if r.returncode != 0:
        return 1
    conv = ["convbin", "-r", "rtcm3", "-tr", "2024/01/10 12:00:00", "-v", "3.04", "-od", "-os", "-o", f"{d}/b.obs", "-n", f"{d}/b.nav",
            f"{d}/b.rtcm3"]
    print(" ".join(conv))
    subprocess.run(conv, capture_output=True, text=True, check=True)
    obs, types = read_rinex_obs(f"{d}/b.obs")
    res_pr, res_ph, res_rate, res_cn0 = RES[m]
    worst = collections.defaultdict(float)
    offsets = collections.defaultdict(set)
    n = 0
    missing = 0
    systems = set()
    codes = set()
    with open(f"{d}/raw.csv") as f:
        for row in csv.DictReader(f):
            tow = float(row["tow_s"])
            tow_ms = math.floor(tow * 1000 + 0.5)
            dt = tow_ms / 1000 - tow
            sat, code = row["sat"], row["code"]
            if sat[0] == "R":
                continue  # carrier by FDMA channel: checked by pseudorange only
            lam = C / CARRIER[(sat[0], code)]
            dop = float(row["doppler_hz"])
            pr = obs.get((tow_ms, sat, "C" + code))
            if pr is None:
                missing += 1
                continue
            systems.add(sat[0])
            codes.add(sat[0] + code)
            n += 1
            worst["C"] = max(worst["C"], abs(pr - (float(row["pseudorange_m"]) - dop * lam * dt)))
            ph = obs.get((tow_ms, sat, "L" + code))
            if ph is not None:
                diff = ph - (float(row["carrier_cycles"]) - dop * dt)
                offsets[(sat, code)].add(round(diff))
                worst["L"] = max(worst["L"], abs(diff - round(diff)) * lam)
            if res_rate is not None:
                worst["D"] = max(worst["D"], abs(obs[(tow_ms, sat, "D" + code)] - dop) * lam)
            worst["S"] = max(worst["S"], abs(obs[(tow_ms, sat, "S" + code)] - float(row["cn0_dbhz"])))
    # GLONASS: pseudoranges (the channel comes from 1020 or MSM7's extended info).
    with open(f"{d}/raw.csv") as f:
        for row in csv.DictReader(f):
            if row["sat"][0] != "R":
                continue
            tow = float(row["tow_s"])
            tow_ms = math.floor(tow * 1000 + 0.5)
            pr = obs.get((tow_ms, row["sat"], "C" + row["code"]))
            if pr is None:
                missing += 1
                continue
            systems.add("R")
            codes.add("R" + row["code"])
            n += 1
            # The shift is below 0.5 ms: the channel's carrier changes it by < 1e-6 m.
            lam = C / (1602e6 if row["code"] == "1C" else 1246e6)
            worst["C"] = max(worst["C"], abs(pr - (float(row["pseudorange_m"]) - float(row["doppler_hz"]) * lam * (tow_ms / 1000 - tow))))
    print(f"{n} observations of {sorted(systems)} compared, {missing} not in the RINEX file; worst |diff|: "
          + ", ".join(f"{k} {v:.6f}" for k, v in sorted(worst.items()))
          + f" (resolution: code {res_pr:.6f} m, phase {res_ph:.6f} m)")
    print("signals: " + " ".join(sorted(codes)))
    ok = n > 0 and missing == 0 and systems == {"G", "R", "E", "C"}
    if a.bands > 1:
        ok &= {"G2L", "R2C", "E7Q", "C7I"} <= codes
    ok &= worst["C"] <= res_pr / 2 + 1e-3
    ok &= worst["L"] <= res_ph / 2 + 1e-3
    if res_rate is not None:
        ok &= worst["D"] <= res_rate / 2 + 1e-3
    ok &= worst["S"] <= res_cn0 / 2 + 0.006  # the CSV's 0.01 dB-Hz and RINEX's 0.001
    jumps = {s: sorted(o) for s, o in offsets.items() if len(o) > 1}
    if jumps:
        print("carrier-phase offset changed within a lock:", jumps)
        ok = False
    # Navigation: every decoded set is one the base sent (RTKLIB keeps the
    # latest set per satellite), within the RTCM scale factors.
    nav = read_rinex_nav(f"{d}/b.nav")
    sent = collections.defaultdict(list)
    with open(f"{d}/eph.csv") as f:
        for row in csv.DictReader(f):
            sent[row["sat"]].append(row)
    kepler = {"sqrt_a": (10, 2**-19), "e": (8, 2**-33), "m0": (6, math.pi * 2**-31), "omega0": (13, math.pi * 2**-31),
              "i0": (15, math.pi * 2**-31), "omega": (17, math.pi * 2**-31), "af0": (0, 2**-31)}
    eph_n, eph_bad = 0, []
    for sat, rows in sent.items():
        if sat not in nav:
            eph_bad.append(sat + " missing")
            continue
        for got in nav[sat]:
            eph_n += 1
            if sat[0] == "R":
                err = min(max(abs(got[3 + 4 * k] * 1e3 - float(r[f"pos_{x}_m"])) for k, x in enumerate("xyz"))
                          for r in rows)
                if err > 0.5:  # 2^-11 km
                    eph_bad.append(f"{sat} position off by {err:.3f} m")
                continue
            match = [r for r in rows if abs(got[11] - float(r["toe_tow_s"]) + (14 if sat[0] == "C" else 0)) < 1]
            if not match:
                eph_bad.append(f"{sat} toe {got[11]} not sent")
                continue
            for k, (i, res) in kepler.items():
                if abs(got[i] - float(match[0][k])) > res:
                    eph_bad.append(f"{sat} {k} {got[i]} != {match[0][k]}")
    print(f"{eph_n} ephemerides compared; {len(eph_bad)} differ: {eph_bad[:5]}")
    ok &= eph_n > 0 and not eph_bad
    print("PASS" if ok else "FAIL")
    if not a.keep:
        shutil.rmtree(d, ignore_errors=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
