#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemud + gpsd end-to-end test (docs/daemon.md §Integration test).

Starts gnssemud on a temporary config (pty symlink in a temp dir, free UDP
port, 2 Hz), a private gpsd on that pty (own control socket, free TCP port,
loopback only, read-only -b), and reads gpspipe -w. Cases:
  demo   - no simulator: TPV mode 3 within 20 m of the demo truth at the TPV's time
  static - the Python sender sends a static point: TPV mode 3 within 20 m of it
  loss   - static, then the sender stops: within timeout + 2 s gpsd
           reports mode <= 1 (the receiver lost its antenna: it extrapolates
           but flags no fix; no frozen fix)
  today  - the default daemon (no --config: the shipped default.toml with its
           2024 multi-GNSS nav file): TPV time within 2 s of the system clock, mode 3
Every process is killed and the temp dir removed on exit, also on failure.

usage: gpsd_integration.py --gnssemud PATH --nav FILE --sender PATH CASE
"""
import argparse
import datetime
import json
import math
import os
import queue
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, daemon_toml, free_port, enu_to_latlon as itlib_enu_to_latlon  # noqa: E402

ORIGIN = (48.8738, 2.2950, 100.0)  # lat deg, lon deg, height m
RADIUS_M = 50.0
TIMEOUT_S = 2.0
RATE_HZ = 2.0
TOLERANCE_M = 20.0
CASE_LIMIT_S = 60.0
STATIC_ENU = (120.0, -80.0, 0.0)  # metres from the origin; far from the demo circle
DEMO_SPEED_M_S = 5.0
# Fixed epoch clock start (GPS time) so the demo truth at any TPV time is known.
START_GPS = "2022-01-01T01:00:00"
START_GPS_EPOCH_S = 1640998800.0  # the same instant as Unix seconds of the GPS calendar
MAX_EXTRAPOLATION = "max_extrapolation_s = 0.5\n"  # [truth] line of these cases
GPS_MINUS_UTC_S = 18.0            # LEAP SECONDS in brdc0010.22n


def enu_to_latlon(e, n):
    return itlib_enu_to_latlon(ORIGIN, e, n)


def horizontal_m(lat_a, lon_a, lat_b, lon_b):
    lat0 = math.radians(ORIGIN[0])
    dn = math.radians(lat_a - lat_b) * 6371000.0
    de = math.radians(lon_a - lon_b) * 6371000.0 * math.cos(lat0)
    return math.hypot(de, dn)


class Rig(RigBase):
    """gnssemud + gpsd + gpspipe in a temp dir; everything torn down by close()."""

    def __init__(self, args):
        super().__init__("gnssemu-it-")
        self.args = args
        self.lines = queue.Queue()
        self.udp_port = free_port(socket.SOCK_DGRAM)
        self.gpsd_port = free_port(socket.SOCK_STREAM)
        self.pty = os.path.join(self.tmp, "gps0")

    def start(self, default_config=False):
        cfg = os.path.join(self.tmp, "it.toml")
        with open(cfg, "w") as f:
            f.write(f"""{daemon_toml(ORIGIN, self.args.nav, START_GPS, RATE_HZ, self.udp_port, timeout_s=TIMEOUT_S,
                                   truth_extra=MAX_EXTRAPOLATION, demo=True)}radius_m = {RADIUS_M}
speed_m_s = {DEMO_SPEED_M_S}
[[output]]
name = "gps0"
type = "pty"
path = "{self.pty}"
[log]
level = "info"
""")
        self.daemon_log = open(os.path.join(self.tmp, "gnssemud.log"), "w")
        # The default daemon keeps its built-in configuration; only the pty
        # and the truth port move to this test's own.
        argv = ["--pty", self.pty, "--truth-port", str(self.udp_port)] if default_config else ["--config", cfg]
        self.daemon = self.spawn([self.args.gnssemud, *argv], stdout=subprocess.PIPE,
                                 stderr=self.daemon_log, text=True)
        banner = self.daemon.stdout.readline()
        if "NMEA on " + self.pty not in banner:
            raise AssertionError(f"unexpected gnssemud banner: {banner!r}")
        print("  " + banner.strip())
        # -N foreground, -n poll without clients, -b read-only (never write
        # probes to our pty), -F private control socket, -S private port.
        # gpsd binds only the loopback unless -G is given.
        self.gpsd_log = open(os.path.join(self.tmp, "gpsd.log"), "w")
        self.spawn(["gpsd", "-N", "-n", "-b", "-F", os.path.join(self.tmp, "gpsd.sock"),
                    "-S", str(self.gpsd_port), "-P", os.path.join(self.tmp, "gpsd.pid"), self.pty],
                   stdout=self.gpsd_log, stderr=subprocess.STDOUT)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            try:
                socket.create_connection(("127.0.0.1", self.gpsd_port), timeout=0.5).close()
                break
            except OSError:
                time.sleep(0.1)
        else:
            raise AssertionError("gpsd did not open its port")
        pipe = self.spawn(["gpspipe", "-w", f"localhost:{self.gpsd_port}"], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, text=True)
        threading.Thread(target=self._reader, args=(pipe.stdout,), daemon=True).start()

    def _reader(self, stream):
        for line in stream:
            try:
                msg = json.loads(line)
            except ValueError:
                continue
            if msg.get("class") == "TPV":
                self.lines.put((time.monotonic(), msg))

    def tpv(self, deadline):
        """Next TPV, or None at the deadline (monotonic s)."""
        try:
            return self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            return None

    def sender(self, *extra):
        return self.spawn([sys.executable, self.args.sender, "--port", str(self.udp_port),
                           "--rate", "10", "--vehicle", "it", *extra])

    def close(self, failed):
        daemon_rc = self.stop_all()
        for f in ("daemon_log", "gpsd_log"):
            if hasattr(self, f):
                getattr(self, f).close()
        if failed:
            self.dump_logs()
        link_left = os.path.lexists(self.pty)
        self.remove_tmp()
        return daemon_rc, link_left


def wait_for(rig, limit_s, predicate, what):
    """First TPV within limit_s for which predicate holds; fails otherwise."""
    deadline = time.monotonic() + limit_s
    seen = 0
    last = None
    while True:
        item = rig.tpv(deadline)
        if item is None:
            raise AssertionError(f"no {what} within {limit_s:.0f} s ({seen} TPVs seen, last {last})")
        seen += 1
        last = item[1]
        if predicate(item[1]):
            return item


def demo_truth_latlon(tpv_time):
    """Where the demo circle puts the antenna at a TPV's UTC time."""
    utc = datetime.datetime.strptime(tpv_time[:19], "%Y-%m-%dT%H:%M:%S").replace(tzinfo=datetime.timezone.utc)
    frac = float("0" + tpv_time[19:].rstrip("Z")) if len(tpv_time) > 20 else 0.0
    elapsed = utc.timestamp() + frac + GPS_MINUS_UTC_S - START_GPS_EPOCH_S
    a = DEMO_SPEED_M_S / RADIUS_M * elapsed  # counter-clockwise from due east
    return enu_to_latlon(RADIUS_M * math.cos(a), RADIUS_M * math.sin(a))


def case_demo(rig):
    def near_truth(m):
        if m.get("mode") != 3:
            return False
        lat, lon = demo_truth_latlon(m["time"])
        return horizontal_m(m["lat"], m["lon"], lat, lon) <= TOLERANCE_M
    _, m = wait_for(rig, 20, near_truth, "mode-3 TPV within 20 m of the demo truth")
    assert m["time"].startswith("2022-01-01T"), f"gpsd time {m['time']} (nav file is 2022-01-01)"
    # Not a lucky one: the following fixes follow the moving truth too.
    for _ in range(4):
        _, m = wait_for(rig, 5, lambda x: x.get("mode") == 3 and "time" in x, "TPV")
        lat, lon = demo_truth_latlon(m["time"])
        d = horizontal_m(m["lat"], m["lon"], lat, lon)
        assert d <= TOLERANCE_M, f"demo fix {d:.1f} m from the demo truth at {m['time']}"
    assert m.get("speed", 0) > 3.0, f"demo speed {m.get('speed')} m/s, expected ~{DEMO_SPEED_M_S}"
    print(f"  demo: mode 3 at {d:.1f} m from the demo truth, gpsd time {m['time']}")


def start_static(rig):
    lat, lon = enu_to_latlon(STATIC_ENU[0], STATIC_ENU[1])
    p = rig.sender("static", "--lat", f"{lat:.9f}", "--lon", f"{lon:.9f}", "--height", f"{ORIGIN[2]}")
    near = lambda m: m.get("mode") == 3 and horizontal_m(m["lat"], m["lon"], lat, lon) <= TOLERANCE_M
    _, m = wait_for(rig, 20, near, "mode-3 TPV within 20 m of the static point")
    # Not a lucky one: the next 4 fixes stay there too.
    for _ in range(4):
        _, m = wait_for(rig, 5, lambda x: True, "TPV")
        assert m.get("mode") == 3, f"lost the fix while truth is sent: {m}"
        d = horizontal_m(m["lat"], m["lon"], lat, lon)
        assert d <= TOLERANCE_M, f"fix {d:.1f} m from the static truth"
        assert abs(m["altHAE"] - ORIGIN[2]) < 3 * TOLERANCE_M, f"height {m['altHAE']} vs {ORIGIN[2]}"
    print(f"  static: mode 3 at {d:.1f} m from the truth point")
    return p


def case_static(rig):
    start_static(rig)


def case_loss(rig):
    p = start_static(rig)
    rig.stop(p)
    t_stop = time.monotonic()
    # The receiver coasts on its filter after the signals are gone but flags
    # that as no fix ([receiver.nav] coast_report = "no_fix").
    limit = TIMEOUT_S + 2.0
    # Drain what gpsd reported before the stop took effect, then demand no fix.
    t, m = wait_for(rig, limit + 5, lambda x: x.get("mode", 0) <= 1, "TPV with mode <= 1 after truth stopped")
    # gpsd reports what the pty carried; allow one epoch of gpsd/pty latency.
    latency = t - t_stop
    assert latency <= limit + 1.0 / RATE_HZ, f"no fix only after {latency:.1f} s (limit {limit} s)"
    print(f"  loss: mode {m.get('mode')} {latency:.1f} s after the sender stopped (timeout {TIMEOUT_S} s)")
    # And it stays lost: no frozen fix.
    deadline = time.monotonic() + 3
    while (item := rig.tpv(deadline)) is not None:
        assert item[1].get("mode", 0) <= 1, f"fix came back without truth: {item[1]}"


def tpv_unix_s(tpv_time):
    """Unix seconds of a TPV time string ("2026-11-24T10:33:28.000Z")."""
    utc = datetime.datetime.strptime(tpv_time[:19], "%Y-%m-%dT%H:%M:%S").replace(tzinfo=datetime.timezone.utc)
    frac = float("0" + tpv_time[19:].rstrip("Z")) if len(tpv_time) > 20 else 0.0
    return utc.timestamp() + frac


def case_today(rig):
    _, m = wait_for(rig, 20, lambda x: x.get("mode") == 3 and "time" in x, "mode-3 TPV from the default daemon")
    worst = 0.0
    for _ in range(5):
        _, m = wait_for(rig, 5, lambda x: x.get("mode") == 3 and "time" in x, "mode-3 TPV")
        off = tpv_unix_s(m["time"]) - time.time()
        worst = max(worst, abs(off))
        assert abs(off) <= 2.0, f"gpsd time {m['time']} is {off:+.2f} s from the system clock"
    today = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
    assert m["time"][:10] in (today, (datetime.datetime.now(datetime.timezone.utc) -
                                      datetime.timedelta(seconds=5)).strftime("%Y-%m-%d")), m["time"]
    if "leapseconds" in m:
        assert m["leapseconds"] == 18, f"leap seconds {m['leapseconds']}"
    with open(rig.daemon_log.name) as f:
        log = f.read()
    assert "nav data moved" in log, "the daemon did not say it moved the shipped 2024 nav data to today"
    print(f"  today: mode 3, gpsd time {m['time']}, at most {worst:.2f} s from the system clock")


def on_alarm(*_):
    raise AssertionError(f"case exceeded {CASE_LIMIT_S:.0f} s")


CASES = {"demo": case_demo, "static": case_static, "loss": case_loss, "today": case_today}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--sender", required=True)
    ap.add_argument("case", choices=sorted(CASES) + ["all"])
    args = ap.parse_args()
    for tool in ("gpsd", "gpspipe"):
        if shutil.which(tool) is None:
            print(f"SKIP: {tool} not installed")
            return 77
    failed = False
    for name in (sorted(CASES) if args.case == "all" else [args.case]):
        rig = Rig(args)
        signal.signal(signal.SIGALRM, on_alarm)
        signal.alarm(int(CASE_LIMIT_S))
        ok = False
        try:
            print(f"case {name}:")
            rig.start(default_config=name == "today")
            CASES[name](rig)
            ok = True
        except AssertionError as e:
            print(f"FAIL {name}: {e}")
        finally:
            signal.alarm(0)
            daemon_rc, link_left = rig.close(failed=not ok)
        if ok and daemon_rc != 0:
            print(f"FAIL {name}: gnssemud exited {daemon_rc} on SIGTERM (want 0)")
            ok = False
        if ok and link_left:
            print(f"FAIL {name}: gnssemud left its pty symlink behind")
            ok = False
        print(f"{'PASS' if ok else 'FAIL'} {name}")
        failed |= not ok
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
