#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Run build/tools/validation/errmodel_validation on every real station-day
of ../shared/data (tools/validation/station_days.py): leave one station out
and the half day ahead at NYA1 (docs/validation.md, "An error model that
holds on unseen stations"). Gzip nav files are unpacked to a temp dir.

Usage: tools/validation/errmodel_validation.py --tool build/tools/validation/errmodel_validation
           [--data ../shared/data] [--seeds 20] [--half-day NYA1-2024-124] [--only STATION] [--csv FILE]
"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import station_days  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tool", required=True)
    ap.add_argument("--data", default=station_days.DEFAULT_DATA)
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--half-day", default="NYA1-2024-124")
    ap.add_argument("--only")
    ap.add_argument("--csv")
    ap.add_argument("--default-world", action="store_true", help="the built-in default world against every day")
    ap.add_argument("--profile", help="this receiver profile (ublox_m8, geodetic) against every day")
    ap.add_argument("--filtered", action="store_true", help="simulate with the whole default receiver (filter)")
    ap.add_argument("--without", action="append", default=[], help="switch a simulated term off (error budget)")
    ap.add_argument("--gain", metavar="LETTERS",
                    help="instead: the multi-system gain (e.g. G,R,E,C) at the multi-system days, the model fitted on "
                         "the GPS days")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        argv = [os.path.abspath(a.tool), "--seeds", str(a.seeds), "--half-day", a.half_day]
        days = station_days.days(a.data)
        if a.gain:
            multi = station_days.multi_system_days(a.data)
            days += multi
            argv += ["--gain", a.gain]
            for d in multi:
                argv += ["--gain-day", d.name]
        for d in days:
            argv += ["--day", f"{d.name},{d.station},{d.obs},{station_days.spp_vs_rtklib.plain_copy(d.nav, tmp)}"]
        if a.only:
            argv += ["--only", a.only]
        for t in a.without:
            argv += ["--without", t]
        if a.profile:
            argv += ["--profile", a.profile]
        if a.filtered:
            argv.append("--filtered")
        if a.default_world:
            argv.append("--default-world")
        if a.csv:
            argv += ["--csv", a.csv]
        return subprocess.run(argv).returncode


if __name__ == "__main__":
    sys.exit(main())
