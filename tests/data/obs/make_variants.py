#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Derive the small parser test files in this folder from the real NYA1 file.

Writes (values copied unchanged from NYA100NOR_S_20241240000_90M_30S_MO.rnx):
  nya1_v211_mixed.o   RINEX 2.11 mixed (G+R), types C1 L1 D1 S1 P2 L2, the first
                      3 epochs then an event (flag 4, header records), a flag-6
                      cycle-slip record and the 4th epoch. Epochs have 16+ satellites,
                      so the satellite list needs continuation lines.
  nya1_v305_events.rnx RINEX 3.05 with the header of the source, epochs 1-2, a
                      flag-5 event with 1 special record, a flag-6 record and epoch 3.
Run from this folder: python3 make_variants.py
"""
SRC = "NYA100NOR_S_20241240000_90M_30S_MO.rnx"

lines = open(SRC).read().splitlines()
end = next(i for i, l in enumerate(lines) if l[60:].strip() == "END OF HEADER")
header, body = lines[: end + 1], lines[end + 1 :]

types = {"G": [], "R": []}
cur = None
for l in header:
    if l[60:].strip() == "SYS / # / OBS TYPES":
        if l[0] != " ":
            cur = l[0]
        if cur in types:
            types[cur] += l[7:58].split()

epochs = []
i = 0
while i < len(body) and len(epochs) < 4:
    n = int(body[i][32:35])
    epochs.append((body[i], body[i + 1 : i + 1 + n]))
    i += 1 + n


def field(rec, sys, code):
    k = types[sys].index(code)
    return rec[3 + 16 * k : 3 + 16 * k + 16].ljust(16)


def label(text, lab):
    return text.ljust(60)[:60] + lab


V2 = {"G": ["C1C", "L1C", "D1C", "S1C", "C2W", "L2W"], "R": ["C1C", "L1C", "D1C", "S1C", "C2P", "L2P"]}

out = [
    label("     2.11           OBSERVATION DATA    M (MIXED)", "RINEX VERSION / TYPE"),
    label("make_variants.py    gnssemu tests", "PGM / RUN BY / DATE"),
    label("Derived from " + SRC[:40], "COMMENT"),
    label("NYA1", "MARKER NAME"),
    label("  1202434.1303   252632.2212  6237772.4351", "APPROX POSITION XYZ"),
    label("        0.0000        0.0000        0.0000", "ANTENNA: DELTA H/E/N"),
    label("     6    C1    L1    D1    S1    P2    L2", "# / TYPES OF OBSERV"),
    label("    30.000", "INTERVAL"),
    label("  2024     5     3     0     0    0.0000000     GPS", "TIME OF FIRST OBS"),
    label("    18", "LEAP SECONDS"),
    label("", "END OF HEADER"),
]


def v2_epoch(head, recs, flag=0):
    sats = [r for r in recs if r[0] in "GR"]
    yy, mo, dd, hh, mi, ss = head[4:6], int(head[7:9]), int(head[10:12]), int(head[13:15]), int(head[16:18]), float(head[19:29])
    ids = "".join(s[:3] for s in sats)
    first = " %s %2d %2d %2d %2d%11.7f  %d%3d" % (yy, mo, dd, hh, mi, ss, flag, len(sats))
    res = [first + ids[:36] + ("%12.9f" % 0.0 if flag == 0 else "")]
    for k in range(36, len(ids), 36):
        res.append(" " * 32 + ids[k : k + 36])
    for s in sats:
        vals = [field(s, s[0], c) for c in V2[s[0]]]
        res.append("".join(vals[:5]).rstrip())
        res.append("".join(vals[5:]).rstrip())
    return res, sats


for e in epochs[:3]:
    out += v2_epoch(*e)[0]
out.append("                            4  2")
out.append(label("EVENT: header records follow", "COMMENT"))
out.append(label("NYA1 AFTER EVENT", "MARKER NAME"))
slip, _ = v2_epoch(epochs[3][0], epochs[3][1][:2], flag=6)
out += slip
out += v2_epoch(*epochs[3])[0]
open("nya1_v211_mixed.o", "w").write("\n".join(out) + "\n")

out = list(header)
for e in epochs[:2]:
    out += [e[0]] + e[1]
out.append(">                              5  1")
out.append(label("EXTERNAL EVENT", "COMMENT"))
out.append(epochs[2][0][:31] + "6  1")
out.append(epochs[2][1][0])
out += [epochs[2][0]] + epochs[2][1]
open("nya1_v305_events.rnx", "w").write("\n".join(out) + "\n")
