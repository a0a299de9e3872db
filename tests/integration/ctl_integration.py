#!/usr/bin/env python3
"""Live faults through gnssemud's control socket, seen by a real gpsd
(docs/faults.md, docs/daemon.md §Control socket).

gnssemud (demo truth, UBX + NMEA on a pty, [control] socket in a temp dir,
--scenario with an outage at 12 s for 4 s), a private gpsd on the pty and
gpspipe -w. Steps, each timed from the moment the command returned:
  1. mode 3; `gnssemu ctl status` lists the scenario's outage as pending,
     the fix and satellites with C/N0 and state
  2. the scenario's outage: TPV mode <= 1, then mode 3 again
  3. `ctl inject` an outage: mode <= 1 within 2 s (the receiver extrapolates
     but flags it no fix, [receiver.nav] coast_report); status shows it
     active; `ctl clear`: mode 3 back through reacquisition
  4. `ctl inject` a CW jammer ramp 20 -> 50 dB over 20 s: gpsd's SKY C/N0
     falls, then mode <= 1; MON-HW jamInd as gpsd's own UBX decoder
     (ubxtool on gpsd) shows it rises; `ctl clear`: mode 3 back
  5. `ctl inject` a port fault (wrong_fix 0): gpsd mode <= 1 while the
     receiver keeps its 3D fix; `ctl clear`: mode 3
  6. a bad scenario: ctl exits 1 naming file:line; nothing was added
  7. the socket is mode 0600 and gone after the daemon exits
Exit 77 (skip) without gpsd/gpspipe/ubxtool."""
import argparse
import json
import os
import queue
import re
import shutil
import signal
import socket
import stat
import subprocess
import sys
import threading
import time

from itlib import RigBase, free_port

ORIGIN = (48.8738, 2.2950, 100.0)
RATE_HZ = 2.0
OUTAGE_LIMIT_S = 2.0   # issue 11: TPV mode <= 1 within 2 s of an injected outage
LIMIT_S = 240

CONFIG = """[origin]
lat_deg = {lat}
lon_deg = {lon}
height_m = {h}
[nav]
file = "{nav}"
[time]
start = "2022-01-01T01:00:00"
[receiver]
rate_hz = {rate}
[truth]
bind = "127.0.0.1"
port = {udp}
[demo]
enabled = true
radius_m = 50.0
speed_m_s = 5.0
[[output]]
name = "gps0"
type = "pty"
path = "{pty}"
baud = 115200
protocols_out = ["ubx", "nmea"]
ubx_messages = ["NAV-PVT", "NAV-STATUS", "NAV-DOP", "NAV-SAT", "MON-HW", "NAV-EOE"]
[status]
port = 0
[control]
socket = "{sock}"
"""

SCENARIO = """[[event]]
type = "outage"
start_s = 12
duration_s = 4
"""

OUTAGE = """[[event]]
type = "outage"
antenna = "open"
start_s = 0
"""

JAMMER = """[[event]]
type = "jammer"
kind = "cw"
start_s = 0
duration_s = 20
js_db = [20, 50]
"""

WRONG_FIX = """[[event]]
type = "port"
fault = "wrong_fix"
output = 0
fix_type = 0
start_s = 0
"""

BAD = """[[event]]
type = "jammer"
start_s = 0
js_db = 20
power_w = 3
"""


class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-ctl-")
        self.args = args
        self.pty = os.path.join(self.tmp, "gps0")
        self.sock = os.path.join(self.tmp, "control.sock")
        self.tpvs = queue.Queue()
        self.sky = []  # (monotonic, mean ss of used satellites)

    def write(self, name, text):
        path = os.path.join(self.tmp, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def start(self):
        cfg = self.write("it.toml", CONFIG.format(lat=ORIGIN[0], lon=ORIGIN[1], h=ORIGIN[2],
                                                   nav=os.path.abspath(self.args.nav), rate=RATE_HZ,
                                                   udp=free_port(socket.SOCK_DGRAM), pty=self.pty, sock=self.sock))
        scen = self.write("scenario.toml", SCENARIO)
        self.daemon_log = open(os.path.join(self.tmp, "gnssemud.log"), "w")
        self.daemon = self.spawn([self.args.gnssemud, "--config", cfg, "--scenario", scen],
                                 stdout=subprocess.PIPE, stderr=self.daemon_log, text=True)
        deadline = time.monotonic() + 15
        while not os.path.exists(self.sock) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert os.path.exists(self.sock), "no control socket"
        self.t_start = time.monotonic()
        pipe = self.spawn_gpsd(self.pty)
        threading.Thread(target=self._reader, args=(pipe.stdout,), daemon=True).start()

    def _reader(self, stream):
        for line in stream:
            try:
                m = json.loads(line)
            except ValueError:
                continue
            now = time.monotonic()
            if m.get("class") == "TPV":
                self.tpvs.put((now, m))
            elif m.get("class") == "SKY" and m.get("satellites"):
                ss = [s["ss"] for s in m["satellites"] if s.get("used") and s.get("ss", 0) > 0]
                self.sky.append((now, sum(ss) / len(ss) if ss else 0.0))

    def ctl(self, *args):
        r = subprocess.run([self.args.gnssemu, "ctl", "--socket", self.sock, *args], capture_output=True, text=True,
                           timeout=15)
        return r.returncode, r.stdout, r.stderr

    def status(self):
        rc, out, err = self.ctl("status")
        assert rc == 0, f"ctl status exit {rc}: {err}"
        reply = json.loads(out)
        assert reply["ok"] is True and reply["cmd"] == "status"
        return reply["status"]

    def mon_hw(self):
        """(jamInd, agcCnt) of every MON-HW gpsd passed on in 2.5 s, decoded by
        gpsd's own UBX decoder (ubxtool, read-only, watching gpsd)."""
        r = subprocess.run(["ubxtool", "-r", "-w", "2.5", f"127.0.0.1:{self.gpsd_port}"], capture_output=True,
                           text=True, timeout=20)
        jam = [int(x) for x in re.findall(r"jamInd (\d+)", r.stdout)]
        agc = [int(x) for x in re.findall(r"agcCnt (\d+)", r.stdout)]
        return list(zip(jam, agc))

    def wait_mode(self, pred, limit_s, what):
        deadline = time.monotonic() + limit_s
        while True:
            try:
                t, m = self.tpvs.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise AssertionError(f"no {what} within {limit_s:.0f} s")
            if pred(m.get("mode", 0)):
                return t, m

    def drain(self):
        while not self.tpvs.empty():
            self.tpvs.get_nowait()


def run(rig):
    rig.start()
    # 1. a fix, and the scenario's event pending
    rig.wait_mode(lambda m: m == 3, 40, "mode-3 TPV")
    st = rig.status()
    assert st["fix"]["type"] == 3, st["fix"]
    assert st["satellites"] and all("cn0_dbhz" in s and "state" in s for s in st["satellites"]), st["satellites"][:2]
    assert len(st["faults"]) == 1 and st["faults"][0]["type"] == "outage", st["faults"]
    run_s, start_s = st["epoch"]["run_s"], st["faults"][0]["start_s"]
    print(f"  status: fix 3D, {st['fix']['num_used']} used, scenario outage at run {start_s:.1f} s (now {run_s:.1f} s)")
    assert abs(start_s - 12.0) < 1.0, f"scenario outage starts at run {start_s} s, expected ~12"

    # 2. the scenario's outage (12-16 s), then the fix returns
    t0, _ = rig.wait_mode(lambda m: m <= 1, 30, "mode <= 1 from the scenario outage")
    t1, _ = rig.wait_mode(lambda m: m == 3, 30, "mode 3 after the scenario outage")
    print(f"  scenario: mode <= 1 for {t1 - t0:.1f} s (outage 4 s, then reacquisition)")

    # 3. live outage and clear
    rig.wait_mode(lambda m: m == 3, 10, "mode 3")
    rc, out, err = rig.ctl("inject", rig.write("outage.toml", OUTAGE))
    assert rc == 0, f"inject exit {rc}: {err}"
    t_inj = time.monotonic()
    reply = json.loads(out)
    assert reply["faults"] == 2 and "outage antenna=open" in reply["injected"][0], reply
    rig.drain()
    t, _ = rig.wait_mode(lambda m: m <= 1, 15, "mode <= 1 after ctl inject outage")
    lost_s = t - t_inj
    st = rig.status()
    active = [f for f in st["faults"] if f["active"]]
    assert len(active) == 1 and active[0]["description"] == "antenna=open", st["faults"]
    assert st["fix"]["num_tracked"] == 0, st["fix"]
    rc, out, err = rig.ctl("clear")
    assert rc == 0 and json.loads(out)["cleared"] == 2, (rc, out, err)
    t_clr = time.monotonic()
    t, _ = rig.wait_mode(lambda m: m == 3, 20, "mode 3 after ctl clear")
    back_s = t - t_clr
    assert lost_s <= OUTAGE_LIMIT_S, f"mode <= 1 only {lost_s:.2f} s after the outage was injected"
    assert rig.status()["faults"] == [], "faults left after clear"
    print(f"  ctl outage: gpsd mode <= 1 {lost_s:.2f} s after inject; mode 3 {back_s:.2f} s after clear")

    # 4. jammer ramp: C/N0 falls, the fix goes, clear brings it back
    rig.wait_mode(lambda m: m == 3, 10, "mode 3")
    before = [ss for t, ss in rig.sky[-6:] if ss > 0]
    hw_before = rig.mon_hw()
    rc, out, err = rig.ctl("inject", rig.write("jammer.toml", JAMMER))
    assert rc == 0, f"inject exit {rc}: {err}"
    t_inj = time.monotonic()
    rig.drain()
    t, _ = rig.wait_mode(lambda m: m <= 1, 30, "mode <= 1 under the jammer")
    during = [ss for ts, ss in rig.sky if t_inj + 2 < ts < t and ss > 0]
    hw_during = rig.mon_hw()
    assert hw_before and hw_during, (hw_before, hw_during)
    jam0, jam1 = max(j for j, _ in hw_before), min(j for j, _ in hw_during)
    assert jam1 >= jam0 + 100, f"jamInd through gpsd {jam0} -> {jam1}"
    assert min(a for _, a in hw_during) < max(a for _, a in hw_before), (hw_before, hw_during)
    assert before and during, (before, during)
    drop = sum(before) / len(before) - min(during)
    assert drop >= 5.0, f"gpsd's C/N0 fell only {drop:.1f} dB under the jammer"
    rc, out, err = rig.ctl("clear")
    assert rc == 0, err
    t_clr = time.monotonic()
    t2, _ = rig.wait_mode(lambda m: m == 3, 20, "mode 3 after clearing the jammer")
    print(f"  ctl jammer: gpsd mean C/N0 of used satellites {sum(before) / len(before):.1f} -> {min(during):.1f} dB-Hz, "
          f"mode <= 1 {t - t_inj:.1f} s after inject (J/S {20 + 30 * (t - t_inj) / 20:.0f} dB); "
          f"mode 3 {t2 - t_clr:.2f} s after clear; MON-HW via gpsd (ubxtool): jamInd {jam0} -> {jam1}, "
          f"agcCnt {max(a for _, a in hw_before)} -> {min(a for _, a in hw_during)}")

    # 5. a link fault: the port reports no fix while the receiver has one
    rig.wait_mode(lambda m: m == 3, 10, "mode 3")
    rc, out, err = rig.ctl("inject", rig.write("wrong_fix.toml", WRONG_FIX))
    assert rc == 0, f"inject exit {rc}: {err}"
    t_inj = time.monotonic()
    rig.drain()
    t, _ = rig.wait_mode(lambda m: m <= 1, 5, "mode <= 1 from the wrong_fix port fault")
    assert rig.status()["fix"]["type"] == 3, "the receiver itself lost its fix"
    rc, out, err = rig.ctl("clear")
    assert rc == 0, err
    t_clr = time.monotonic()
    t2, _ = rig.wait_mode(lambda m: m == 3, 5, "mode 3 after clearing the port fault")
    print(f"  ctl wrong_fix 0: gpsd mode <= 1 {t - t_inj:.2f} s after inject while the receiver has 3D; "
          f"mode 3 {t2 - t_clr:.2f} s after clear")

    # 6. a bad scenario changes nothing
    bad = rig.write("bad.toml", BAD)
    rc, out, err = rig.ctl("inject", bad)
    assert rc == 1 and f"{bad}:5:" in err and "power_w" in err, (rc, out, err)
    assert rig.status()["faults"] == []
    print(f"  bad inject: exit 1, {err.strip()[:120]}")
    rc, _, err2 = rig.ctl("frobnicate")
    assert rc == 2, (rc, err2)

    # 7. the socket: 0600 while running, removed at exit
    mode = stat.S_IMODE(os.stat(rig.sock).st_mode)
    assert mode == 0o600, oct(mode)
    rig.stop(rig.daemon)
    assert rig.daemon.returncode == 0, f"gnssemud exit {rig.daemon.returncode}"
    assert not os.path.exists(rig.sock), "socket file left after exit"
    print("  socket: mode 0600, removed at exit")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    args = ap.parse_args()
    for tool in ("gpsd", "gpspipe", "ubxtool"):
        if shutil.which(tool) is None:
            print(f"SKIP: {tool} not installed")
            return 77
    rig = Rig(args)
    signal.signal(signal.SIGALRM, lambda *_: (_ for _ in ()).throw(AssertionError(f"over {LIMIT_S} s")))
    signal.alarm(LIMIT_S)
    ok = False
    try:
        run(rig)
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
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
