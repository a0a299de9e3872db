#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Binary truth end to end (docs/truth-protocol.md §Binary record).

Starts gnssemud on a temporary config (NMEA on a pty in a temp dir, free UDP
port, realtime) and reads GGA from the pty. Cases:
  static  the C++ sender (send_truth) sends a point ~4 km from the origin,
          far from the demo circle, as binary LLA records at 50 Hz: GGA
          converges there and stays
  mixed   binary records from one vehicle and JSON from another
          (send_truth.py) on the same port: both accepted, none dropped, the
          binary one drives the fix
  flood   a 2 km circle at 1000 Hz for --flood-seconds with 10 Hz epochs:
          every record sent is accepted, none dropped, no epoch skipped, the
          fixes lie on the circle; prints the figures
Every process is killed and the temp dir removed on exit, also on failure.

usage: truth_binary_integration.py --gnssemud PATH --sender PATH --json-sender PATH --nav FILE CASE
"""
import argparse
import math
import os
import re
import select
import signal
import socket
import subprocess
import sys
import time
import tty

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, parse_gga  # noqa: E402

ORIGIN = (48.8738, 2.2950, 100.0)   # lat deg, lon deg, height m
FAR_LLA = (48.9050, 2.3300, 130.0)  # ~3.5 km north, ~2.6 km east of ORIGIN
TOLERANCE_M = 20.0
FLOOD_RADIUS_M = 2000.0
FLOOD_SPEED_M_S = 20.0
EARTH_RADIUS_M = 6371000.0


def ground_distance_m(lat_a, lon_a, lat_b, lon_b):
    """Haversine distance on a sphere; plenty for a 20 m tolerance."""
    pa, pb = math.radians(lat_a), math.radians(lat_b)
    h = math.sin((pb - pa) / 2) ** 2 + math.cos(pa) * math.cos(pb) * math.sin(math.radians(lon_b - lon_a) / 2) ** 2
    return 2 * EARTH_RADIUS_M * math.asin(math.sqrt(h))


class Rig(RigBase):
    def __init__(self, args, rate_hz):
        super().__init__("gnssemu-truthbin-it-")
        self.args = args
        self.udp_port = free_port(socket.SOCK_DGRAM)
        self.pty = os.path.join(self.tmp, "gps0")
        self.rate_hz = rate_hz
        self.buf = b""
        self.fd = None

    def start(self):
        cfg = os.path.join(self.tmp, "it.toml")
        with open(cfg, "w") as f:
            f.write(f"""
[origin]
lat_deg = {ORIGIN[0]}
lon_deg = {ORIGIN[1]}
height_m = {ORIGIN[2]}
[nav]
file = "{os.path.abspath(self.args.nav)}"
[receiver]
rate_hz = {self.rate_hz}
[truth]
bind = "127.0.0.1"
port = {self.udp_port}
timeout_s = 2.0
max_extrapolation_s = 0.5
[demo]
enabled = true
[[output]]
name = "gps0"
type = "pty"
path = "{self.pty}"
baud = 115200
sentences = ["GGA", "RMC"]
[log]
level = "info"
""")
        self.daemon_log_path = os.path.join(self.tmp, "gnssemud.log")
        self.daemon_log = open(self.daemon_log_path, "w")
        self.daemon = self.spawn([self.args.gnssemud, "--config", cfg], stdout=subprocess.PIPE,
                                 stderr=self.daemon_log, text=True)
        banner = self.daemon.stdout.readline()
        if "NMEA on " + self.pty not in banner:
            raise AssertionError(f"unexpected gnssemud banner: {banner!r}")
        self.fd = os.open(self.pty, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        tty.setraw(self.fd)

    def sender(self, *argv, log="send_truth.log"):
        return self.spawn([self.args.sender, "--port", str(self.udp_port), *argv],
                          stdout=subprocess.DEVNULL, stderr=open(os.path.join(self.tmp, log), "w"))

    def json_sender(self, *argv):
        return self.spawn([sys.executable, self.args.json_sender, "--port", str(self.udp_port), *argv],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def gga(self, deadline):
        """Next (quality, lat, lon, alt) from the pty, or None at the deadline (monotonic s)."""
        while True:
            nl = self.buf.find(b"\n")
            if nl >= 0:
                line, self.buf = self.buf[:nl].decode(errors="replace").strip(), self.buf[nl + 1:]
                fix = parse_gga(line)
                if fix is not None:
                    return fix
                continue
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            r, _, _ = select.select([self.fd], [], [], left)
            if r:
                try:
                    self.buf += os.read(self.fd, 65536)
                except BlockingIOError:
                    pass

    def wait_fix(self, limit_s, predicate, what):
        deadline = time.monotonic() + limit_s
        last = None
        while (fix := self.gga(deadline)) is not None:
            last = fix
            if fix[0] >= 1 and predicate(fix[1], fix[2]):
                return fix
        raise AssertionError(f"no {what} within {limit_s:.0f} s (last GGA {last})")

    def stop_daemon_and_read_log(self):
        self.stop(self.daemon)
        self.daemon_log.flush()
        return open(self.daemon_log_path).read()

    def close(self, failed):
        if self.fd is not None:
            os.close(self.fd)
        rc = self.stop_all()
        self.daemon_log.close()
        if failed:
            self.dump_logs()
        self.remove_tmp()
        return rc


def daemon_cpu_s(pid):
    """User + system CPU time of a process so far, s (Linux /proc)."""
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def truth_summary(log):
    """(accepted, dropped, epochs, skipped) from the daemon's exit summary."""
    m = re.search(r"truth: (\d+) packets accepted, (\d+) dropped; (\d+) epochs, (\d+) skipped", log)
    if not m:
        raise AssertionError("no truth summary in the daemon log")
    return tuple(int(x) for x in m.groups())


def converge_on_far_point(rig):
    near = lambda lat, lon: ground_distance_m(lat, lon, FAR_LLA[0], FAR_LLA[1]) <= TOLERANCE_M
    rig.wait_fix(20, near, f"GGA within {TOLERANCE_M:.0f} m of the far point")
    for _ in range(4):  # not a lucky one: the next fixes stay there
        q, lat, lon, _ = rig.wait_fix(5, lambda *_: True, "GGA with a fix")
        d = ground_distance_m(lat, lon, FAR_LLA[0], FAR_LLA[1])
        assert d <= TOLERANCE_M, f"fix {d:.1f} m from the far point"
    return d


def case_static(rig):
    rig.start()
    rig.sender("--vehicle", "bin", "--rate", "50", "static", "--lla", *(f"{x:.9f}" for x in FAR_LLA))
    d = converge_on_far_point(rig)
    log = rig.stop_daemon_and_read_log()
    accepted, dropped, _, _ = truth_summary(log)
    assert accepted > 0 and dropped == 0, f"{accepted} accepted, {dropped} dropped"
    print(f"  static: GGA {d:.1f} m from the binary truth ~4 km away; {accepted} records accepted, 0 dropped")


def case_mixed(rig):
    rig.start()
    rig.sender("--vehicle", "bin", "--rate", "50", "static", "--lla", *(f"{x:.9f}" for x in FAR_LLA))
    rig.wait_fix(20, lambda lat, lon: ground_distance_m(lat, lon, *FAR_LLA[:2]) <= TOLERANCE_M, "binary fix")
    rig.json_sender("--vehicle", "json", "--rate", "20", "static", "--enu", "10", "10", "0")
    d = converge_on_far_point(rig)  # JSON from another vehicle does not move the fix
    log = rig.stop_daemon_and_read_log()
    accepted, dropped, _, _ = truth_summary(log)
    for vehicle in ("bin", "json"):
        assert f"truth: vehicle '{vehicle}' from" in log, f"vehicle {vehicle} never accepted"
    assert "drives the receiver" in log and "'bin' drives" in log, "binary vehicle does not drive"
    assert dropped == 0, f"{dropped} dropped"
    print(f"  mixed: binary and JSON vehicles both accepted ({accepted} packets, 0 dropped); fix {d:.1f} m from "
          "the binary truth")


def case_flood(rig):
    rig.start()
    duration = rig.args.flood_seconds
    sender = rig.sender("--vehicle", "flood", "--rate", "1000", "--duration", str(duration),
                        "circle", "--radius", str(FLOOD_RADIUS_M), "--speed", str(FLOOD_SPEED_M_S))
    on_circle = lambda lat, lon: abs(ground_distance_m(lat, lon, *ORIGIN[:2]) - FLOOD_RADIUS_M) <= TOLERANCE_M
    rig.wait_fix(20, on_circle, "GGA on the 2 km circle")
    fixes = 0
    deadline = time.monotonic() + duration - 3.0
    while time.monotonic() < deadline:
        q, lat, lon, _ = rig.wait_fix(5, lambda *_: True, "GGA with a fix")
        r = ground_distance_m(lat, lon, *ORIGIN[:2])
        assert abs(r - FLOOD_RADIUS_M) <= TOLERANCE_M, f"fix {r:.1f} m from the origin during the flood"
        fixes += 1
    sender.wait(duration + 10)
    cpu_s = daemon_cpu_s(rig.daemon.pid)
    sent_line = open(os.path.join(rig.tmp, "send_truth.log")).read().strip()
    m = re.search(r"(\d+) records sent in ([\d.]+) s .* (\d+) send errors, (\d+) more than one period late, "
                  r"latest ([\d.]+) ms", sent_line)
    assert m, f"sender summary: {sent_line!r}"
    sent, elapsed, errors, late, latest_ms = int(m[1]), float(m[2]), int(m[3]), int(m[4]), float(m[5])
    log = rig.stop_daemon_and_read_log()
    accepted, dropped, epochs, skipped = truth_summary(log)
    late_warnings = log.count("epoch loop late")
    print(f"  flood: sent {sent} records in {elapsed:.1f} s ({sent / elapsed:.0f}/s; {errors} send errors, "
          f"{late} sent > 1 ms late, latest {latest_ms:.1f} ms)")
    print(f"  flood: daemon accepted {accepted}, dropped {dropped}; {epochs} epochs, {skipped} skipped, "
          f"{late_warnings} late-loop warnings; {fixes} fixes on the circle during the flood; "
          f"daemon CPU {cpu_s:.2f} s in total")
    assert errors == 0 and sent >= 0.95 * 1000 * duration, f"sender reached only {sent} records"
    assert accepted == sent and dropped == 0, f"sent {sent}, accepted {accepted}, dropped {dropped}"
    assert skipped == 0 and late_warnings == 0, f"{skipped} epochs skipped"


CASES = {"static": (case_static, 1.0), "mixed": (case_mixed, 1.0), "flood": (case_flood, 10.0)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--sender", required=True, help="send_truth (C++)")
    ap.add_argument("--json-sender", required=True, help="send_truth.py")
    ap.add_argument("--nav", required=True)
    ap.add_argument("--flood-seconds", type=float, default=10.0)
    ap.add_argument("case", choices=sorted(CASES))
    args = ap.parse_args()
    run, rate_hz = CASES[args.case]
    limit_s = 60 + (args.flood_seconds if args.case == "flood" else 0)

    def on_alarm(*_):
        raise AssertionError(f"case exceeded {limit_s:.0f} s")

    rig = Rig(args, rate_hz)
    signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(int(limit_s))
    ok = False
    try:
        print(f"case {args.case}:")
        run(rig)
        ok = True
    except AssertionError as e:
        print(f"FAIL {args.case}: {e}")
    finally:
        signal.alarm(0)
        daemon_rc = rig.close(failed=not ok)
    if ok and daemon_rc != 0:
        print(f"FAIL {args.case}: gnssemud exited {daemon_rc} on SIGTERM (want 0)")
        ok = False
    print(f"{'PASS' if ok else 'FAIL'} {args.case}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
