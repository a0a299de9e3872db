#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes config.toml and truth.csv of every pipeline golden case.

The expected files are written by the test itself:
  GNSSEMU_REBUILD_GOLDEN=1 build/tests/test_cli --gtest_filter='PipelineGolden*'
Run this script only to change a case's inputs; then rebuild and review the diff.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
PARIS = (48.8738, 2.2950, 100.0)
ELKO = (40.8, -115.8, 1600.0)
A_WGS84 = 6378137.0
E2_WGS84 = 6.69437999014e-3


def base_config(nav, origin, rate_hz=1.0, mask_deg=5.0, ubx=(), sentences=("RMC", "VTG", "GGA", "GSA", "GSV", "GLL"),
                rates=None, extra=""):
    lat, lon, h = origin
    out = f"""# Pipeline golden case (tests/golden/pipeline/README.md); all other keys at their defaults.
[origin]
lat_deg = {lat}
lon_deg = {lon}
height_m = {h}

[nav]
file = "../../../data/nav/{nav}"

[receiver]
rate_hz = {rate_hz}
elevation_mask_deg = {mask_deg}
seed = 7
{extra}
[[output]]
name = "golden"
type = "pty"
path = "/tmp/gnssemu-golden/gps0"
baud = 115200
ubx_messages = [{", ".join('"%s"' % m for m in ubx)}]
"""
    if sentences is not None:  # None: the emulated device's default set
        out += f"""sentences = [{", ".join('"%s"' % s for s in sentences)}]\n"""
    if rates:
        out += "rates = { " + ", ".join(f"{k} = {v}" for k, v in rates.items()) + " }\n"
    return out


def enu_to_lla(origin, e, n, u):
    """Small-offset local ENU -> geodetic (enough for a test trajectory)."""
    lat0, lon0, h0 = origin
    phi = math.radians(lat0)
    rn = A_WGS84 / math.sqrt(1 - E2_WGS84 * math.sin(phi) ** 2)
    rm = rn * (1 - E2_WGS84) / (1 - E2_WGS84 * math.sin(phi) ** 2)
    return (lat0 + math.degrees(n / (rm + h0)), lon0 + math.degrees(e / ((rn + h0) * math.cos(phi))), h0 + u)


def write(case, config, rows, header):
    d = os.path.join(HERE, case)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "config.toml"), "w") as f:
        f.write(config)
    with open(os.path.join(d, "truth.csv"), "w") as f:
        f.write(header + "\n")
        for r in rows:
            f.write(",".join(r) + "\n")


def static_rows(week, tow0, tow1, origin, step=1.0):
    n = int(round((tow1 - tow0) / step))
    return [[str(week), f"{tow0 + k * step:.1f}", f"{origin[0]:.9f}", f"{origin[1]:.9f}", f"{origin[2]:.3f}"]
            for k in range(n + 1)]


def drive(origin, t0, duration_s, step, legs, start=(0.0, 0.0)):
    """legs: list of (duration_s, speed_m_s, turn_rate_deg_s, accel_m_s2). Returns rows with ENU velocity."""
    rows = []
    e, n = start
    heading = 0.0  # from north
    speed = legs[0][1]
    t = 0.0
    leg_end = 0.0
    leg_i = -1
    dt = step
    steps = int(round(duration_s / step))
    for k in range(steps + 1):
        t = k * step
        while leg_i + 1 < len(legs) and t >= leg_end - 1e-9:
            leg_i += 1
            leg_end += legs[leg_i][0]
        _, _, turn, accel = legs[leg_i]
        lat, lon, h = enu_to_lla(origin, e, n, 0.0)
        ve, vn = speed * math.sin(math.radians(heading)), speed * math.cos(math.radians(heading))
        rows.append(["2190", f"{t0 + t:.1f}", f"{lat:.9f}", f"{lon:.9f}", f"{h:.3f}", f"{ve:.4f}", f"{vn:.4f}", "0.0000"])
        e += ve * dt
        n += vn * dt
        heading = (heading + turn * dt) % 360.0
        speed = max(0.0, speed + accel * dt)
    return rows


def main():
    lla_header = "gps_week,tow_s,lat_deg,lon_deg,height_m"
    all_ubx = ("NAV-PVT", "NAV-POSLLH", "NAV-VELNED", "NAV-STATUS", "NAV-DOP", "NAV-SOL", "NAV-TIMEUTC", "NAV-SAT",
               "NAV-SVINFO", "MON-HW", "NAV-EOE")
    # 1. Static, open sky, every message and sentence, default models.
    write("static_open_sky",
          base_config("brdc0010.22n", PARIS, ubx=all_ubx,
                      sentences=("RMC", "VTG", "GGA", "GSA", "GSV", "GLL", "GST", "ZDA"), rates={"NAV-SVINFO": 5}),
          static_rows(2190, 522000.0, 522180.0, PARIS), lla_header)
    # 2. A vehicle at 10 Hz: straight, a 0.3 g turn, braking to a stop, standing.
    legs = [(8.0, 20.0, 0.0, 0.0), (6.0, 20.0, 8.4, 0.0), (6.0, 20.0, 0.0, -3.4), (10.0, 0.0, 0.0, 0.0)]
    write("moving_10hz",
          base_config("brdc0010.22n", PARIS, rate_hz=10.0, ubx=("NAV-PVT", "NAV-STATUS", "NAV-DOP", "NAV-SAT"),
                      sentences=("RMC", "VTG", "GGA", "GSA", "GSV", "GST"),
                      rates={"NAV-SAT": 10, "GSV": 10, "GSA": 5}),
          drive(PARIS, 523000.0, 30.0, 0.1, legs), lla_header + ",ve_m_s,vn_m_s,vu_m_s")
    # 3. Truth lost for 25 s, then back (antenna disconnected / simulator stalled).
    rows = static_rows(2190, 524000.0, 524040.0, PARIS)
    rows += [["2190", "524041.0", "", "", "", "0"]]
    rows += [r + ["1"] for r in static_rows(2190, 524066.0, 524100.0, PARIS)]
    rows = [r + ["1"] if len(r) == 5 else r for r in rows]
    write("truth_loss",
          base_config("brdc0010.22n", PARIS, ubx=("NAV-PVT", "NAV-STATUS", "NAV-SAT", "MON-HW"),
                      sentences=("RMC", "GGA", "GSA", "GSV", "GST")),
          rows, lla_header + ",valid")
    # 4. Driving north through a street canyon (tests/data/scenes/street_canyon.toml).
    scene = """
[scene]
mesh = "../../../data/scenes/street_canyon.toml"
rays = 256
max_bounces = 2
"""
    legs = [(60.0, 6.0, 0.0, 0.0)]
    write("building_canyon",
          base_config("brdc0010.22n", PARIS, ubx=("NAV-PVT", "NAV-SAT", "NAV-SVINFO"),
                      sentences=("RMC", "GGA", "GSA", "GSV", "GST")) + scene,
          drive(PARIS, 522500.0, 60.0, 1.0, legs, start=(0.0, -180.0)), lla_header + ",ve_m_s,vn_m_s,vu_m_s")
    # 5. A 36 deg mask: 4 satellites, then 3 -> 2D fix on the held height.
    write("fix_2d",
          base_config("brdc0010.22n", PARIS, mask_deg=36.0, ubx=("NAV-PVT", "NAV-DOP", "NAV-SOL"),
                      sentences=("RMC", "GGA", "GSA", "GSV", "GST")),
          static_rows(2190, 522800.0, 523040.0, PARIS), lla_header)
    # 6. Across the GPS week rollover (and UTC midnight 18 s before it), Elko, Nevada, 2018-07-28/29.
    rows = static_rows(2011, 604700.0, 604799.0, ELKO) + static_rows(2012, 0.0, 120.0, ELKO)
    write("week_rollover",
          base_config("ELKO00USA_R_20182100000_01D_MN.rnx", ELKO, ubx=("NAV-PVT", "NAV-TIMEUTC", "NAV-SOL", "NAV-STATUS"),
                      sentences=("RMC", "GGA", "ZDA", "GST")),
          rows, lla_header)
    # 7. Four systems and QZSS (G, R, E, C, J) from the IGS merged broadcast file, 32 channels, Paris,
    #    2024-01-10 01:00 GPST: GLONASS, Galileo, BeiDou (GEOs too) through the shared sky.
    write("four_systems",
          base_config("BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz", PARIS, ubx=("NAV-PVT", "NAV-DOP", "NAV-SAT"),
                      sentences=("RMC", "GGA", "GSA", "GSV", "GST"),
                      extra='constellations = ["G", "R", "E", "C", "J"]\n'
                            'generation = "m9"  # an M8 tracks at most three major systems at once\nmax_channels = 32\n'),
          static_rows(2296, 262800.0, 262920.0, PARIS), lla_header)
    # 8. A NEO-M8N as it ships (GPS + GLONASS + QZSS + SBAS, NMEA 4.0, its default sentences) with the
    #    M8's per-system time messages, Paris, 2024-01-10 02:00 GPST.
    write("m8_gps_glonass",
          base_config("BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz", PARIS, sentences=None,
                      ubx=("NAV-PVT", "NAV-SAT", "NAV-SVINFO", "NAV-TIMEGLO", "NAV-TIMEUTC", "MON-HW",
                           "NAV-EOE"),
                      extra='generation = "m8"\n'),
          static_rows(2296, 266400.0, 266520.0, PARIS), lla_header)
    # 9. A NEO-M9N as it ships (GPS + GLONASS + Galileo + BeiDou + QZSS + SBAS, NMEA 4.10, its default
    #    sentences) with NAV-SIG and every system's time message.
    write("m9_four_systems",
          base_config("BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz", PARIS, sentences=None,
                      ubx=("NAV-PVT", "NAV-SAT", "NAV-SIG", "NAV-TIMEGLO", "NAV-TIMEGAL", "NAV-TIMEBDS",
                           "NAV-TIMEUTC", "MON-RF", "NAV-EOE"),
                      extra='generation = "m9"\n'),
          static_rows(2296, 266400.0, 266520.0, PARIS), lla_header)


if __name__ == "__main__":
    main()
