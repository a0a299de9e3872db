#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
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
  7. `ctl inject` byte_loss 0.05 on the pty: ctl status shows the port's
     link_bytes_lost rise at 5 % of its bytes; a SIGHUP whose file renames
     that output warns naming the event, which keeps acting on the port;
     the log has one `fault start:` and one `fault end:` line per event
  8. a second daemon with a --scenario port event on its second output: a
     SIGHUP whose file drops that output is refused naming the event, and
     the event keeps acting
  9. the socket is mode 0600 and gone after the daemon exits
Exit 77 (skip) without gpsd/gpspipe/ubxtool."""
import json
import os
import re
import signal
import socket
import stat
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, gpsd_daemon_main  # noqa: E402

ORIGIN = (48.8738, 2.2950, 100.0)
RATE_HZ = 2.0
OUTAGE_LIMIT_S = 2.0   # a user's failsafe needs TPV mode <= 1 within 2 s of an injected outage
LIMIT_S = 240

# Every daemon of the test: the place, the nav data, the rate, truth on loopback.
BASE = """[origin]
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
"""
# No status page; the control socket.
CONTROL = """[status]
port = 0
[control]
socket = "{sock}"
"""
CONFIG = BASE + """[demo]
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
""" + CONTROL

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

BYTE_LOSS_P = 0.05
BYTE_LOSS = """[[event]]
type = "port"
fault = "byte_loss"
output = 0
probability = 0.05
start_s = 0
"""

# Step 8: a second daemon with two file outputs; its scenario drops messages on the second.
CONFIG_FILES = BASE + """[[output]]
name = "out0"
type = "file"
path = "{dir}/out0.nmea"
{second}""" + CONTROL
SECOND_OUTPUT = """[[output]]
name = "out1"
type = "file"
path = "{dir}/out1.nmea"
"""
DROP_ON_OUT1 = """[[event]]
type = "port"
fault = "drop"
output = 1
probability = 0.5
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
        self.sky = []  # (monotonic, mean ss of used satellites)

    def write(self, name, text):
        path = os.path.join(self.tmp, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def config_args(self, sock):
        """BASE and CONTROL's fields: a free truth port, the control socket at sock."""
        return dict(lat=ORIGIN[0], lon=ORIGIN[1], h=ORIGIN[2], nav=os.path.abspath(self.args.nav), rate=RATE_HZ,
                    udp=free_port(socket.SOCK_DGRAM), sock=sock)

    def start(self):
        cfg = self.write("it.toml", CONFIG.format(pty=self.pty, **self.config_args(self.sock)))
        scen = self.write("scenario.toml", SCENARIO)
        self.daemon_log = open(os.path.join(self.tmp, "gnssemud.log"), "w")
        self.daemon = self.spawn([self.args.gnssemud, "--config", cfg, "--scenario", scen],
                                 stdout=subprocess.PIPE, stderr=self.daemon_log, text=True)
        deadline = time.monotonic() + 15
        while not os.path.exists(self.sock) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert os.path.exists(self.sock), "no control socket"
        self.t_start = time.monotonic()
        self.watch_gpsd(self.spawn_gpsd(self.pty).stdout, self._on_sky)

    def _on_sky(self, now, m):
        if m.get("class") == "SKY" and m.get("satellites"):
            ss = [s["ss"] for s in m["satellites"] if s.get("used") and s.get("ss", 0) > 0]
            self.sky.append((now, sum(ss) / len(ss) if ss else 0.0))

    def ctl(self, *args, sock=None):
        r = subprocess.run([self.args.gnssemu, "ctl", "--socket", sock or self.sock, *args], capture_output=True,
                           text=True, timeout=15)
        return r.returncode, r.stdout, r.stderr

    def status(self, sock=None):
        rc, out, err = self.ctl("status", sock=sock)
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

    def wait_log(self, path, pattern, start, limit_s=5.0):
        """The first match of pattern in the log at path after byte start."""
        deadline = time.monotonic() + limit_s
        while True:
            with open(path, errors="replace") as f:
                f.seek(start)
                m = re.search(pattern, f.read())
            if m:
                return m
            if time.monotonic() > deadline:
                raise AssertionError(f"no log line /{pattern}/ in {os.path.basename(path)} within {limit_s:.0f} s")
            time.sleep(0.1)

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

    # 7. a link fault's counters in ctl status, a reload renaming its output, one log line per transition
    log_path = os.path.join(rig.tmp, "gnssemud.log")
    gps0 = lambda st: next(p for p in st["ports"] if p["name"] == "gps0")
    p0 = gps0(rig.status())
    rc, out, err = rig.ctl("inject", rig.write("byte_loss.toml", BYTE_LOSS))
    assert rc == 0, f"inject exit {rc}: {err}"
    time.sleep(3.0)
    p1 = gps0(rig.status())
    lost = p1["link_bytes_lost"] - p0["link_bytes_lost"]
    offered = p1["bytes_offered"] - p0["bytes_offered"]
    written = p1["bytes_written"] - p0["bytes_written"]
    assert lost > 0 and offered > 0, (p0, p1)
    assert abs(lost / offered - BYTE_LOSS_P) < 0.015, f"{lost} of {offered} bytes lost"
    assert abs(lost / (lost + written) - BYTE_LOSS_P) < 0.02, f"{lost} lost, {written} written"
    others = [k for k in p1 if k.startswith("link_") and k != "link_bytes_lost" and p1[k] != p0[k]]
    assert not others, f"other link counters moved under byte_loss: {others}"
    # The reloaded file renames the output: a restart would not find "gps0" at index 0.
    mark = os.path.getsize(log_path)
    with open(os.path.join(rig.tmp, "it.toml")) as f:
        renamed = f.read().replace('name = "gps0"', 'name = "gpsX"')
    rig.write("it.toml", renamed)
    rig.daemon.send_signal(signal.SIGHUP)
    m = rig.wait_log(log_path, r"reload: (ctl inject:1: port event \(fault = \"byte_loss\"\): output = 0 is \"gps0\" "
                     r"now but \"gpsX\" in .*)", mark)
    rig.wait_log(log_path, r"reload: .* applied in", mark)
    time.sleep(1.0)
    p2 = gps0(rig.status())
    assert p2["link_bytes_lost"] > p1["link_bytes_lost"], "byte loss stopped acting after the reload"
    rc, out, err = rig.ctl("clear")
    assert rc == 0 and json.loads(out)["cleared"] == 1, (rc, out, err)
    print(f"  ctl byte_loss {BYTE_LOSS_P}: link_bytes_lost {lost} of {offered} bytes offered "
          f"({100 * lost / offered:.2f} %), {100 * lost / (lost + written):.2f} % of the bytes on the line; "
          f"reload warned: {m.group(1)[:100]}...")
    rig.wait_log(log_path, r"fault end: port fault=byte_loss .*cleared", mark)
    with open(log_path, errors="replace") as f:
        log = f.read()
    starts = re.findall(r"fault start: (.*) \(run ([\d.]+) s\)", log)
    ends = re.findall(r"fault end: (.*) \(run ([\d.]+) s(?:, ([^)]*))?\)", log)
    want = ["outage antenna=blockage for 4.0 s", "outage antenna=open", "jammer kind=cw js_db=20→50 for 20.0 s",
            "port fault=wrong_fix output=0 fix_type=0 on gps0", "port fault=byte_loss output=0 probability=0.05 on gps0"]
    assert [t for t, _ in starts] == want, starts
    assert [t for t, _, _ in ends] == want, ends
    assert abs(float(starts[0][1]) - 12.0) < 0.6 and abs(float(ends[0][1]) - 16.0) < 0.6, (starts[0], ends[0])
    assert ends[0][2] == "" and all(why == "cleared" for _, _, why in ends[1:2] + ends[3:]), ends
    print(f"  log: {len(starts)} 'fault start' and {len(ends)} 'fault end' lines for 5 events, e.g. "
          f"'fault start: {starts[2][0]} (run {starts[2][1]} s)'")

    # 8. a reload that drops the output of a --scenario port event is refused
    sock2 = os.path.join(rig.tmp, "control2.sock")
    cfg_args = dict(rig.config_args(sock2), dir=rig.tmp)
    cfg2 = rig.write("two.toml", CONFIG_FILES.format(second=SECOND_OUTPUT.format(dir=rig.tmp), **cfg_args))
    scen2 = rig.write("drop.toml", DROP_ON_OUT1)
    log2_path = os.path.join(rig.tmp, "gnssemud2.log")
    with open(log2_path, "w") as log2:
        d2 = rig.spawn([rig.args.gnssemud, "--config", cfg2, "--scenario", scen2], stdout=subprocess.DEVNULL,
                       stderr=log2)
    rig.wait_log(log2_path, r"fault start: port fault=drop output=1 probability=0.5 on out1", 0, 15.0)
    rig.write("two.toml", CONFIG_FILES.format(second="", **cfg_args))
    mark = os.path.getsize(log2_path)
    d2.send_signal(signal.SIGHUP)
    m = rig.wait_log(log2_path, r"reload failed, keeping the running configuration: (.*)", mark)
    assert (f"{scen2}:1: port event (fault = \"drop\"): output = 1 (\"out1\") does not exist in {cfg2}: "
            "1 [[output]] table(s)") in m.group(1), m.group(1)
    q0 = rig.status(sock=sock2)["ports"]
    time.sleep(1.0)
    q1 = rig.status(sock=sock2)["ports"]
    assert [p["name"] for p in q1] == ["out0", "out1"], q1
    assert q1[1]["link_messages_dropped"] > q0[1]["link_messages_dropped"] > 0, (q0[1], q1[1])
    assert q1[0]["link_messages_dropped"] == 0, q1[0]
    rig.stop(d2)
    assert d2.returncode == 0, f"second gnssemud exit {d2.returncode}"
    print(f"  reload without the scenario's output refused: {m.group(1)[:110]}...")

    # 9. the socket: 0600 while running, removed at exit
    mode = stat.S_IMODE(os.stat(rig.sock).st_mode)
    assert mode == 0o600, oct(mode)
    rig.stop(rig.daemon)
    assert rig.daemon.returncode == 0, f"gnssemud exit {rig.daemon.returncode}"
    assert not os.path.exists(rig.sock), "socket file left after exit"
    print("  socket: mode 0600, removed at exit")


def main():
    return gpsd_daemon_main(Rig, run, LIMIT_S)


if __name__ == "__main__":
    sys.exit(main())
