#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Per-epoch summary of a `gnssemu batch --errors` CSV (with or without scene columns)."""
import csv
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
n = len(rows)
fix = [r for r in rows if r["e_m"] != ""]
h = sorted(math.hypot(float(r["e_m"]), float(r["n_m"])) for r in fix)
pct = lambda v, p: v[min(len(v) - 1, int(p * len(v)))] if v else float("nan")
outages, run = [], 0
for r in rows:
    if r["e_m"] == "":
        run += 1
    elif run:
        outages.append(run)
        run = 0
if run:
    outages.append(run)
print(f"epochs {n}, fixes {len(fix)} ({100.0 * len(fix) / n:.1f}%), outages {len(outages)} (longest {max(outages, default=0)} epochs)")
print(f"horizontal error: median {pct(h, 0.5):.1f} m, 95% {pct(h, 0.95):.1f} m, max {pct(h, 1.0):.1f} m")
print(f"satellites used per epoch: mean {sum(float(r['nsat']) for r in rows) / n:.2f}")
if "nlos" in rows[0]:
    mean = lambda k: sum(float(r[k]) for r in rows) / n
    with_nlos = sum(1 for r in rows if float(r["nlos"]) > 0)
    print(f"per epoch: above mask {mean('nvisible'):.2f}, tracked {mean('ntracked'):.2f}, NLOS tracked {mean('nlos'):.2f}, "
          f"blocked {mean('nblocked'):.2f}; epochs with NLOS {with_nlos} ({100.0 * with_nlos / n:.1f}%)")
    d = [float(r["nlos_delay_mean_m"]) for r in rows if float(r["nlos"]) > 0]
    if d:
        d.sort()
        print(f"NLOS extra delay (per-epoch mean over NLOS satellites): median {pct(d, 0.5):.1f} m, max {d[-1]:.1f} m")
