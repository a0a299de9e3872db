#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""C/N0 against elevation of real u-blox receivers with their (patch)
antennas, from the logs in ../shared/data/receiver-logs: GPS satellites of
NMEA GSV (elevation, SNR) and UBX NAV-SAT (elev, cno). Prints per log the
mean C/N0 in elevation bins and the least-squares line
C/N0 = zenith + slope (1 - sin el), the form of the link budget's antenna
pattern; and the antenna gains that make the default link budget (EIRP
26.8 dBW, noise figure 2 dB, countryside rise 1 dB) reproduce that line
(docs/models.md, "Receiver profiles"). Only the Python standard library.

Usage: tools/validation/ublox_cn0.py [--data ../shared/data]
"""
import argparse
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import station_days  # noqa: E402  (DEFAULT_DATA)

# log, receiver, what to read
LOGS = [
    ("gpsd/ublox-8.log", "MAX-M8Q (u-blox M8)", "nmea"),
    ("gpsd/ublox-neo-m8n.log", "NEO-M8N (u-blox M8)", "ubx"),
    ("gpsd/ublox-neo-m8t.log", "NEO-M8T (u-blox M8)", "ubx"),
    ("pyubx2/pygpsdata-MIXED.log", "u-blox (NAV-PVT/NAV-SAT, M8 or later)", "ubx"),
    ("gpsd/ublox-neo-m9n-nmea.log", "NEO-M9N (u-blox M9)", "nmea"),
    ("gpsd/ublox-zed-f9p-nmea.log", "ZED-F9P (u-blox F9)", "nmea"),
]

# Link budget defaults of core/signal/link_budget.hpp (LinkBudgetConfig).
EIRP_DBW, NOISE_FIGURE_DB, RISE_DB = 26.8, 2.0, 1.0
N0_DBW_HZ = 10 * math.log10(1.380649e-23 * 290.0)
L1_HZ, C = 1575.42e6, 299792458.0
R_EARTH, H_GPS = 6371.0e3, 20200.0e3


def strip_comments(raw):
    """gpsd logs start with '#' comment lines; the rest is the byte stream."""
    out, pos = bytearray(), 0
    for line in raw.splitlines(keepends=True):
        if pos == 0 and line.startswith(b"#"):
            continue
        pos = 1
        out += line
    return bytes(out)


def nmea_gps_gsv(data):
    """(elevation deg, SNR dB-Hz) of GPS satellites in $GPGSV (and $GNGSV with PRN 1-32)."""
    out = []
    for line in data.split(b"\n"):
        s = line.strip().decode("ascii", "replace")
        i = s.find("$")
        if i < 0:
            continue
        s = s[i:]
        if not (s.startswith("$GPGSV") or s.startswith("$GNGSV")) or "*" not in s:
            continue
        body, cs = s[1:].split("*", 1)
        x = 0
        for ch in body:
            x ^= ord(ch)
        if cs[:2].upper() != f"{x:02X}":
            continue
        f = body.split(",")
        for k in range(4, len(f) - 3, 4):
            try:
                prn, el, snr = int(f[k]), float(f[k + 1]), float(f[k + 3])
            except ValueError:
                continue
            if 1 <= prn <= 32 and snr > 0:
                out.append((el, snr))
    return out


def ubx_nav_sat(data):
    """(elevation deg, cno dB-Hz) of GPS satellites (gnssId 0) in UBX NAV-SAT (0x01 0x35)."""
    out, i = [], 0
    while True:
        i = data.find(b"\xb5\x62", i)
        if i < 0 or i + 8 > len(data):
            return out
        cls, mid, n = data[i + 2], data[i + 3], struct.unpack_from("<H", data, i + 4)[0]
        end = i + 6 + n + 2
        if end > len(data):
            return out
        a = b = 0
        for byte in data[i + 2:i + 6 + n]:
            a = (a + byte) & 0xFF
            b = (b + a) & 0xFF
        if (a, b) == (data[end - 2], data[end - 1]) and cls == 0x01 and mid == 0x35:
            p = data[i + 6:i + 6 + n]
            for k in range(p[5]):
                gnss, sv, cno, elev = struct.unpack_from("<BBBb", p, 8 + 12 * k)
                if gnss == 0 and cno > 0 and elev > 0:
                    out.append((float(elev), float(cno)))
            i = end
        else:
            i += 2


def fit(samples):
    """C/N0 = z + s (1 - sin el): (z, s, rms)."""
    x = [1 - math.sin(math.radians(e)) for e, _ in samples]
    y = [c for _, c in samples]
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((v - mx) ** 2 for v in x)
    s = sum((u - mx) * (v - my) for u, v in zip(x, y)) / sxx if sxx > 0 else 0.0
    z = my - s * mx
    rms = math.sqrt(sum((v - z - s * u) ** 2 for u, v in zip(x, y)) / n)
    return z, s, rms


def gps_range_m(el_deg):
    se = math.sin(math.radians(el_deg))
    r = R_EARTH + H_GPS
    return math.sqrt((R_EARTH * se) ** 2 + r * r - R_EARTH ** 2) - R_EARTH * se


def fspl_db(d):
    return 20 * math.log10(4 * math.pi * d * L1_HZ / C)


def gains_for(z, s):
    """Zenith and horizon antenna gains (dBic) that give C/N0 z at 90 deg and
    z + s at 0 deg in the default link budget (antenna linear in 1 - sin el)."""
    noise = N0_DBW_HZ + NOISE_FIGURE_DB + RISE_DB
    gz = z - EIRP_DBW + fspl_db(gps_range_m(90.0)) + noise
    # The free-space loss grows 2.1 dB from zenith to horizon; the pattern takes the rest.
    gh = z + s - EIRP_DBW + fspl_db(gps_range_m(0.0)) + noise
    return gz, gh


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", default=station_days.DEFAULT_DATA)
    a = ap.parse_args()
    bins = [(5, 15), (15, 30), (30, 45), (45, 60), (60, 90)]
    print("receiver,log,samples," + ",".join(f"el_{lo}_{hi}_dbhz" for lo, hi in bins) +
          ",fit_zenith_dbhz,fit_slope_db,fit_rms_db,antenna_zenith_dbi,antenna_horizon_dbi")
    for path, name, kind in LOGS:
        full = os.path.join(a.data, "receiver-logs", path)
        if not os.path.exists(full):
            print(f"{name},{path},missing")
            continue
        data = strip_comments(open(full, "rb").read())
        samples = nmea_gps_gsv(data) if kind == "nmea" else ubx_nav_sat(data)
        if len(samples) < 10:
            print(f"{name},{path},{len(samples)}")
            continue
        means = []
        for lo, hi in bins:
            v = [c for e, c in samples if lo <= e < hi]
            means.append(f"{sum(v) / len(v):.1f}" if v else "")
        z, s, rms = fit(samples)
        gz, gh = gains_for(z, s)
        print(f"{name},{path},{len(samples)}," + ",".join(means) + f",{z:.1f},{s:.1f},{rms:.1f},{gz:.1f},{gh:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
