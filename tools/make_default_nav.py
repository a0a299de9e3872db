#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The shipped multi-GNSS nav file (config/nav/README.md) from an IGS merged
broadcast file (RINEX 3 `MN`, e.g. shared/data/nav/BRDC00IGS_R_20240100000_01D_MN.rnx.gz):

  - systems G, R, E, C, J, S kept; NavIC (I) records dropped (not modelled);
  - SBAS: a GEO's record serves |t - toc| <= 360 s (RTKLIB MAXDTOE_S, the
    store's rule), and the source has one every 16-256 s; per GEO the first
    is kept, then the last one less than SBAS_SPAN_S after the last kept, so
    that the kept windows still cover the day without a gap;
  - a record listed twice (same text: the merge of several stations) kept once;
  - Galileo: I/NAV records only (data-source bit 9, what the store uses); of
    several with one toe the first transmitted (the store's choice); and per
    satellite its first set, then each set an hour or more after the last
    one kept (instead of every 10 min: a Galileo set serves 4 h);
  - header: every line but the per-satellite copies of BDSA/BDSB (the first
    of each is kept: it is the one the reader uses).

Record values are copied as they are. Writes gzip (mtime 0: reproducible).

usage: make_default_nav.py SOURCE.rnx.gz OUT.rnx.gz
"""
import calendar
import gzip
import sys

KEEP = set("GRECJS")
SBAS_SPAN_S = 700  # < 2 x 360 s: neighbouring windows overlap


def records(lines):
    """Records as lists of lines: a record starts at a line not starting with a space."""
    cur = []
    for line in lines:
        if line[:1] != " " and cur:
            yield cur
            cur = []
        cur.append(line)
    if cur:
        yield cur


def field(line, k):
    """The k-th 19-character data field of a continuation line (4 spaces, then 4 fields)."""
    return float(line[4 + 19 * k:4 + 19 * (k + 1)].replace("D", "E"))


def inav(rec):
    return int(field(rec[5], 1)) & 512


def toc_s(rec):
    """The record's toc as seconds since 1970 (its own time scale; only differences matter)."""
    y, mo, d, h, mi, sec = (int(x) for x in rec[0][4:23].split())
    return calendar.timegm((y, mo, d, h, mi, sec))


def thin_hourly(recs):
    """Per satellite (records in toc order): the first, then each one an hour or more after the last kept."""
    out, last = [], {}
    for rec in sorted(recs, key=lambda r: (r[0][:3], toc_s(r))):
        sat, t = rec[0][:3], toc_s(rec)
        if sat in last and t - last[sat] < 3600:
            continue
        last[sat] = t
        out.append(rec)
    return out


def thin_sbas(recs):
    """Per GEO (records in toc order): the first, then the latest one within SBAS_SPAN_S of the last kept."""
    out = []
    by_sat = {}
    for rec in sorted(recs, key=lambda r: (r[0][:3], toc_s(r))):
        by_sat.setdefault(rec[0][:3], []).append(rec)
    for sat_recs in by_sat.values():
        kept = [sat_recs[0]]
        for i, rec in enumerate(sat_recs[1:], 1):
            nxt = sat_recs[i + 1] if i + 1 < len(sat_recs) else None
            # Keep rec when the next one would be too far from the last kept.
            if nxt is None or toc_s(nxt) - toc_s(kept[-1]) > SBAS_SPAN_S:
                if toc_s(rec) != toc_s(kept[-1]):
                    kept.append(rec)
        out.extend(kept)
    return out


def main(src, dst):
    text = gzip.open(src, "rt").read().splitlines()
    end = next(i for i, l in enumerate(text) if l[60:].strip() == "END OF HEADER")
    header, seen_bds = [], set()
    for line in text[:end + 1]:
        if line[60:].strip() == "IONOSPHERIC CORR" and line[:4] in ("BDSA", "BDSB"):
            if line[:4] in seen_bds:
                continue
            seen_bds.add(line[:4])
        header.append(line)
    kept, seen, galileo, sbas = [], set(), {}, []
    for rec in records(text[end + 1:]):
        sys_letter = rec[0][0]
        if sys_letter not in KEEP:
            continue
        key = "\n".join(rec)
        if key in seen:
            continue
        seen.add(key)
        if sys_letter == "E" and not inav(rec):
            continue
        if sys_letter == "S":
            sbas.append(rec)
            continue
        if sys_letter == "E":
            k = rec[0][:23]  # satellite and toc
            if k in galileo and field(galileo[k][7], 0) <= field(rec[7], 0):
                continue
            galileo[k] = rec
            continue
        kept.append(rec)
    kept.extend(thin_hourly(galileo.values()))
    kept.extend(thin_sbas(sbas))
    order = "GRECJS"
    kept.sort(key=lambda r: (order.index(r[0][0]), r[0][:3]))  # stable: file order within a satellite
    out, counts = [], {}
    for rec in kept:
        out.extend(rec)
        counts[rec[0][0]] = counts.get(rec[0][0], 0) + 1
    with open(dst, "wb") as raw, gzip.GzipFile(filename="", mode="wb", fileobj=raw, mtime=0) as f:
        f.write(("\n".join(header + out) + "\n").encode("ascii"))
    print(" ".join(f"{s}{counts.get(s, 0)}" for s in order), "records")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
