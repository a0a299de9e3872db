#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Independent GPS broadcast-ephemeris satellite-state reference.

This is deliberately a SECOND CODE PATH for checking the C++ orbit module
(core/orbit). It was written only from the specification, never from the C++
sources: IS-GPS-200 Table 20-IV and section 20.3.3.3.3.1, the RINEX 2.11 and
3.x nav record layouts (summarised with sources in
shared/reference/gps-orbits.md, sections 1-3, 5, 6). Standard library only,
Python floats (IEEE double).

What it computes, for GPS time t (continuous week + seconds of week):
  * ephemeris selection: healthy (SV health == 0) sets only; nearest toe;
    |t - toe| <= 7200 s (inclusive). Differences are taken in continuous time
    ((week - week_toe) * 604800 + (tow - toe_tow)), so no +-302400 s rule is
    needed. Equal-distance candidates that differ are reported as ties.
  * position: IS-GPS-200 Table 20-IV, mu = 3.986005e14 m^3/s^2,
    OmegaE_dot = 7.2921151467e-5 rad/s, Kepler by Newton to |dE| < 1e-15.
    ECEF at time t (no Sagnac / light-time handling: that is the caller's job).
  * velocity: five-point central finite difference of the position function,
        v = (-p(t+2h) + 8 p(t+h) - 8 p(t-h) + p(t-2h)) / (12 h),  h = 0.5 s.
    Truncation error h^4/30 * |d5p/dt5|; |d5p/dt5| <= ~1e-11 m/s^5 for a GPS
    orbit in ECEF (a * n^3 with a ~ 0.57 m/s^2, n ~ 1.46e-4 rad/s, plus
    Earth-rotation terms), so truncation < 2e-14 m/s. Rounding dominates:
    the Table 20-IV term OmegaE_dot * toe reaches ~44 rad, whose double
    spacing (7e-15 rad) moves the position by ~2e-7 m, giving ~3e-7 m/s in v.
    Measured against the analytic (bc_velo) derivative: <= 2.7e-7 m/s. The
    classic two-point difference with h = 0.5 ms (truncation h^2/6 * |jerk|
    ~ 1e-11 m/s, rounding ~2e-7 m / 1e-3 s) is off by up to 2e-4 m/s; it is
    printed for comparison by `eval --check-velocity`.
  * clock: af0 + af1*(t - toc) + af2*(t - toc)^2 + F*e*sqrt(A)*sin(E),
    F = -4.442807633e-10 s/m^0.5; TGD is NOT subtracted (L1/L2 ionosphere-free
    convention; an L1 C/A user subtracts TGD separately, IS-GPS-200
    20.3.3.3.3.2).

Re-run (from the repository root):
    python3 tools/reference/satpos_reference.py generate \\
        --nav-dir tests/data/nav --out-dir tests/data/reference
  regenerates tests/data/reference/satpos_<nav basename>.csv and the case
  tables in tests/data/reference/README.md (between the CASES markers).
Ad-hoc evaluation, same columns as the CSV files:
    python3 tools/reference/satpos_reference.py eval --nav FILE --week W --tow S
"""

import argparse
import datetime
import math
import os
import sys

# IS-GPS-200 Table 20-IV and 20.3.3.3.3.1.
MU_M3_S2 = 3.986005e14
OMEGA_E_DOT_RAD_S = 7.2921151467e-5
F_REL_S_SQRTM = -4.442807633e-10
SECONDS_PER_WEEK = 604800
MAX_DTOE_S = 7200.0          # RTKLIB MAXDTOE; gps-orbits.md section 5
KEPLER_TOL_RAD = 1e-15
KEPLER_MAX_ITER = 30
FD_STEP_S = 0.5              # five-point stencil step
FD2_STEP_S = 0.5e-3          # two-point check step

GPS_EPOCH = datetime.date(1980, 1, 6)

CSV_HEADER = ("prn,week,tow_s,toe_week,toe_tow_s,iode,x_m,y_m,z_m,"
              "vx_m_s,vy_m_s,vz_m_s,clk_bias_s")


class NavError(Exception):
    pass


# ---------------------------------------------------------------- time ----

def calendar_to_gps(year, month, day, hour, minute, sec):
    """Calendar GPS time -> (week, tow_s). sec may carry a fraction."""
    days = (datetime.date(year, month, day) - GPS_EPOCH).days
    whole = days * 86400 + hour * 3600 + minute * 60
    week, rem = divmod(whole, SECONDS_PER_WEEK)
    tow = rem + sec
    if tow >= SECONDS_PER_WEEK:
        week += 1
        tow -= SECONDS_PER_WEEK
    return week, tow


def tdiff(week_a, tow_a, week_b, tow_b):
    """(week_a, tow_a) - (week_b, tow_b) in seconds, continuous time."""
    return (week_a - week_b) * SECONDS_PER_WEEK + (tow_a - tow_b)


def normalise(week, tow):
    while tow < 0:
        week -= 1
        tow += SECONDS_PER_WEEK
    while tow >= SECONDS_PER_WEEK:
        week += 1
        tow -= SECONDS_PER_WEEK
    return week, tow


# -------------------------------------------------------------- parser ----

def _num(path, lineno, line, col):
    field = line[col:col + 19].strip()
    if not field:
        return 0.0  # RINEX: blank = not known
    try:
        return float(field.replace('D', 'E').replace('d', 'e'))
    except ValueError:
        raise NavError(f"{path}:{lineno}: bad number '{field}' at column {col}")


def _int(path, lineno, text, what):
    try:
        return int(text)
    except ValueError:
        raise NavError(f"{path}:{lineno}: bad {what} '{text.strip()}'")


def parse_nav(path):
    """Return (version, list of ephemeris dicts, skipped non-GPS records)."""
    with open(path, 'r', encoding='ascii', errors='replace') as fh:
        lines = fh.read().splitlines()
    version = None
    header_end = None
    for i, line in enumerate(lines):
        label = line[60:80].strip()
        if label == 'RINEX VERSION / TYPE':
            try:
                version = float(line[0:9])
            except ValueError:
                raise NavError(f"{path}:{i + 1}: bad RINEX version")
            ftype = line[20:21]
            system = line[40:41]
            if ftype != 'N':
                raise NavError(f"{path}:{i + 1}: not a GPS/GNSS nav file "
                               f"(type '{ftype}')")
            if version >= 3 and system not in ('G', 'M'):
                raise NavError(f"{path}:{i + 1}: nav file for system "
                               f"'{system}', no GPS records")
        if label == 'END OF HEADER':
            header_end = i
            break
    if version is None or header_end is None:
        raise NavError(f"{path}:1: missing RINEX VERSION / TYPE or END OF HEADER")

    v3 = version >= 3.0
    c0 = 4 if v3 else 3           # first value column on continuation lines
    first_cols = (23, 42, 61) if v3 else (22, 41, 60)
    ephs = []
    skipped = 0
    i = header_end + 1
    n = len(lines)
    while i < n:
        line = lines[i]
        if not line.strip():
            i += 1
            continue
        if v3:
            sysc = line[0]
            if sysc == ' ':
                raise NavError(f"{path}:{i + 1}: continuation line where a "
                               f"record start was expected")
            if sysc != 'G':
                skipped += 1
                i += 1
                while i < n and lines[i].startswith('    '):
                    i += 1
                continue
            prn = _int(path, i + 1, line[1:3], 'PRN')
            year = _int(path, i + 1, line[4:8], 'year')
            mon = _int(path, i + 1, line[9:11], 'month')
            day = _int(path, i + 1, line[12:14], 'day')
            hh = _int(path, i + 1, line[15:17], 'hour')
            mi = _int(path, i + 1, line[18:20], 'minute')
            ss = float(_int(path, i + 1, line[21:23], 'second'))
        else:
            prn = _int(path, i + 1, line[0:2], 'PRN')
            yy = _int(path, i + 1, line[3:5], 'year')
            year = 1900 + yy if yy >= 80 else 2000 + yy
            mon = _int(path, i + 1, line[6:8], 'month')
            day = _int(path, i + 1, line[9:11], 'day')
            hh = _int(path, i + 1, line[12:14], 'hour')
            mi = _int(path, i + 1, line[15:17], 'minute')
            try:
                ss = float(line[17:22])
            except ValueError:
                raise NavError(f"{path}:{i + 1}: bad seconds '{line[17:22]}'")
        if i + 7 >= n:
            raise NavError(f"{path}:{i + 1}: truncated record for PRN {prn}")
        start = i + 1
        vals = [_num(path, start, line, c) for c in first_cols]
        for k in range(1, 8):
            cl = lines[i + k]
            cols = (c0, c0 + 19, c0 + 38, c0 + 57)
            vals.extend(_num(path, i + k + 1, cl, c) for c in cols)
        i += 8
        toc_week, toc_tow = calendar_to_gps(year, mon, day, hh, mi, ss)
        e = {
            'prn': prn, 'line': start,
            'toc_week': toc_week, 'toc_tow': toc_tow,
            'af0': vals[0], 'af1': vals[1], 'af2': vals[2],
            'iode': int(round(vals[3])), 'crs': vals[4], 'delta_n': vals[5],
            'm0': vals[6],
            'cuc': vals[7], 'e': vals[8], 'cus': vals[9], 'sqrt_a': vals[10],
            'toe_tow': vals[11], 'cic': vals[12], 'omega0': vals[13],
            'cis': vals[14],
            'i0': vals[15], 'crc': vals[16], 'omega': vals[17],
            'omega_dot': vals[18],
            'idot': vals[19], 'week_field': int(round(vals[21])),
            'sv_accuracy': vals[23], 'health': int(round(vals[24])),
            'tgd': vals[25], 'iodc': int(round(vals[26])),
            'transmit_tow': vals[27], 'fit_h': vals[28],
        }
        if not (1 <= prn <= 32):
            raise NavError(f"{path}:{start}: GPS PRN {prn} out of range 1..32")
        if e['sqrt_a'] <= 0.0 or not (0.0 <= e['e'] < 1.0):
            raise NavError(f"{path}:{start}: PRN {prn}: impossible sqrt(A) "
                           f"{e['sqrt_a']} or e {e['e']}")
        # BO-5 week is the week of toe (continuous). Cross-check it against
        # toc, which is a calendar epoch; if they disagree by more than half a
        # week the week field is taken to be off by one (RTKLIB adjweek idea).
        toe_week = e['week_field']
        d = tdiff(toe_week, e['toe_tow'], toc_week, toc_tow)
        if d > SECONDS_PER_WEEK / 2:
            toe_week -= 1
        elif d < -SECONDS_PER_WEEK / 2:
            toe_week += 1
        e['toe_week'] = toe_week
        e['week_adjusted'] = toe_week != e['week_field']
        ephs.append(e)
    return version, ephs, skipped


# ---------------------------------------------------------- evaluation ----

def kepler(m, e):
    ek = m
    for _ in range(KEPLER_MAX_ITER):
        de = (ek - e * math.sin(ek) - m) / (1.0 - e * math.cos(ek))
        ek -= de
        if abs(de) < KEPLER_TOL_RAD:
            break
    return ek


def position(eph, tk):
    """ECEF position (m) and eccentric anomaly at tk = t - toe (s)."""
    a = eph['sqrt_a'] * eph['sqrt_a']
    n = math.sqrt(MU_M3_S2 / (a * a * a)) + eph['delta_n']
    mk = eph['m0'] + n * tk
    ek = kepler(mk, eph['e'])
    e = eph['e']
    nu = math.atan2(math.sqrt(1.0 - e * e) * math.sin(ek), math.cos(ek) - e)
    phi = nu + eph['omega']
    s2, c2 = math.sin(2.0 * phi), math.cos(2.0 * phi)
    du = eph['cus'] * s2 + eph['cuc'] * c2
    dr = eph['crs'] * s2 + eph['crc'] * c2
    di = eph['cis'] * s2 + eph['cic'] * c2
    u = phi + du
    r = a * (1.0 - e * math.cos(ek)) + dr
    inc = eph['i0'] + eph['idot'] * tk + di
    xp = r * math.cos(u)
    yp = r * math.sin(u)
    om = (eph['omega0'] + (eph['omega_dot'] - OMEGA_E_DOT_RAD_S) * tk
          - OMEGA_E_DOT_RAD_S * eph['toe_tow'])
    co, so, ci = math.cos(om), math.sin(om), math.cos(inc)
    x = xp * co - yp * ci * so
    y = xp * so + yp * ci * co
    z = yp * math.sin(inc)
    return (x, y, z), ek


def velocity_fd5(eph, tk, h=FD_STEP_S):
    p2, _ = position(eph, tk + 2 * h)
    p1, _ = position(eph, tk + h)
    m1, _ = position(eph, tk - h)
    m2, _ = position(eph, tk - 2 * h)
    return tuple((-p2[k] + 8.0 * p1[k] - 8.0 * m1[k] + m2[k]) / (12.0 * h)
                 for k in range(3))


def velocity_fd2(eph, tk, h=FD2_STEP_S):
    p1, _ = position(eph, tk + h)
    m1, _ = position(eph, tk - h)
    return tuple((p1[k] - m1[k]) / (2.0 * h) for k in range(3))


def clock_bias(eph, week, tow, ek):
    dt = tdiff(week, tow, eph['toc_week'], eph['toc_tow'])
    rel = F_REL_S_SQRTM * eph['e'] * eph['sqrt_a'] * math.sin(ek)
    return eph['af0'] + eph['af1'] * dt + eph['af2'] * dt * dt + rel


def _params_key(eph):
    skip = ('line', 'transmit_tow', 'week_adjusted')
    return tuple((k, v) for k, v in sorted(eph.items()) if k not in skip)


def select(ephs_by_prn, prn, week, tow):
    """Return (eph, None), (None, None) if none valid, or (None, tie list)."""
    best = None
    best_abs = None
    for eph in ephs_by_prn.get(prn, ()):
        if eph['health'] != 0:
            continue
        d = abs(tdiff(week, tow, eph['toe_week'], eph['toe_tow']))
        if d > MAX_DTOE_S:
            continue
        if best_abs is None or d < best_abs:
            best, best_abs = [eph], d
        elif d == best_abs:
            best.append(eph)
    if best is None:
        return None, None
    keys = {_params_key(e) for e in best}
    if len(keys) > 1:
        return None, best
    return best[0], None


def state(eph, week, tow):
    tk = tdiff(week, tow, eph['toe_week'], eph['toe_tow'])
    pos, ek = position(eph, tk)
    vel = velocity_fd5(eph, tk)
    clk = clock_bias(eph, week, tow, ek)
    return pos, vel, clk


def fmt(v):
    return '%.17g' % v


def row(eph, week, tow, pos, vel, clk):
    return ','.join([str(eph['prn']), str(week), fmt(tow), str(eph['toe_week']),
                     fmt(eph['toe_tow']), str(eph['iode'])]
                    + [fmt(c) for c in pos] + [fmt(c) for c in vel]
                    + [fmt(clk)])


def by_prn(ephs):
    out = {}
    for e in ephs:
        out.setdefault(e['prn'], []).append(e)
    return out


def epoch_rows(index, week, tow, ties=None, only_prns=None):
    rows = []
    for prn in sorted(index):
        if only_prns is not None and prn not in only_prns:
            continue
        eph, tie = select(index, prn, week, tow)
        if tie is not None:
            if ties is not None:
                ties.append((prn, week, tow, tie))
            continue
        if eph is None:
            continue
        pos, vel, clk = state(eph, week, tow)
        rows.append((prn, week, tow, eph, row(eph, week, tow, pos, vel, clk)))
    return rows


# ------------------------------------------------------- epoch planning ----

def plan_epochs(ephs):
    """Evaluation epochs for one file: list of (case, week, tow, prns|None).

    Derived from the file's own toe values so the plan follows the data.
    """
    healthy = [e for e in ephs if e['health'] == 0]
    toes = sorted({(e['toe_week'], e['toe_tow']) for e in healthy})
    # Day of the file: the calendar day holding most toc values.
    days = {}
    for e in ephs:
        w, t = e['toc_week'], e['toc_tow']
        day_start = (w, (int(t) // 86400) * 86400)
        days[day_start] = days.get(day_start, 0) + 1
    day_w, day_t = max(days.items(), key=lambda kv: kv[1])[0]
    plan = []
    # Ordinary epochs: every 2 h at hh:47:13.25 (never half-way between two
    # integer toes, so no ties), plus one at a sub-second fraction.
    for k in range(12):
        w, t = normalise(day_w, day_t + k * 7200 + 2833.25)
        plan.append(('mid-day', w, t, None))
    w, t = normalise(day_w, day_t + 43200 + 1234.5)
    plan.append(('mid-day', w, t, None))
    # Validity edges of each satellite's first and last healthy toe:
    # t = toe -+ 7200 (inclusive limit) and -+ 7199; only that PRN is listed.
    idx = by_prn(healthy)
    firsts, lasts = {}, {}
    for prn in sorted(idx):
        lst = sorted(idx[prn], key=lambda e: tdiff(e['toe_week'], e['toe_tow'], 0, 0))
        firsts[prn], lasts[prn] = lst[0], lst[-1]
    for off, case in ((-7200, 'edge toe-7200'), (-7199, 'edge toe-7199')):
        for prn in sorted(idx):
            w, t = normalise(firsts[prn]['toe_week'], firsts[prn]['toe_tow'] + off)
            plan.append((case, w, t, {prn}))
    for off, case in ((7199, 'edge toe+7199'), (7200, 'edge toe+7200')):
        for prn in sorted(idx):
            w, t = normalise(lasts[prn]['toe_week'], lasts[prn]['toe_tow'] + off)
            plan.append((case, w, t, {prn}))
    # Week boundary: any healthy toe within 2 h of a week start or end.
    boundaries = set()
    for w, t in toes:
        if t <= MAX_DTOE_S:
            boundaries.add(w)
        if t >= SECONDS_PER_WEEK - MAX_DTOE_S:
            boundaries.add(w + 1)
    for wb in sorted(boundaries):
        for off in (-7200, -16, -1, 0, 1, 16, 7184, 7185):
            w, t = normalise(wb, off)
            plan.append(('week boundary %d/0 %+ds' % (wb, off), w, t, None))
    return plan


def generate_file(nav_path, out_dir):
    version, ephs, skipped = parse_nav(nav_path)
    index = by_prn(ephs)
    base = os.path.basename(nav_path)
    ties = []
    seen = set()
    rows = []
    cases = []
    for case, w, t, prns in plan_epochs(ephs):
        for prn, rw, rt, eph, text in epoch_rows(index, w, t, ties, prns):
            key = (prn, rw, rt)
            if key in seen:
                continue
            seen.add(key)
            rows.append(text)
            cases.append((case, prn, rw, rt, eph))
    out = os.path.join(out_dir, 'satpos_%s.csv' % base)
    with open(out, 'w', encoding='ascii', newline='\n') as fh:
        fh.write(CSV_HEADER + '\n')
        for r in rows:
            fh.write(r + '\n')
    adjusted = [e for e in ephs if e['week_adjusted']]
    # Negative cases: one second beyond the first / last healthy toe window.
    absent = []
    for prn, lst in sorted(by_prn([e for e in ephs if e['health'] == 0]).items()):
        lst = sorted(lst, key=lambda e: tdiff(e['toe_week'], e['toe_tow'], 0, 0))
        for e, off in ((lst[0], -7201), (lst[-1], 7201)):
            w, t = normalise(e['toe_week'], e['toe_tow'] + off)
            if select(index, prn, w, t) == (None, None):
                absent.append((prn, w, t))
    unhealthy = [e for e in ephs if e['health'] != 0]
    return {'nav': base, 'csv': os.path.basename(out), 'version': version,
            'n_eph': len(ephs), 'skipped': skipped, 'rows': len(rows),
            'cases': cases, 'ties': ties, 'adjusted': adjusted,
            'unhealthy': unhealthy, 'absent': absent,
            'healthy_prns': {e['prn'] for e in ephs if e['health'] == 0}}


def summarise(info):
    """Markdown case table for one file; row numbers are 1-based data rows
    (CSV line number minus 1)."""
    out = ['### `%s` (from `%s`, RINEX %.2f, %d GPS records, %d non-GPS '
           'skipped, %d rows)' % (info['csv'], info['nav'], info['version'],
                                  info['n_eph'], info['skipped'], info['rows']),
           '']
    groups = []
    for i, (case, prn, w, t, eph) in enumerate(info['cases'], start=1):
        dt = tdiff(w, t, eph['toe_week'], eph['toe_tow'])
        label = case
        if eph['toe_week'] < w:
            label += ', toe in previous week'
        elif eph['toe_week'] > w:
            label += ', toe in next week'
        if groups and groups[-1][0] == label:
            groups[-1][2] = i
            groups[-1][3].append((prn, w, t, dt))
        else:
            groups.append([label, i, i, [(prn, w, t, dt)]])
    merged = {}
    order = []
    for label, a, b, items in groups:
        if label not in merged:
            merged[label] = []
            order.append(label)
        merged[label].append((a, b, items))
    out.append('| case | data rows | (prn, week, tow_s, t-toe s) |')
    out.append('|---|---|---|')
    for label in order:
        spans = merged[label]
        rows_txt = ', '.join(('%d' % a) if a == b else ('%d-%d' % (a, b))
                             for a, b, _ in spans)
        items = [it for _, _, its in spans for it in its]
        if label == 'mid-day':
            epochs = sorted({(w, t) for _, w, t, _ in items})
            ex = '%d rows, %d PRNs, epochs %s' % (
                len(items), len({p for p, *_ in items}),
                ' '.join('%d/%s' % (w, fmt(t)) for w, t in epochs))
        else:
            shown = items if len(items) <= 6 else items[:6]
            ex = '; '.join('G%02d %d/%s %+g' % (p, w, fmt(t), dt)
                           for p, w, t, dt in shown)
            if len(items) > len(shown):
                ex += '; ... (%d rows)' % len(items)
        out.append('| %s | %s | %s |' % (label, rows_txt, ex))
    out.append('')
    if info['ties']:
        out.append('Epochs skipped because different sets tie for nearest toe:')
        for prn, w, t, tie in info['ties']:
            out.append('- G%02d at %d/%s: toes %s' % (
                prn, w, fmt(t), ', '.join('%d/%s IODE %d (line %d)' % (
                    e['toe_week'], fmt(e['toe_tow']), e['iode'], e['line'])
                    for e in tie)))
    else:
        out.append('No ties for nearest toe at any planned epoch.')
    if info['unhealthy']:
        per = {}
        for e in info['unhealthy']:
            per.setdefault(e['prn'], []).append(e)
        out.append('Unhealthy records (never selected): ' + '; '.join(
            'G%02d %d records, health %s, toe %d/%s .. %d/%s' % (
                prn, len(es), '/'.join(sorted({str(e['health']) for e in es})),
                es[0]['toe_week'], fmt(es[0]['toe_tow']), es[-1]['toe_week'],
                fmt(es[-1]['toe_tow'])) for prn, es in sorted(per.items()))
            + '. PRNs with healthy sets too: %s.' % (', '.join(
                'G%02d' % p for p in sorted(per) if p in info['healthy_prns'])
                or 'none'))
    else:
        out.append('No unhealthy records.')
    out.append('Expected NO ephemeris (|t - toe| = 7201 s beyond the first or '
               'last healthy toe; not rows of the CSV): ' + ', '.join(
                   'G%02d %d/%s' % (p, w, fmt(t)) for p, w, t in info['absent'])
               + '.')
    if info['adjusted']:
        out.append('Week field disagreed with toc by more than half a week '
                   '(adjusted): ' + ', '.join('G%02d line %d' % (
                       e['prn'], e['line']) for e in info['adjusted']) + '.')
    else:
        out.append('BO-5 week agrees with toc for every record.')
    out.append('')
    return '\n'.join(out)


DEFAULT_FILES = ('brdc0010.22n', 'ab422100.18n',
                 'NYA100NOR_S_20241240000_01D_GN.rnx',
                 'ELKO00USA_R_20182100000_01D_MN.rnx')
BEGIN_MARK = '<!-- BEGIN CASES (generated by satpos_reference.py) -->'
END_MARK = '<!-- END CASES -->'


def cmd_generate(args):
    os.makedirs(args.out_dir, exist_ok=True)
    parts = []
    for name in args.files or DEFAULT_FILES:
        info = generate_file(os.path.join(args.nav_dir, name), args.out_dir)
        print('%s: %d rows, %d ties' % (info['csv'], info['rows'],
                                         len(info['ties'])), file=sys.stderr)
        parts.append(summarise(info))
    readme = os.path.join(args.out_dir, 'README.md')
    text = '\n'.join(parts)
    if os.path.exists(readme):
        with open(readme, encoding='utf-8') as fh:
            cur = fh.read()
        if BEGIN_MARK in cur and END_MARK in cur:
            head = cur.split(BEGIN_MARK)[0]
            tail = cur.split(END_MARK, 1)[1]
            with open(readme, 'w', encoding='utf-8') as fh:
                fh.write(head + BEGIN_MARK + '\n' + text + END_MARK + tail)
            return 0
    print(text)
    return 0


def cmd_eval(args):
    _, ephs, _ = parse_nav(args.nav)
    index = by_prn(ephs)
    ties = []
    print(CSV_HEADER)
    for _, _, _, eph, text in epoch_rows(index, args.week, args.tow, ties):
        print(text)
        if args.check_velocity:
            tk = tdiff(args.week, args.tow, eph['toe_week'], eph['toe_tow'])
            v5 = velocity_fd5(eph, tk)
            v2 = velocity_fd2(eph, tk)
            print('#   |v5-v2| = %.3g m/s' % math.sqrt(
                sum((a - b) ** 2 for a, b in zip(v5, v2))))
    for prn, w, t, tie in ties:
        print('# G%02d tie at %d/%s: %d different sets' % (prn, w, fmt(t),
                                                           len(tie)),
              file=sys.stderr)
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    sub = ap.add_subparsers(dest='cmd', required=True)
    g = sub.add_parser('generate', help='write the reference CSV files')
    g.add_argument('--nav-dir', default='tests/data/nav')
    g.add_argument('--out-dir', default='tests/data/reference')
    g.add_argument('files', nargs='*', help='nav file names (default: all)')
    e = sub.add_parser('eval', help='states of all satellites at one epoch')
    e.add_argument('--nav', required=True)
    e.add_argument('--week', type=int, required=True)
    e.add_argument('--tow', type=float, required=True)
    e.add_argument('--check-velocity', action='store_true',
                   help='also print |five-point - two-point 0.5 ms| velocity')
    args = ap.parse_args(argv)
    try:
        return cmd_generate(args) if args.cmd == 'generate' else cmd_eval(args)
    except (NavError, OSError) as exc:
        print('error: %s' % exc, file=sys.stderr)
        return 1


if __name__ == '__main__':
    sys.exit(main())
