#!/usr/bin/env python3
"""gnssemu spp against RTKLIB's rnx2rtkp (single point) on the real NYA1 data.

Both solve the same 90-minute RINEX 3.05 file with the same broadcast nav
file, the same 10 degree mask, GPS C1C only, broadcast Klobuchar and a
Saastamoinen troposphere (docs/validation.md). Prints per-epoch 3D
differences (max, RMS) and each solver's error against the station's
header coordinates; fails when an epoch differs by more than --max-diff.
Exit 77 (CTest skip) when rnx2rtkp is not installed.
"""
import argparse
import math
import os
import shutil
import subprocess
import sys
import tempfile

STATION = (1202434.1303, 252632.2212, 6237772.4351)  # NYA1 APPROX POSITION XYZ

RTKLIB_CONF = """pos1-posmode       =single
pos1-frequency     =l1
pos1-elmask        ={mask}
pos1-ionoopt       =brdc
pos1-tropopt       =saas
pos1-sateph        =brdc
pos1-navsys        =1
out-solformat      =xyz
out-timesys        =gpst
out-timeform       =tow
"""


def enu(d, ref):
    x, y, z = ref
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1 - 6.69437999014e-3))  # geodetic latitude, 1 iteration is enough here
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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--obs", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--mask", type=float, default=10.0)
    ap.add_argument("--config", help="gnssemu config for spp's solver settings (e.g. troposphere mapping)")
    ap.add_argument("--max-diff", type=float, default=1.5, help="largest allowed per-epoch 3D difference, m")
    ap.add_argument("--p95-diff", type=float, default=0.8, help="largest allowed 95th percentile 3D difference, m")
    ap.add_argument("--rms-diff", type=float, default=0.45, help="largest allowed RMS 3D difference, m")
    a = ap.parse_args()

    rnx2rtkp = shutil.which("rnx2rtkp")
    if rnx2rtkp is None:
        print("SKIP: rnx2rtkp (Debian package rtklib) is not installed")
        return 77

    with tempfile.TemporaryDirectory() as tmp:
        conf = os.path.join(tmp, "single.conf")
        with open(conf, "w") as f:
            f.write(RTKLIB_CONF.format(mask=a.mask))
        pos = os.path.join(tmp, "rtk.pos")
        subprocess.run([rnx2rtkp, "-k", conf, "-o", pos, a.obs, a.nav], check=True,
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

    argv = [a.gnssemu, "spp", "--obs", a.obs, "--nav", a.nav, "--mask", str(a.mask)]
    if a.config:
        argv += ["--config", a.config]
    res = subprocess.run(argv, check=True, capture_output=True, text=True)
    lines = res.stdout.strip().splitlines()
    head = lines[0].split(",")
    col = {n: i for i, n in enumerate(head)}
    ours = {}
    for line in lines[1:]:
        c = line.split(",")
        key = (int(c[col["gps_week"]]), round(float(c[col["tow_s"]]), 1))
        ours[key] = (float(c[col["x_m"]]), float(c[col["y_m"]]), float(c[col["z_m"]]), int(c[col["nsat"]]))

    common = sorted(set(ours) & set(rtk))
    if not common:
        print("FAIL: no common epochs")
        return 1
    diffs, e_ours, e_rtk, nsat_diff = [], [], [], 0
    for k in common:
        o, r = ours[k], rtk[k]
        d = [o[i] - r[i] for i in range(3)]
        diffs.append(math.sqrt(sum(x * x for x in d)))
        e_ours.append(enu([o[i] - STATION[i] for i in range(3)], STATION))
        e_rtk.append(enu([r[i] - STATION[i] for i in range(3)], STATION))
        nsat_diff += o[3] != r[3]
    mx = max(diffs)
    rms = math.sqrt(sum(x * x for x in diffs) / len(diffs))
    p95 = sorted(diffs)[int(0.95 * (len(diffs) - 1))]
    worst = common[diffs.index(mx)]
    print(f"epochs: gnssemu {len(ours)}, rnx2rtkp {len(rtk)}, common {len(common)}, "
          f"different satellite count {nsat_diff}")
    print(f"3D difference gnssemu - rnx2rtkp: max {mx:.3f} m (week {worst[0]} tow {worst[1]}), "
          f"95th percentile {p95:.3f} m, RMS {rms:.3f} m")
    for name, e in (("gnssemu", e_ours), ("rnx2rtkp", e_rtk)):
        s = stats(e)
        print(f"{name:9s} error vs NYA1 header position: " +
              ", ".join(f"{k} mean {m:+.3f} RMS {q:.3f} m" for k, (m, q) in s.items()))
    ok = len(common) >= 0.95 * max(len(ours), len(rtk)) and mx <= a.max_diff and p95 <= a.p95_diff and rms <= a.rms_diff
    print("PASS" if ok else f"FAIL: limits max {a.max_diff} m, 95th percentile {a.p95_diff} m, RMS {a.rms_diff} m, "
          "95 % common epochs")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
