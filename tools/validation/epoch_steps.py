#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Epoch-to-epoch behaviour of a static receiver: ours against real u-blox logs.

For each source it prints the median and 95th percentile of
- the horizontal and the vertical step between consecutive fixes (m),
- the reported speed over ground (m/s; the truth is 0, so it is velocity noise),
- the climb a host gets by differencing the altitude (|dAlt| / dt, m/s),
and the number of epochs. Sources:
- ours: `gnssemu batch` on a config (default: config/default.toml) with static
  truth at its [origin], at 1, 5 and 10 Hz (the same config with `rate_hz`
  replaced), NMEA GGA/RMC as a host reads them;
- the real logs in ../shared/data/receiver-logs (static receivers): NMEA GGA
  + RMC (MAX-M8Q, NEO-M9N, ZED-F9P) and UBX NAV-PVT (NEO-M8N at 5 Hz, the
  pyubx2 u-blox 8 log), positions at the resolution each receiver printed.

Usage: tools/validation/epoch_steps.py --gnssemu build/tools/gnssemu/gnssemu
       [--config config/default.toml] [--minutes 60] [--seed N] [--logs DIR]
Only the Python standard library is used.
"""
import argparse
import math
import os
import re
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LOGS = os.path.join(os.path.dirname(ROOT), "shared", "data", "receiver-logs")
KNOT_M_S = 1852.0 / 3600.0
EARTH_R_M = 6371000.0

# (label, path under LOGS, kind)
REAL = [
    ("MAX-M8Q (u-blox 8) NMEA 1 Hz", "gpsd/ublox-8.log", "nmea"),
    ("NEO-M8N NAV-PVT 5 Hz", "gpsd/ublox-neo-m8n.log", "ubx"),
    ("u-blox 8 (pyubx2) NAV-PVT 1 Hz", "pyubx2/pygpsdata-MIXED.log", "ubx"),
    ("NEO-M9N NMEA 1 Hz", "gpsd/ublox-neo-m9n-nmea.log", "nmea"),
    ("ZED-F9P NMEA 1 Hz (29 s)", "gpsd/ublox-zed-f9p-nmea.log", "nmea"),
    ("ZED-F9P NMEA 1 Hz (654 s)", "gpsd/ublox-zed-f9p_hpg1.11.log", "nmea"),
]


def quantile(v, q):
    v = sorted(v)
    if not v:
        return float("nan")
    pos = q * (len(v) - 1)
    i = int(pos)
    f = pos - i
    return v[i] * (1 - f) + v[i + 1] * f if i + 1 < len(v) else v[i]


def nmea_ok(line):
    m = re.match(r"^\$([^*]*)\*([0-9A-Fa-f]{2})\s*$", line)
    if not m:
        return None
    ck = 0
    for ch in m.group(1):
        ck ^= ord(ch)
    return m.group(1).split(",") if ck == int(m.group(2), 16) else None


def hms_s(field):
    return int(field[0:2]) * 3600 + int(field[2:4]) * 60 + float(field[4:])


def coord_deg(value, hemi, deg_digits):
    d = int(value[:deg_digits]) + float(value[deg_digits:]) / 60.0
    return -d if hemi in "SW" else d


def read_nmea(path):
    """Epochs {t_s: [lat, lon, alt, speed]} from GGA (position) and RMC (speed)."""
    epochs = {}
    with open(path, "rb") as f:
        text = f.read().decode("ascii", errors="replace")
    for raw in re.findall(r"\$[^$\r\n]*", text):
        p = nmea_ok(raw)
        if p is None or len(p[0]) != 5:
            continue
        kind = p[0][2:]
        if kind == "GGA" and len(p) > 9 and p[2] and p[6] not in ("", "0"):
            t = hms_s(p[1])
            e = epochs.setdefault(t, [None, None, None, None])
            e[0], e[1], e[2] = coord_deg(p[2], p[3], 2), coord_deg(p[4], p[5], 3), float(p[9])
        elif kind == "RMC" and len(p) > 7 and p[2] == "A" and p[7]:
            epochs.setdefault(hms_s(p[1]), [None, None, None, None])[3] = float(p[7]) * KNOT_M_S
    return {t: e for t, e in epochs.items() if e[0] is not None}


def read_ubx_pvt(path):
    """Epochs {t_s: [lat, lon, hMSL, gSpeed]} from UBX NAV-PVT with a 3D fix."""
    with open(path, "rb") as f:
        data = f.read()
    epochs = {}
    i = 0
    while True:
        i = data.find(b"\xb5\x62\x01\x07", i)
        if i < 0 or i + 6 > len(data):
            break
        n = struct.unpack_from("<H", data, i + 4)[0]
        end = i + 6 + n + 2
        if n < 84 or end > len(data):
            i += 2
            continue
        a = b = 0
        for byte in data[i + 2:i + 6 + n]:
            a = (a + byte) & 0xFF
            b = (b + a) & 0xFF
        if (a, b) != (data[end - 2], data[end - 1]):
            i += 2
            continue
        p = data[i + 6:i + 6 + n]
        itow = struct.unpack_from("<I", p, 0)[0]
        fix_type, flags = p[20], p[21]
        lon, lat, _h, hmsl = struct.unpack_from("<iiii", p, 24)
        gspeed = struct.unpack_from("<i", p, 60)[0]
        if fix_type == 3 and flags & 1:
            epochs[itow / 1000.0] = [lat * 1e-7, lon * 1e-7, hmsl * 1e-3, gspeed * 1e-3]
        i = end
    return epochs


def figures(epochs):
    ts = sorted(epochs)
    h, v, climb, speed = [], [], [], []
    for a, b in zip(ts, ts[1:]):
        dt = b - a
        if dt <= 0 or dt > 1.5:  # consecutive epochs only (rates up to 1 Hz and 0.7 s gaps)
            continue
        p, q = epochs[a], epochs[b]
        lat = math.radians(0.5 * (p[0] + q[0]))
        dn = math.radians(q[0] - p[0]) * EARTH_R_M
        de = math.radians(q[1] - p[1]) * EARTH_R_M * math.cos(lat)
        h.append(math.hypot(de, dn))
        v.append(abs(q[2] - p[2]))
        climb.append(abs(q[2] - p[2]) / dt)
    for t in ts:
        if epochs[t][3] is not None:
            speed.append(epochs[t][3])
    dts = sorted(b - a for a, b in zip(ts, ts[1:]))
    rate = 1.0 / quantile(dts, 0.5) if dts else float("nan")
    return {"n": len(ts), "rate": rate, "h50": quantile(h, 0.5), "h95": quantile(h, 0.95), "v50": quantile(v, 0.5),
            "v95": quantile(v, 0.95), "s50": quantile(speed, 0.5), "s95": quantile(speed, 0.95),
            "c50": quantile(climb, 0.5), "c95": quantile(climb, 0.95)}


def config_origin(text):
    sec = re.search(r"(?ms)^\[origin\](.*?)^\[", text).group(1)
    get = lambda k: float(re.search(rf"(?m)^{k}\s*=\s*([-0-9.eE+]+)", sec).group(1))
    return get("lat_deg"), get("lon_deg"), get("height_m")


def ours(gnssemu, config, rate_hz, seconds, seed, tmp):
    text = open(config).read()
    text = re.sub(r"(?m)^rate_hz\s*=.*$", f"rate_hz = {rate_hz}", text)
    if seed is not None:
        text = re.sub(r"(?m)^seed\s*=.*$", f"seed = {seed}", text)
    # Relative paths in the config stay relative to its folder.
    cfg = os.path.join(os.path.dirname(os.path.abspath(config)), f".epoch_steps_{os.getpid()}_{rate_hz}.toml")
    with open(cfg, "w") as f:
        f.write(text)
    lat, lon, h = config_origin(text)
    truth = os.path.join(tmp, "truth.csv")
    t0 = 522000.0  # 2022-01-01 01:00 GPST: inside the default nav file's day
    with open(truth, "w") as f:
        f.write(f"gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,{t0},{lat},{lon},{h}\n2190,{t0 + seconds},{lat},{lon},{h}\n")
    nmea = os.path.join(tmp, f"out_{rate_hz}.nmea")
    try:
        subprocess.run([gnssemu, "batch", "--config", cfg, "--truth", truth, "--nmea", nmea], check=True,
                       capture_output=True, text=True)
    finally:
        os.remove(cfg)
    return read_nmea(nmea)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--config", default=os.path.join(ROOT, "config", "default.toml"))
    ap.add_argument("--minutes", type=float, default=60.0, help="simulated span at 1 Hz (5 and 10 Hz: a sixth of it)")
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--logs", default=LOGS)
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for rate, span in ((1.0, 60.0 * a.minutes), (5.0, 10.0 * a.minutes), (10.0, 10.0 * a.minutes)):
            e = ours(os.path.abspath(a.gnssemu), a.config, rate, span, a.seed, tmp)
            rows.append((f"ours {os.path.basename(a.config)} {rate:g} Hz", figures(e)))
    for label, rel, kind in REAL:
        path = os.path.join(a.logs, rel)
        if not os.path.exists(path):
            print(f"# missing {path}", file=sys.stderr)
            continue
        rows.append((label, figures(read_nmea(path) if kind == "nmea" else read_ubx_pvt(path))))
    print("source,epochs,rate_hz,h_step_median_m,h_step_p95_m,v_step_median_m,v_step_p95_m,"
          "speed_median_m_s,speed_p95_m_s,climb_median_m_s,climb_p95_m_s")
    for label, f in rows:
        print(f"{label},{f['n']},{f['rate']:.1f},{f['h50']:.3f},{f['h95']:.3f},{f['v50']:.3f},{f['v95']:.3f},"
              f"{f['s50']:.3f},{f['s95']:.3f},{f['c50']:.2f},{f['c95']:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
