#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Cross-check satpos_reference.py against RTKLIB (third-party implementation).

RTKLIB's rnx2rtkp (Debian package rtklib, 2.4.3 b34) prints, at debug trace
level 4, one line per satellite from satposs():
    "<time to 1e-6 s> sat=NN rs=<x y z to 1 mm> dts=<clock in ns to 1e-3>"
The state is evaluated at the signal transmission time, ECEF at that time,
clock including the relativistic term and excluding TGD -- the same
convention as the reference CSV files.

To get states at chosen epochs without real observations, this script writes
a minimal RINEX 2.11 observation file (C1 only, every PRN, P = 0.075 s * c)
so transmission time ~ receive time - 0.075 s - clock. It is harness input,
not data. A real observation file can be given with --obs instead.

Printing resolution limits the agreement: 1e-6 s in time (up to 2 mm along
track at 3.9 km/s), 0.5 mm per axis, 0.5 ps in clock. The script reports the
raw difference and the difference left after allowing a time offset within
+-0.5 us along the velocity.

Note: RTKLIB selects the ephemeris by receive time, the reference by
transmission time; receive epochs within 0.1 s of a point half-way between
two toes (odd hours) may select different sets. The default epochs avoid it.

Usage (from the repository root):
    python3 tools/reference/check_against_rtklib.py --nav tests/data/nav/brdc0010.22n
    python3 tools/reference/check_against_rtklib.py --nav NAV --obs OBS
"""

import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import satpos_reference as ref  # noqa: E402

LIGHT_TIME_S = 0.075
C_M_S = 299792458.0
TRACE_RE = re.compile(r'^4 (\d+)/(\d+)/(\d+) (\d+):(\d+):([\d.]+) sat=\s*(\d+) '
                      r'rs=\s*(\S+)\s+(\S+)\s+(\S+) dts=\s*(\S+)')


def gps_to_calendar(week, tow):
    import datetime
    whole = int(math.floor(tow))
    t = (datetime.datetime(1980, 1, 6)
         + datetime.timedelta(weeks=week, seconds=whole))
    return t, tow - whole


def write_obs(path, epochs):
    """epochs: list of (week, tow) receive times."""
    def hdr(text, label):
        return '%-60s%-20s\n' % (text, label)
    prns = list(range(1, 33))
    with open(path, 'w', encoding='ascii') as fh:
        fh.write(hdr('     2.11           OBSERVATION DATA    G (GPS)',
                     'RINEX VERSION / TYPE'))
        fh.write(hdr('SYNTHETIC', 'MARKER NAME'))
        fh.write(hdr('  4549397.1706  1874003.1392  4045167.6109',
                     'APPROX POSITION XYZ'))
        fh.write(hdr('     1    C1', '# / TYPES OF OBSERV'))
        t0, f0 = gps_to_calendar(*epochs[0])
        fh.write(hdr('%6d%6d%6d%6d%6d%13.7f     GPS' % (
            t0.year, t0.month, t0.day, t0.hour, t0.minute, t0.second + f0),
            'TIME OF FIRST OBS'))
        fh.write(hdr('', 'END OF HEADER'))
        for week, tow in epochs:
            t, frac = gps_to_calendar(week, tow)
            sats = ['G%02d' % p for p in prns]
            fh.write(' %02d %2d %2d %2d %2d%11.7f  0%3d%s\n' % (
                t.year % 100, t.month, t.day, t.hour, t.minute,
                t.second + frac, len(sats), ''.join(sats[:12])))
            for k in range(12, len(sats), 12):
                fh.write(' ' * 32 + ''.join(sats[k:k + 12]) + '\n')
            for _ in prns:
                fh.write('%14.3f  \n' % (LIGHT_TIME_S * C_M_S))


def default_epochs(ephs):
    """Receive epochs: hh:10 and hh:40 over the toe span, plus +-20 s and
    the validity limits around every week start within the span."""
    healthy = [e for e in ephs if e['health'] == 0]
    times = sorted(ref.tdiff(e['toe_week'], e['toe_tow'], 0, 0) for e in healthy)
    first, last = times[0] - 7200, times[-1] + 7200
    out = []
    t = (int(first) // 3600) * 3600 + 600
    while t <= last:
        for dt in (0, 1800):
            if first <= t + dt <= last:
                out.append(t + dt)
        t += 3600
    wk = int(first) // ref.SECONDS_PER_WEEK + 1
    while wk * ref.SECONDS_PER_WEEK <= last:
        b = wk * ref.SECONDS_PER_WEEK
        for dt in (-7199, -7184, -16, -1, 0, 1, 16, 7183, 7199):
            if first <= b + dt <= last:
                out.append(b + dt)
        wk += 1
    out = sorted(set(out))
    return [divmod(t, ref.SECONDS_PER_WEEK) for t in out]


def run_rtklib(obs, nav, workdir):
    pos = os.path.join(workdir, 'out.pos')
    subprocess.run(['rnx2rtkp', '-x', '4', '-p', '0', '-sys', 'G', '-o', pos,
                    obs, nav], stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL, check=False)
    trace = pos + '.trace'
    if not os.path.exists(trace):
        raise SystemExit('rnx2rtkp wrote no trace (is rtklib installed?)')
    return trace


def compare(nav, trace):
    _, ephs, _ = ref.parse_nav(nav)
    index = ref.by_prn(ephs)
    n = skipped = other_week = 0
    worst_raw = worst_res = worst_clk_ns = sum2 = 0.0
    with open(trace, encoding='ascii', errors='replace') as fh:
        for line in fh:
            m = TRACE_RE.match(line)
            if not m:
                continue
            y, mo, d, hh, mi = (int(v) for v in m.group(1, 2, 3, 4, 5))
            prn = int(m.group(7))
            rtk = tuple(float(v) for v in m.group(8, 9, 10))
            dts_ns = float(m.group(11))
            if prn > 32 or rtk == (0.0, 0.0, 0.0):
                skipped += 1
                continue
            week, tow = ref.calendar_to_gps(y, mo, d, hh, mi, float(m.group(6)))
            eph, _ = ref.select(index, prn, week, tow)
            if eph is None:
                skipped += 1
                continue
            pos, vel, clk = ref.state(eph, week, tow)
            diff = [a - b for a, b in zip(pos, rtk)]
            raw = math.sqrt(sum(c * c for c in diff))
            v2 = sum(c * c for c in vel)
            tau = sum(a * b for a, b in zip(diff, vel)) / v2
            tau = max(-0.5e-6, min(0.5e-6, tau))
            res = math.sqrt(sum((a - c * tau) ** 2 for a, c in zip(diff, vel)))
            n += 1
            other_week += eph['toe_week'] != week
            sum2 += raw * raw
            worst_raw = max(worst_raw, raw)
            worst_res = max(worst_res, res)
            worst_clk_ns = max(worst_clk_ns, abs(clk * 1e9 - dts_ns))
    print('%s: %d states compared (%d with toe in another week), %d without '
          'a state on one side; position diff max %.4f m, rms %.4f m; after '
          'time-print resolution max %.4f m; clock diff max %.4f ns' % (
              os.path.basename(nav), n, other_week, skipped, worst_raw,
              math.sqrt(sum2 / max(n, 1)), worst_res, worst_clk_ns))
    return n, worst_res, worst_clk_ns


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--nav', required=True)
    ap.add_argument('--obs', help='real RINEX obs file (default: synthetic)')
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        obs = args.obs
        if obs is None:
            _, ephs, _ = ref.parse_nav(args.nav)
            epochs = [ref.normalise(w, t + LIGHT_TIME_S)
                      for w, t in default_epochs(ephs)]
            obs = os.path.join(tmp, 'synthetic.obs')
            write_obs(obs, epochs)
        trace = run_rtklib(obs, args.nav, tmp)
        n, res, clk = compare(args.nav, trace)
    # Print resolution: 0.5 mm per axis -> 0.87 mm; clock 0.0005 ns.
    return 0 if n > 0 and res < 1.0e-3 and clk < 1.0e-3 else 1


if __name__ == '__main__':
    sys.exit(main())
