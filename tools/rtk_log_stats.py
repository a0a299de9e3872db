#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""RTK state statistics of an NMEA log: GGA quality counts, the fixed
fraction, run lengths of fixed (4) and float (5), and the time from leaving
fixed to being fixed again. Epochs without a GGA (a gap in the log) count as
no fix. docs/rtk.md compares these figures with gnssemu's simulated drive.

    tools/rtk_log_stats.py LOG.nmea [--rate-hz 1]
"""
import argparse
import itertools
import statistics
import sys


def gga_qualities(path, rate_hz):
    """(seconds of day, quality) per GGA, gaps filled with quality 0."""
    out = []
    with open(path, errors="replace") as f:
        for line in f:
            if not line.startswith("$") or line[3:6] != "GGA":
                continue
            p = line.split(",")
            if len(p) < 7 or len(p[1]) < 6:
                continue
            t = int(p[1][0:2]) * 3600 + int(p[1][2:4]) * 60 + float(p[1][4:])
            q = int(p[6]) if p[6].isdigit() else 0
            if out:
                missing = round((t - out[-1][0]) * rate_hz) - 1
                out.extend((out[-1][0] + (k + 1) / rate_hz, 0) for k in range(max(0, missing)))
            out.append((t, q))
    return out


def runs(q, state):
    return [len(list(g)) for k, g in itertools.groupby(q) if k == state]


def refix_gaps(q):
    """Epochs from leaving fixed to fixed again, for every gap that ends fixed."""
    gaps, i = [], 1
    while i < len(q):
        if q[i - 1] == 4 and q[i] != 4:
            j = i
            while j < len(q) and q[j] != 4:
                j += 1
            if j < len(q):
                gaps.append(j - i)
            i = j
        i += 1
    return gaps


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("log")
    ap.add_argument("--rate-hz", type=float, default=1.0)
    a = ap.parse_args()
    epochs = gga_qualities(a.log, a.rate_hz)
    if not epochs:
        sys.exit(f"{a.log}: no GGA sentences")
    q = [e[1] for e in epochs]
    n = len(q)
    counts = {k: q.count(k) for k in sorted(set(q))}
    med = lambda v: statistics.median(v) if v else float("nan")
    print("epochs,q4,q5,q2,q1,q0,fixed_fraction,fixed_runs,fixed_run_median_s,fixed_run_mean_s,"
          "float_runs,float_run_median_s,refix_gaps,refix_median_s,refix_p90_s")
    g = sorted(refix_gaps(q))
    p90 = g[int(0.9 * (len(g) - 1))] / a.rate_hz if g else float("nan")
    f4, f5 = runs(q, 4), runs(q, 5)
    print(f"{n},{counts.get(4, 0)},{counts.get(5, 0)},{counts.get(2, 0)},{counts.get(1, 0)},{counts.get(0, 0)},"
          f"{counts.get(4, 0) / n:.3f},{len(f4)},{med(f4) / a.rate_hz:.1f},"
          f"{(sum(f4) / len(f4) if f4 else float('nan')) / a.rate_hz:.1f},{len(f5)},{med(f5) / a.rate_hz:.1f},"
          f"{len(g)},{med(g) / a.rate_hz:.1f},{p90:.1f}")


if __name__ == "__main__":
    main()
