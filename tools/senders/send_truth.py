#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Example truth sender for gnssemud (docs/truth-protocol.md). Stdlib only.

  send_truth.py static --lat 48.8738 --lon 2.295 --height 100
  send_truth.py static --enu 10 -20 0
  send_truth.py circle --radius 30 --speed 5            # ENU circle around the configured origin
  send_truth.py csv track.csv                            # replay: sim_time_s + lla/enu/ecef columns

Common options: --host, --port, --rate (Hz), --vehicle, --duration (s, 0 = forever).
"""
import argparse
import csv
import json
import math
import socket
import sys
import time

VERSION = 1


def packet(vehicle, sim_time_s, pos_key, pos, vel_enu=None):
    """One datagram: pos_key is 'lla', 'enu' or 'ecef'; pos the matching dict."""
    msg = {"version": VERSION, "vehicle": vehicle, "sim_time_s": sim_time_s, pos_key: pos}
    if vel_enu is not None:
        msg["vel_enu"] = {"e_m_s": vel_enu[0], "n_m_s": vel_enu[1], "u_m_s": vel_enu[2]}
    # allow_nan=False: NaN is not JSON; fail here rather than have the daemon drop it.
    return json.dumps(msg, allow_nan=False).encode()


def paced(rate_hz, duration_s):
    """Yields sim times on an absolute schedule (no drift)."""
    period = 1.0 / rate_hz
    t0 = time.monotonic()
    k = 0
    while duration_s <= 0 or k * period <= duration_s:
        delay = t0 + k * period - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        yield k * period
        k += 1


def run_static(args, send):
    if args.enu is not None:
        key, pos = "enu", {"e_m": args.enu[0], "n_m": args.enu[1], "u_m": args.enu[2]}
    elif args.lat is not None and args.lon is not None:
        key, pos = "lla", {"lat_deg": args.lat, "lon_deg": args.lon, "height_m": args.height}
    else:
        sys.exit("static: give --lat/--lon[/--height] or --enu E N U")
    for t in paced(args.rate, args.duration):
        send(packet(args.vehicle, args.sim_start + t, key, pos, (0.0, 0.0, 0.0)))


def run_circle(args, send):
    w = args.speed / args.radius
    for t in paced(args.rate, args.duration):
        a = w * t
        pos = {"e_m": args.radius * math.cos(a), "n_m": args.radius * math.sin(a), "u_m": args.up}
        vel = (-args.speed * math.sin(a), args.speed * math.cos(a), 0.0)
        send(packet(args.vehicle, args.sim_start + t, "enu", pos, vel))


def run_csv(args, send):
    with open(args.file, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{args.file}: no rows")
    cols = set(rows[0].keys())
    for key, names in (("lla", ("lat_deg", "lon_deg", "height_m")), ("enu", ("e_m", "n_m", "u_m")),
                       ("ecef", ("x_m", "y_m", "z_m"))):
        if set(names) <= cols:
            break
    else:
        sys.exit(f"{args.file}: need columns lat_deg,lon_deg,height_m or e_m,n_m,u_m or x_m,y_m,z_m")
    if "sim_time_s" not in cols:
        sys.exit(f"{args.file}: need a sim_time_s column")
    has_vel = {"ve_m_s", "vn_m_s", "vu_m_s"} <= cols
    t0_sim = float(rows[0]["sim_time_s"])
    t0 = time.monotonic()
    for line, row in enumerate(rows, start=2):
        try:
            sim = float(row["sim_time_s"])
            pos = {n: float(row[n]) for n in names}
            vel = tuple(float(row[c]) for c in ("ve_m_s", "vn_m_s", "vu_m_s")) if has_vel else None
        except (TypeError, ValueError) as e:
            sys.exit(f"{args.file}:{line}: {e}")
        delay = t0 + (sim - t0_sim) / args.speedup - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        send(packet(args.vehicle, sim, key, pos, vel))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=5500)
    p.add_argument("--vehicle", default="ego")
    p.add_argument("--rate", type=float, default=10.0, help="packets per second (static, circle)")
    p.add_argument("--duration", type=float, default=0.0, help="seconds to send, 0 = forever")
    p.add_argument("--sim-start", type=float, default=0.0, help="sim_time_s of the first packet")
    sub = p.add_subparsers(dest="mode", required=True)
    s = sub.add_parser("static", help="a fixed point")
    s.add_argument("--lat", type=float)
    s.add_argument("--lon", type=float)
    s.add_argument("--height", type=float, default=0.0)
    s.add_argument("--enu", type=float, nargs=3, metavar=("E", "N", "U"))
    c = sub.add_parser("circle", help="a circle around the configured origin (ENU)")
    c.add_argument("--radius", type=float, default=30.0)
    c.add_argument("--speed", type=float, default=5.0)
    c.add_argument("--up", type=float, default=0.0)
    r = sub.add_parser("csv", help="replay a CSV file at its own pace")
    r.add_argument("file")
    r.add_argument("--speedup", type=float, default=1.0)
    args = p.parse_args()

    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    dest = (args.host, args.port)

    def send(data):
        sock.sendto(data, dest)

    try:
        {"static": run_static, "circle": run_circle, "csv": run_csv}[args.mode](args, send)
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
