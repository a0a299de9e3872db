#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemu spp against RTKLIB's rnx2rtkp (single point) on real observations.

Both solve the same RINEX observation file with the same broadcast nav file,
the same mask, the same systems (--systems, RINEX letters; default GPS: C1C,
RINEX 2: C1), broadcast Klobuchar and a Saastamoinen troposphere
(docs/validation.md). Compact RINEX observations (.crx, .crx.gz) are decoded
for rnx2rtkp with --rinex-from-crx (the project's own decoder). Prints per-epoch 3D
differences (median, 95th percentile, max, RMS) and each solver's error
against the station (--station, else the obs header's APPROX POSITION XYZ);
fails when a figure exceeds its limit. `compare()` is also used by
tools/validation/spp_vs_rtklib_days.py for every station-day.
Exit 77 (CTest skip) when rnx2rtkp is not installed.
"""
import argparse
import gzip
import math
import os
import shutil
import subprocess
import sys
import tempfile

RTKLIB_CONF = """pos1-posmode       =single
pos1-frequency     =l1
pos1-elmask        ={mask}
pos1-ionoopt       =brdc
pos1-tropopt       =saas
pos1-sateph        =brdc
pos1-navsys        ={navsys}
out-solformat      =xyz
out-timesys        =gpst
out-timeform       =tow
"""


def enu(d, ref):
    x, y, z = ref
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1 - 6.69437999014e-3))
    for _ in range(5):
        n = 6378137.0 / math.sqrt(1 - 6.69437999014e-3 * math.sin(lat) ** 2)
        h = p / math.cos(lat) - n
        lat = math.atan2(z, p * (1 - 6.69437999014e-3 * n / (n + h)))
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    e = -so * d[0] + co * d[1]
    nn = -sl * co * d[0] - sl * so * d[1] + cl * d[2]
    u = cl * co * d[0] + cl * so * d[1] + sl * d[2]
    return e, nn, u


def stats(rows):
    out = {}
    for k, name in enumerate("ENU"):
        v = [r[k] for r in rows]
        m = sum(v) / len(v)
        out[name] = (m, math.sqrt(sum(x * x for x in v) / len(v)))
    return out


# RTKLIB's navigation-system bits (rtklib.h SYS_*).
NAVSYS_BITS = {"G": 1, "R": 4, "E": 8, "J": 16, "C": 32}


def navsys(systems):
    return sum(NAVSYS_BITS[s] for s in systems.split(","))


def plain_copy(path, tmp, rinex_from_crx=None):
    """rnx2rtkp would unpack a .gz next to the original: unpack into tmp instead;
    Compact RINEX is decoded with rinex_from_crx."""
    if path.endswith(".crx") or path.endswith(".crx.gz"):
        if rinex_from_crx is None:
            raise ValueError(f"{path}: Compact RINEX needs --rinex-from-crx")
        out = os.path.join(tmp, os.path.basename(path).split(".crx")[0] + ".rnx")
        with open(out, "w") as f:
            subprocess.run([rinex_from_crx, path], check=True, stdout=f)
        return out
    if not path.endswith(".gz"):
        return path
    out = os.path.join(tmp, os.path.basename(path)[:-3])
    with gzip.open(path, "rb") as f, open(out, "wb") as g:
        shutil.copyfileobj(f, g)
    return out


def header_position(obs):
    """APPROX POSITION XYZ of a RINEX observation header (plain or gzip)."""
    opener = gzip.open if obs.endswith(".gz") else open
    with opener(obs, "rt") as f:
        for line in f:
            if "APPROX POSITION XYZ" in line[60:]:
                return tuple(float(v) for v in line[:60].split()[:3])
            if "END OF HEADER" in line[60:]:
                break
    raise ValueError(f"{obs}: no APPROX POSITION XYZ in the header")


def run_rnx2rtkp(rnx2rtkp, obs, nav, mask, tmp, systems="G", rinex_from_crx=None):
    conf = os.path.join(tmp, "single.conf")
    with open(conf, "w") as f:
        f.write(RTKLIB_CONF.format(mask=mask, navsys=navsys(systems)))
    pos = os.path.join(tmp, "rtk.pos")
    subprocess.run([rnx2rtkp, "-k", conf, "-o", pos, plain_copy(obs, tmp, rinex_from_crx), plain_copy(nav, tmp)],
                   check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rtk = {}
    with open(pos) as f:
        for line in f:
            if line.startswith("%") or not line.strip():
                continue
            c = line.split()
            if c[5] != "5":  # Q = 5: single
                continue
            rtk[(int(c[0]), round(float(c[1]), 1))] = (float(c[2]), float(c[3]), float(c[4]), int(c[6]))
    return rtk


def run_spp(gnssemu, obs, nav, mask, config, preset, systems="G"):
    argv = [gnssemu, "spp", "--obs", obs, "--nav", nav, "--mask", str(mask), "--systems", systems]
    if config:
        argv += ["--config", config]
    if preset:
        argv += ["--preset", preset]
    res = subprocess.run(argv, check=True, capture_output=True, text=True)
    lines = res.stdout.strip().splitlines()
    col = {n: i for i, n in enumerate(lines[0].split(","))}
    ours = {}
    for line in lines[1:]:
        c = line.split(",")
        key = (int(c[col["gps_week"]]), round(float(c[col["tow_s"]]), 1))
        ours[key] = (float(c[col["x_m"]]), float(c[col["y_m"]]), float(c[col["z_m"]]), int(c[col["nsat"]]))
    return ours


def compare(gnssemu, rnx2rtkp, obs, nav, mask=10.0, config=None, preset=None, station=None, systems="G",
            rinex_from_crx=None):
    """Epoch-by-epoch comparison; a dict of counts, difference figures (m) and
    both solvers' E/N/U (mean, RMS) against the station."""
    with tempfile.TemporaryDirectory() as tmp:
        nav = plain_copy(nav, tmp)
        plain_obs = plain_copy(obs, tmp, rinex_from_crx)
        station = station or header_position(plain_obs)
        rtk = run_rnx2rtkp(rnx2rtkp, plain_obs, nav, mask, tmp, systems)
        ours = run_spp(gnssemu, obs, nav, mask, config, preset, systems)
    common = sorted(set(ours) & set(rtk))
    r = {"ours": len(ours), "rtk": len(rtk), "common": len(common)}
    if not common:
        return r
    diffs, e_ours, e_rtk, nsat_diff = [], [], [], 0
    for k in common:
        o, q = ours[k], rtk[k]
        diffs.append(math.sqrt(sum((o[i] - q[i]) ** 2 for i in range(3))))
        e_ours.append(enu([o[i] - station[i] for i in range(3)], station))
        e_rtk.append(enu([q[i] - station[i] for i in range(3)], station))
        nsat_diff += o[3] != q[3]
    s = sorted(diffs)
    r.update(nsat_diff=nsat_diff, median=s[len(s) // 2] if len(s) % 2 else 0.5 * (s[len(s) // 2 - 1] + s[len(s) // 2]),
             p95=s[int(0.95 * (len(s) - 1))], max=s[-1], worst=common[diffs.index(s[-1])],
             rms=math.sqrt(sum(x * x for x in diffs) / len(diffs)), enu_ours=stats(e_ours), enu_rtk=stats(e_rtk))
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--obs", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--mask", type=float, default=10.0)
    ap.add_argument("--config", help="gnssemu config for spp's solver settings (e.g. troposphere mapping)")
    ap.add_argument("--preset", choices=["rtklib"], help="gnssemu spp --preset")
    ap.add_argument("--station", help="X,Y,Z (ECEF m); default: the obs header's APPROX POSITION XYZ")
    ap.add_argument("--systems", default="G", help="RINEX letters of the systems both solve with, e.g. G,R,E,C")
    ap.add_argument("--rinex-from-crx", help="Compact RINEX decoder (build/tools/validation/rinex_from_crx)")
    ap.add_argument("--max-diff", type=float, default=1.5, help="largest allowed per-epoch 3D difference, m")
    ap.add_argument("--p95-diff", type=float, default=0.8, help="largest allowed 95th percentile 3D difference, m")
    ap.add_argument("--rms-diff", type=float, default=0.45, help="largest allowed RMS 3D difference, m")
    ap.add_argument("--median-diff", type=float, default=math.inf, help="largest allowed median 3D difference, m")
    ap.add_argument("--min-common", type=float, default=0.95,
                    help="smallest allowed fraction of epochs both solve (of the larger count)")
    a = ap.parse_args()

    rnx2rtkp = shutil.which("rnx2rtkp")
    if rnx2rtkp is None:
        print("SKIP: rnx2rtkp (Debian package rtklib) is not installed")
        return 77
    station = tuple(float(v) for v in a.station.split(",")) if a.station else None
    r = compare(a.gnssemu, rnx2rtkp, a.obs, a.nav, a.mask, a.config, a.preset, station, a.systems, a.rinex_from_crx)
    if not r["common"]:
        print("FAIL: no common epochs")
        return 1
    print(f"epochs: gnssemu {r['ours']}, rnx2rtkp {r['rtk']}, common {r['common']}, "
          f"different satellite count {r['nsat_diff']}")
    print(f"3D difference gnssemu - rnx2rtkp: median {r['median']:.3f} m, 95th percentile {r['p95']:.3f} m, "
          f"max {r['max']:.3f} m (week {r['worst'][0]} tow {r['worst'][1]}), RMS {r['rms']:.3f} m")
    for name in ("ours", "rtk"):
        label = "gnssemu" if name == "ours" else "rnx2rtkp"
        print(f"{label:9s} error vs station: " +
              ", ".join(f"{k} mean {m:+.3f} RMS {q:.3f} m" for k, (m, q) in r["enu_" + name].items()))
    ok = (r["common"] >= a.min_common * max(r["ours"], r["rtk"]) and r["max"] <= a.max_diff and r["p95"] <= a.p95_diff
          and r["rms"] <= a.rms_diff and r["median"] <= a.median_diff)
    print("PASS" if ok else f"FAIL: limits median {a.median_diff} m, max {a.max_diff} m, 95th percentile "
          f"{a.p95_diff} m, RMS {a.rms_diff} m, {100 * a.min_common:g} % common epochs")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
