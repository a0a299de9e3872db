#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Truth trajectory for the Paris evidence drive (docs/benchmarks.md).

Avenue de la Grande Armee -> Place Charles de Gaulle ring (counter-clockwise,
radius 110 m around the Arc) -> Avenue des Champs-Elysees, then back, twice.
Local frame: ENU with the Arc de Triomphe at the origin (48.87378 N,
2.29503 E, Wikipedia), i.e. the configs' [origin]; the etoile scene is
placed with offset_m = [127.37, -38.10, 0] (the Arc's centre in the scene's
own frame is (-127.37, 38.10); its x is east, y north: the Arc's facade runs
at bearing 24.6 deg, the Champs-Elysees axis at 115 deg as on the map).

usage: paris_drive.py OUT.csv [speed_m_s] [rate_hz]
"""
import math
import sys

LAT0, LON0, H0 = 48.87378, 2.29503, 100.0   # ground at the Arc, ellipsoidal
ANTENNA_M = 1.5
WEEK, TOW0 = 2190, 561600.0                  # 2022-01-01 12:00 GPST (brdc0010.22n)
A, F = 6378137.0, 1.0 / 298.257223563
E2 = F * (2.0 - F)


def ecef(lat, lon, h):
    s, c = math.sin(lat), math.cos(lat)
    n = A / math.sqrt(1.0 - E2 * s * s)
    return ((n + h) * c * math.cos(lon), (n + h) * c * math.sin(lon), (n * (1.0 - E2) + h) * s)


def lla(x, y, z):
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1.0 - E2))
    for _ in range(10):
        s = math.sin(lat)
        n = A / math.sqrt(1.0 - E2 * s * s)
        h = p / math.cos(lat) - n
        lat = math.atan2(z, p * (1.0 - E2 * n / (n + h)))
    s = math.sin(lat)
    n = A / math.sqrt(1.0 - E2 * s * s)
    return lat, lon, p / math.cos(lat) - n


def enu_to_lla(e, n, u):
    lat0, lon0 = math.radians(LAT0), math.radians(LON0)
    x0, y0, z0 = ecef(lat0, lon0, H0)
    sl, cl, so, co = math.sin(lat0), math.cos(lat0), math.sin(lon0), math.cos(lon0)
    dx = -so * e - sl * co * n + cl * co * u
    dy = co * e - sl * so * n + cl * so * u
    dz = cl * n + sl * u
    lat, lon, h = lla(x0 + dx, y0 + dy, z0 + dz)
    return math.degrees(lat), math.degrees(lon), h


def polar(bearing_deg, d_m):
    b = math.radians(bearing_deg)
    return (d_m * math.sin(b), d_m * math.cos(b))


def route():
    pts = [polar(295.0, d) for d in range(300, 110, -5)]
    pts += [polar(b, 110.0) for b in range(295, 114, -2)]    # counter-clockwise round the Arc
    pts += [polar(115.0, d) for d in range(110, 421, 5)]
    return pts


def main():
    out = sys.argv[1]
    speed = float(sys.argv[2]) if len(sys.argv) > 2 else 8.0
    rate = float(sys.argv[3]) if len(sys.argv) > 3 else 1.0
    one = route()
    path = one + one[::-1][1:] + one[1:] + one[::-1][1:]
    # Resample at constant speed.
    samples, t, carry = [], 0.0, 0.0
    step = speed / rate
    for (e0, n0), (e1, n1) in zip(path, path[1:]):
        seg = math.hypot(e1 - e0, n1 - n0)
        s = carry
        while s < seg:
            f = s / seg
            samples.append((e0 + f * (e1 - e0), n0 + f * (n1 - n0), (e1 - e0) / seg * speed, (n1 - n0) / seg * speed))
            s += step
        carry = s - seg
    with open(out, "w") as f:
        f.write("gps_week,tow_s,lat_deg,lon_deg,height_m,ve_m_s,vn_m_s,vu_m_s\n")
        for k, (e, n, ve, vn) in enumerate(samples):
            lat, lon, h = enu_to_lla(e, n, ANTENNA_M)
            f.write(f"{WEEK},{TOW0 + k / rate:.3f},{lat:.9f},{lon:.9f},{h:.3f},{ve:.3f},{vn:.3f},0.000\n")
    print(f"{len(samples)} epochs, {len(samples) / rate:.0f} s, {out}")


if __name__ == "__main__":
    main()
