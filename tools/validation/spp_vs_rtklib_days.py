#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemu spp against RTKLIB rnx2rtkp on every real station-day of
../shared/data (docs/validation.md, "Our single-point solution against
RTKLIB"): one row per day with the per-epoch 3D difference (median, 95th
percentile, max) and the epochs each solved, for `spp --preset rtklib`
(RTKLIB's weights, models and test), and for the receiver's own settings
with RTKLIB's troposphere mapping (--config, e.g.
tests/data/config/spp_rtklib_models.toml) when given.

Usage: tools/validation/spp_vs_rtklib_days.py --gnssemu build/tools/gnssemu/gnssemu
           [--data ../shared/data] [--config tests/data/config/spp_rtklib_models.toml]
Only the Python standard library and Debian's rnx2rtkp are used.
"""
import argparse
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import station_days  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--data", default=station_days.DEFAULT_DATA)
    ap.add_argument("--mask", type=float, default=10.0)
    ap.add_argument("--config", help="also compare the receiver's own weights with this config")
    a = ap.parse_args()
    rnx2rtkp = shutil.which("rnx2rtkp")
    if rnx2rtkp is None:
        print("rnx2rtkp (Debian package rtklib) is not installed", file=sys.stderr)
        return 1
    runs = [("preset rtklib", None, "rtklib")] + ([("config " + os.path.basename(a.config), a.config, None)]
                                                  if a.config else [])
    print("day,solver,epochs_gnssemu,epochs_rnx2rtkp,common,nsat_differ,median_m,p95_m,max_m,rms_m")
    for d in station_days.days(a.data):
        for label, config, preset in runs:
            r = station_days.spp_vs_rtklib.compare(os.path.abspath(a.gnssemu), rnx2rtkp, d.obs, d.nav, a.mask, config, preset, d.arp)
            print(f"{d.name},{label},{r['ours']},{r['rtk']},{r['common']},{r.get('nsat_diff', 0)},"
                  f"{r.get('median', float('nan')):.4f},{r.get('p95', float('nan')):.4f},"
                  f"{r.get('max', float('nan')):.4f},{r.get('rms', float('nan')):.4f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
