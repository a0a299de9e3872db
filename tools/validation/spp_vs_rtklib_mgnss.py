#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemu spp --preset rtklib against RTKLIB rnx2rtkp in single-point mode
with the same systems, on every multi-GNSS station-day of ../shared/data that
has a nav file (docs/validation.md, "Several systems"): one row per day and
system mix with the per-epoch 3D difference (median, 95th percentile, max)
and the epochs each solved. Compact RINEX is decoded for rnx2rtkp by the
project's own decoder (build/tools/validation/rinex_from_crx).

Usage: tools/validation/spp_vs_rtklib_mgnss.py --gnssemu build/tools/gnssemu/gnssemu \
           --rinex-from-crx build/tools/validation/rinex_from_crx [--data ../shared/data] [--mask 10]
Only the Python standard library and Debian's rnx2rtkp are used.
"""
import argparse
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import station_days  # noqa: E402

MIXES = ["G", "G,R", "G,E", "G,C", "G,R,E,C"]
# name, obs, nav, system mixes (those the nav file carries)
DAYS = [
    ("BELE-2024-010", "obs/BELE00BRA_R_20240100000_01D_30S_MO.crx.gz", "nav/BRDC00IGS_R_20240100000_01D_MN.rnx.gz", MIXES),
    ("TLSE-2024-001", "obs/TLSE00FRA_R_20240011200_15M_01S_MO.crx.gz", "nav/BRDC00IGS_R_20240010000_01D_MN.rnx.gz", MIXES),
    ("AJAC-2024-209", "obs/AJAC00FRA_R_20242090000_01D_30S_MO.crx.gz", "nav/GRAS00FRA_R_20242090000_01D_EN.rnx.gz", ["E"]),
    ("AJAC-2024-210", "obs/AJAC00FRA_R_20242100000_01D_30S_MO.crx.gz", "nav/GRAS00FRA_R_20242100000_01D_EN.rnx.gz", ["E"]),
    ("NYA1-2024-124", "obs/NYA100NOR_S_20241240000_01D_30S_MO.crx.gz", "nav/NYA100NOR_S_20241240000_01D_GN.rnx", ["G"]),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--rinex-from-crx", required=True)
    ap.add_argument("--data", default=station_days.DEFAULT_DATA)
    ap.add_argument("--mask", type=float, default=10.0)
    ap.add_argument("--only", help="run only the day with this name")
    a = ap.parse_args()
    rnx2rtkp = shutil.which("rnx2rtkp")
    if rnx2rtkp is None:
        print("rnx2rtkp (Debian package rtklib) is not installed", file=sys.stderr)
        return 1
    print("day,systems,epochs_gnssemu,epochs_rnx2rtkp,common,nsat_differ,median_m,p95_m,max_m,rms_m")
    for name, obs, nav, mixes in DAYS:
        if a.only and name != a.only:
            continue
        for systems in mixes:
            r = station_days.spp_vs_rtklib.compare(
                os.path.abspath(a.gnssemu), rnx2rtkp, os.path.join(a.data, obs), os.path.join(a.data, nav), a.mask,
                None, "rtklib", None, systems, os.path.abspath(a.rinex_from_crx))
            print(f"{name},{systems.replace(',', '+')},{r['ours']},{r['rtk']},{r['common']},{r.get('nsat_diff', 0)},"
                  f"{r.get('median', float('nan')):.4f},{r.get('p95', float('nan')):.4f},"
                  f"{r.get('max', float('nan')):.4f},{r.get('rms', float('nan')):.4f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
