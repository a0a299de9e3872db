# SPDX-License-Identifier: Apache-2.0
"""Shared pieces of the integration tests: free loopback ports, and a rig
that owns its processes and temp dir and tears them down even on failure."""
import argparse
import json
import math
import os
import queue
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
import time


def enu_to_latlon(origin, e, n):
    """Small-offset ENU (m) -> lat/lon (deg) at origin (lat deg, lon deg, h m);
    meridian and prime-vertical radii of WGS 84, < 1 mm error at 150 m."""
    lat0 = math.radians(origin[0])
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    w = math.sqrt(1 - e2 * math.sin(lat0) ** 2)
    r_n = a / w
    r_m = a * (1 - e2) / w ** 3
    return (origin[0] + math.degrees(n / (r_m + origin[2])),
            origin[1] + math.degrees(e / ((r_n + origin[2]) * math.cos(lat0))))


def parse_gga(line):
    """(quality, lat deg, lon deg, altitude above sea level m or None) of a $--GGA sentence, or None."""
    f = line.split("*")[0].split(",")
    if len(f) < 7 or not f[0].endswith("GGA") or not f[2] or not f[4]:
        return None
    lat = int(f[2][:2]) + float(f[2][2:]) / 60.0
    lon = int(f[4][:3]) + float(f[4][3:]) / 60.0
    alt = float(f[9]) if len(f) > 9 and f[9] else None
    return int(f[6] or 0), -lat if f[3] == "S" else lat, -lon if f[5] == "W" else lon, alt


def free_port(kind):
    """A port on 127.0.0.1 that is free now (socket.SOCK_DGRAM or SOCK_STREAM)."""
    s = socket.socket(socket.AF_INET, kind)
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def daemon_toml(origin, nav, start, rate_hz, udp_port, timeout_s=2.0, truth_extra="", demo=False):
    """The tables a daemon test starts from: [origin], [nav], [time] start,
    [receiver] rate_hz, [truth] on loopback at udp_port and [demo] (off, or
    on with its defaults); the test appends its own tables."""
    return f"""
[origin]
lat_deg = {origin[0]}
lon_deg = {origin[1]}
height_m = {origin[2]}
[nav]
file = "{os.path.abspath(nav)}"
[time]
start = "{start}"
[receiver]
rate_hz = {rate_hz}
[truth]
bind = "127.0.0.1"
port = {udp_port}
timeout_s = {timeout_s}
{truth_extra}[demo]
enabled = {"true" if demo else "false"}
"""


class RigBase:
    """Processes in their own sessions plus a temp dir. Subclasses set
    self.daemon to the gnssemud process so stop_all() reports its exit code."""

    def __init__(self, prefix):
        self.tmp = tempfile.mkdtemp(prefix=prefix)
        self.procs = []

    def spawn(self, argv, **kw):
        p = subprocess.Popen(argv, start_new_session=True, **kw)
        self.procs.append(p)
        return p

    def stop(self, p):
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
            try:
                p.wait(5)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()

    def stop_all(self):
        """SIGTERM (then SIGKILL) every process, newest first; the daemon's exit code."""
        rc = None
        for p in reversed(self.procs):
            try:
                self.stop(p)
            except ProcessLookupError:
                pass
            if p is getattr(self, "daemon", None):
                rc = p.returncode
        return rc

    def spawn_gpsd(self, path, readonly=True, tag=""):
        """A private gpsd on path (-N foreground, -n poll without clients, -b
        read-only unless readonly is False, own control socket and free
        loopback port in self.gpsd_port, log in gpsd{tag}.log) and gpspipe -w
        on it: the gpspipe process (text stdout). tag tells several apart."""
        gport = free_port(socket.SOCK_STREAM)
        self.gpsd_port = gport
        log = open(os.path.join(self.tmp, f"gpsd{tag}.log"), "w")
        self.spawn(["gpsd", "-N", "-n"] + (["-b"] if readonly else []) +
                   ["-F", os.path.join(self.tmp, f"gpsd{tag}.sock"), "-S", str(gport), "-P",
                    os.path.join(self.tmp, f"gpsd{tag}.pid"), path], stdout=log, stderr=subprocess.STDOUT)
        log.close()  # gpsd holds its own descriptor
        deadline = time.monotonic() + 10
        while True:
            try:
                socket.create_connection(("127.0.0.1", gport), timeout=0.5).close()
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise AssertionError("gpsd did not open its port")
                time.sleep(0.1)
        return self.spawn(["gpspipe", "-w", f"localhost:{gport}"], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, text=True)

    def watch_gpsd(self, stream, on_other=None):
        """Read gpspipe's JSON lines on a thread: TPVs into a queue for
        wait_mode, every other object to on_other(monotonic, message)."""
        self.tpvs = queue.Queue()

        def reader():
            for line in stream:
                try:
                    m = json.loads(line)
                except ValueError:
                    continue
                now = time.monotonic()
                if m.get("class") == "TPV":
                    self.tpvs.put((now, m))
                elif on_other is not None:
                    on_other(now, m)

        threading.Thread(target=reader, daemon=True).start()

    def wait_mode(self, pred, limit_s, what):
        """(monotonic, TPV) of the first TPV from watch_gpsd whose mode pred accepts."""
        deadline = time.monotonic() + limit_s
        while True:
            try:
                t, m = self.tpvs.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise AssertionError(f"no {what} within {limit_s:.0f} s")
            if pred(m.get("mode", 0)):
                return t, m

    def dump_logs(self):
        """Print the tail of every *.log in the temp dir (on failure)."""
        for name in sorted(os.listdir(self.tmp)):
            if name.endswith(".log"):
                print(f"--- {name} ---")
                print(open(os.path.join(self.tmp, name), errors="replace").read()[-3000:])

    def remove_tmp(self):
        shutil.rmtree(self.tmp, ignore_errors=True)


def run_rig(rig, body, limit_s):
    """body(rig) under a limit_s alarm; on AssertionError print FAIL and the
    logs; always tear the rig down. The exit code: 0 passed, 1 failed."""
    signal.signal(signal.SIGALRM, lambda *_: (_ for _ in ()).throw(AssertionError(f"over {limit_s} s")))
    signal.alarm(limit_s)
    ok = False
    try:
        body(rig)
        ok = True
    except AssertionError as e:
        print(f"FAIL: {e}")
    finally:
        signal.alarm(0)
        rig.stop_all()
        if hasattr(rig, "daemon_log"):
            rig.daemon_log.close()
        if not ok:
            rig.dump_logs()
        rig.remove_tmp()
    print("OK" if ok else "FAILED")
    return 0 if ok else 1


def gpsd_daemon_main(make_rig, body, limit_s, tools=("gpsd", "gpspipe", "ubxtool")):
    """main() of a test of gnssemud (--gnssemud, --gnssemu, --nav) seen by
    gpsd: exit 77 (skip) when one of tools is missing, else run_rig."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    args = ap.parse_args()
    for tool in tools:
        if shutil.which(tool) is None:
            print(f"SKIP: {tool} not installed")
            return 77
    return run_rig(make_rig(args), body, limit_s)
