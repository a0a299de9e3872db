#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemu's receiver against RTKLIB's rnx2rtkp on gnssemu's own RINEX.

`gnssemu batch --preset rtklib` runs the receiver with rnx2rtkp's single-point
models and weights (Klobuchar, Saastamoinen, snapshot least squares, no
smoothing) and writes its raw measurements (--rinex-obs) and the broadcast sets
it used (--rinex-nav); rnx2rtkp solves the same files with the same mask and
systems. Both fixes are compared with the truth epoch by epoch: the 3D
difference between them must stay within the limits (docs/raw-output.md).
Exit 77 (CTest skip) when rnx2rtkp is not installed.
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from spp_vs_rtklib import RTKLIB_CONF, navsys  # noqa: E402

A, E2 = 6378137.0, 6.69437999014e-3


def ecef(lat_deg, lon_deg, h):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
            (n * (1 - E2) + h) * math.sin(lat))


def enu(d, lat_deg, lon_deg):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    return (-so * d[0] + co * d[1], -sl * co * d[0] - sl * so * d[1] + cl * d[2],
            cl * co * d[0] + cl * so * d[1] + sl * d[2])


def read_truth(path):
    truth = {}
    with open(path) as f:
        col = {n: i for i, n in enumerate(f.readline().strip().split(","))}
        for line in f:
            c = line.strip().split(",")
            truth[(int(c[col["gps_week"]]), round(float(c[col["tow_s"]]), 1))] = (
                float(c[col["lat_deg"]]), float(c[col["lon_deg"]]), float(c[col["height_m"]]))
    return truth


def median(v):
    s = sorted(v)
    n = len(s)
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--truth", required=True)
    ap.add_argument("--systems", default="G", help="RINEX letters both solve with, e.g. G,R,E,C")
    ap.add_argument("--mask", type=float, default=5.0, help="the config's elevation mask, deg")
    ap.add_argument("--median-diff", type=float, default=0.05, help="largest allowed median 3D difference, m")
    ap.add_argument("--min-common", type=float, default=0.9,
                    help="smallest allowed fraction of gnssemu's fixes rnx2rtkp also solves")
    ap.add_argument("--bands", type=int, default=1,
                    help="signals per satellite (batch --bands); 2: rnx2rtkp reads both and solves on L1 alike")
    ap.add_argument("--generation", help="run the config as this [receiver] generation (f9p: two bands)")
    a = ap.parse_args()
    rnx2rtkp = shutil.which("rnx2rtkp")
    if rnx2rtkp is None:
        print("SKIP: rnx2rtkp (Debian package rtklib) is not installed")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        obs, nav, errors = (os.path.join(tmp, n) for n in ("run.obs", "run.nav", "errors.csv"))
        config = a.config
        if a.generation:
            # The same file as another chip: its generation line replaced, its
            # nav file by absolute path (the copy lives elsewhere).
            config = os.path.join(tmp, "config.toml")
            base = os.path.dirname(os.path.abspath(a.config))
            with open(a.config) as f:
                text = f.read()
            text, n = re.subn(r'^generation = "[a-z0-9]+"', f'generation = "{a.generation}"', text, count=1,
                              flags=re.M)
            if n == 0:
                text = text.replace("[receiver]\n", f'[receiver]\ngeneration = "{a.generation}"\n', 1)
            text = re.sub(r'^file = "([^/"][^"]*)"', lambda m: f'file = "{os.path.join(base, m.group(1))}"', text,
                          flags=re.M)
            with open(config, "w") as f:
                f.write(text)
        subprocess.run([a.gnssemu, "batch", "--config", config, "--truth", a.truth, "--systems", a.systems,
                        "--preset", "rtklib", "--rinex-obs", obs, "--rinex-nav", nav, "--errors", errors,
                        "--bands", str(a.bands)],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        conf = os.path.join(tmp, "single.conf")
        with open(conf, "w") as f:
            f.write(RTKLIB_CONF.format(mask=a.mask, navsys=navsys(a.systems)))
        types = {}
        with open(obs) as f:
            for line in f:
                if "END OF HEADER" in line:
                    break
                if line[60:].startswith("SYS / # / OBS TYPES") and line[0] != " ":
                    types[line[0]] = line[7:58].split()
        print("RINEX observation types: " + "; ".join(f"{k} {' '.join(v)}" for k, v in sorted(types.items())))
        if a.bands > 1 and any(len({t[1:] for t in v}) < 2 for v in types.values()):
            print("FAIL: a system without its second signal in the header")
            return 1
        pos = os.path.join(tmp, "rtk.pos")
        subprocess.run([rnx2rtkp, "-k", conf, "-o", pos, obs, nav], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        truth = read_truth(a.truth)
        ours = {}
        with open(errors) as f:
            col = {n: i for i, n in enumerate(f.readline().strip().split(","))}
            for line in f:
                c = line.strip().split(",")
                if c[col["e_m"]] == "" or int(c[col["fix_type"]]) < 2:
                    continue
                ours[(int(c[col["gps_week"]]), round(float(c[col["tow_s"]]), 1))] = tuple(
                    float(c[col[k]]) for k in ("e_m", "n_m", "u_m"))
        rtk = {}
        with open(pos) as f:
            for line in f:
                if line.startswith("%") or not line.strip():
                    continue
                c = line.split()
                if c[5] != "5":  # Q = 5: single
                    continue
                rtk[(int(c[0]), round(float(c[1]), 1))] = (float(c[2]), float(c[3]), float(c[4]))
    common = sorted(k for k in ours if k in rtk and k in truth)
    if not common:
        print(f"FAIL: no common epochs (gnssemu {len(ours)}, rnx2rtkp {len(rtk)})")
        return 1
    diffs, h_ours, h_rtk = [], [], []
    for k in common:
        lat, lon, h = truth[k]
        t = ecef(lat, lon, h)
        q = enu([rtk[k][i] - t[i] for i in range(3)], lat, lon)
        o = ours[k]
        diffs.append(math.sqrt(sum((o[i] - q[i]) ** 2 for i in range(3))))
        h_ours.append(math.hypot(o[0], o[1]))
        h_rtk.append(math.hypot(q[0], q[1]))
    s = sorted(diffs)
    med = median(diffs)
    print(f"systems {a.systems}: epochs gnssemu {len(ours)}, rnx2rtkp {len(rtk)}, common {len(common)}")
    print(f"3D difference gnssemu - rnx2rtkp: median {med:.4f} m, 95th percentile {s[int(0.95 * (len(s) - 1))]:.4f} m, "
          f"max {s[-1]:.4f} m")
    print(f"horizontal error vs truth, median: gnssemu {median(h_ours):.3f} m, rnx2rtkp {median(h_rtk):.3f} m")
    ok = med <= a.median_diff and len(common) >= a.min_common * len(ours)
    print("PASS" if ok else f"FAIL: limits median {a.median_diff} m, {100 * a.min_common:g} % common epochs")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
