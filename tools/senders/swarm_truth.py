#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Truth for a swarm: N vehicles v0 .. v{N-1} (gnssemud's [fleet] ids) flying
one circle in formation, one JSON datagram per vehicle per tick.

  swarm_truth.py --count 3 [--formation line|vee|grid] [--spacing 10] [--radius 100]
                 [--speed 10] [--up 30] [--rate 10] [--duration 0] [--host 127.0.0.1] [--port 5500]

The formation's centre goes round a circle of --radius m about the local
origin ([origin] of the daemon) at --speed m/s, --up m above it; vehicle k
keeps its slot in the formation's body frame (x ahead, y right): `line`
abreast (k * spacing to the right of the leader), `vee` (alternately left
and right, one spacing behind per pair) or `grid` (rows of ceil(sqrt(N))).
Positions are local ENU, velocities the slot's own along the circle.
"""
import argparse
import math
import os
import socket
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from send_truth import packet, paced  # noqa: E402


def slot(k, n, formation, spacing):
    """Vehicle k's (ahead, right) offset from the formation's centre, m."""
    if formation == "line":
        return 0.0, (k - (n - 1) / 2.0) * spacing
    if formation == "vee":
        if k == 0:
            return 0.0, 0.0
        pair = (k + 1) // 2
        side = 1.0 if k % 2 else -1.0
        return -pair * spacing, side * pair * spacing
    cols = max(1, math.ceil(math.sqrt(n)))
    return -(k // cols) * spacing, (k % cols - (cols - 1) / 2.0) * spacing


def states(t, n, a):
    """(vehicle id, (e, n, u), (ve, vn, vu)) of every vehicle at sim time t."""
    w = a.speed / a.radius  # rad/s, counter-clockwise seen from above
    th = w * t
    ce, cn = a.radius * math.cos(th), a.radius * math.sin(th)
    fe, fn = -math.sin(th), math.cos(th)  # heading of the centre
    re, rn = fn, -fe                      # its right
    out = []
    for k in range(n):
        ahead, right = slot(k, n, a.formation, a.spacing)
        e = ce + ahead * fe + right * re
        nn = cn + ahead * fn + right * rn
        # Rigid rotation about the circle's centre: v = w x r.
        out.append((f"v{k}", (e, nn, a.up), (-w * nn, w * e, 0.0)))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=5500)
    p.add_argument("--count", type=int, default=3, help="vehicles v0 .. v{count-1}")
    p.add_argument("--formation", choices=["line", "vee", "grid"], default="vee")
    p.add_argument("--spacing", type=float, default=10.0, help="m between slots")
    p.add_argument("--radius", type=float, default=100.0, help="m, the formation centre's circle")
    p.add_argument("--speed", type=float, default=10.0, help="m/s of the centre")
    p.add_argument("--up", type=float, default=30.0, help="m above the origin")
    p.add_argument("--rate", type=float, default=10.0, help="ticks per second")
    p.add_argument("--duration", type=float, default=0.0, help="seconds to send, 0 = forever")
    a = p.parse_args()
    if a.count < 1 or a.radius <= 0 or a.rate <= 0:
        sys.exit("swarm_truth: --count >= 1, --radius > 0 and --rate > 0")
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    for t in paced(a.rate, a.duration):
        for vid, (e, n, u), vel in states(t, a.count, a):
            s.sendto(packet(vid, t, "enu", {"e_m": e, "n_m": n, "u_m": u}, vel), (a.host, a.port))
    return 0


if __name__ == "__main__":
    sys.exit(main())
