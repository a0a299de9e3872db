#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The M9's jamming report through a real gpsd (docs/faults.md §gpsd,
docs/ubx.md §Generations).

gnssemud with [receiver] generation = "m9" (MON-RF and SEC-SIG in the pty's
ubx_messages, [control] socket), a private gpsd on the pty (not read-only:
ubxtool writes through it). Steps:
  1. MON-VER polled through gpsd (ubxtool -p MON-VER): a NEO-M9N, SPG 4.04,
     PROTVER 32.01, from the daemon's config path
  2. mode 3; CFG-ITFM with the monitor enabled sent through gpsd (ubxtool -c):
     ACK; MON-RF as gpsd's own decoder (ubxtool -r) shows one block,
     jammingState 1 (ok), jamInd low
  3. `ctl inject` a CW jammer ramp 20 -> 50 dB over 12 s: jamInd rises,
     jammingState 2 (warning, fix still OK) and 3 (critical, fix gone)
  4. `ctl clear`: jammingState back to 1
Exit 77 (skip) without gpsd/gpspipe/ubxtool."""
import json
import os
import re
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, gpsd_daemon_main  # noqa: E402

LIMIT_S = 90

CONFIG = """[origin]
lat_deg = 48.8738
lon_deg = 2.2950
height_m = 100.0
[nav]
file = "{nav}"
[time]
start = "2022-01-01T01:00:00"
[receiver]
rate_hz = 2.0
generation = "m9"
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
ubx_messages = ["NAV-PVT", "NAV-STATUS", "NAV-DOP", "NAV-SAT", "MON-RF", "SEC-SIG", "NAV-EOE"]
[status]
port = 0
[control]
socket = "{sock}"
"""

JAMMER = """[[event]]
type = "jammer"
kind = "cw"
start_s = 0
duration_s = 12
js_db = [20, 50]
"""

# CFG-ITFM: bbThreshold 3 dB, cwThreshold 15 dB, the factory algorithm bits, enable (b31).
CFG_ITFM_ENABLE = "06,39,f3,ac,62,ad,1e,03,00,00"


class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-m9-")
        self.args = args
        self.pty = os.path.join(self.tmp, "gps0")
        self.sock = os.path.join(self.tmp, "control.sock")

    def start(self):
        cfg = os.path.join(self.tmp, "m9.toml")
        with open(cfg, "w") as f:
            f.write(CONFIG.format(nav=os.path.abspath(self.args.nav), udp=free_port(socket.SOCK_DGRAM), pty=self.pty,
                                  sock=self.sock))
        self.daemon_log = open(os.path.join(self.tmp, "gnssemud.log"), "w")
        self.daemon = self.spawn([self.args.gnssemud, "--config", cfg], stdout=subprocess.DEVNULL,
                                 stderr=self.daemon_log)
        deadline = time.monotonic() + 15
        while not (os.path.exists(self.sock) and os.path.exists(self.pty)) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert os.path.exists(self.sock), "no control socket"
        self.watch_gpsd(self.spawn_gpsd(self.pty, readonly=False).stdout)

    def ubxtool(self, *args, wait_s=1.5):
        r = subprocess.run(["ubxtool", "-P", "32.01", "-w", str(wait_s), *args, f"127.0.0.1:{self.gpsd_port}"],
                           capture_output=True, text=True, timeout=20)
        return r.stdout + r.stderr

    def ctl(self, *args):
        r = subprocess.run([self.args.gnssemu, "ctl", "--socket", self.sock, *args], capture_output=True, text=True,
                           timeout=15)
        assert r.returncode == 0, f"ctl {args[0]} exit {r.returncode}: {r.stderr}"
        return json.loads(r.stdout)

    def mon_rf(self, wait_s=1.0):
        """(nBlocks, jammingState, jamInd, agcCnt) of every MON-RF gpsd passed
        on in wait_s, decoded by gpsd's UBX decoder (ubxtool, read-only)."""
        out = self.ubxtool("-r", wait_s=wait_s)
        head = re.findall(r"UBX-MON-RF:\n version (\d+) nBlocks (\d+)", out)
        blocks = re.findall(r"blockId (\d+) flags x([0-9a-f]+) .*\n\s+noisePerMS (\d+) agcCnt (\d+) jamInd (\d+)", out)
        assert len(head) == len(blocks), (head, blocks)
        return [(int(n), int(fl, 16) & 3, int(j), int(a)) for (_, n), (_, fl, _, a, j) in zip(head, blocks)]


def run(rig):
    rig.start()
    t0 = time.monotonic()
    # 1. a fix; the chip is a NEO-M9N (MON-VER polled through gpsd)
    rig.wait_mode(lambda m: m == 3, 30, "mode-3 TPV")
    t_fix = time.monotonic() - t0
    out = rig.ubxtool("-p", "MON-VER", wait_s=2.0)
    assert "FWVER=SPG 4.04" in out and "PROTVER=32.01" in out and "00190000" in out, out[-800:]
    print("  MON-VER through gpsd: hwVersion 00190000, FWVER=SPG 4.04, PROTVER=32.01")

    # 2. the monitor enabled through gpsd; MON-RF ok
    assert "UBX-ACK-ACK" in rig.ubxtool("-c", CFG_ITFM_ENABLE), "CFG-ITFM not ACKed"
    clean = rig.mon_rf()
    assert clean, "no MON-RF through gpsd"
    assert all(n == 1 and s == 1 for n, s, _, _ in clean), f"clean sky MON-RF {clean}"
    jam0 = max(j for _, _, j, _ in clean)

    # 3. the CW ramp: warning while the fix holds, critical once it is gone
    with open(os.path.join(rig.tmp, "jammer.toml"), "w") as f:
        f.write(JAMMER)
    reply = rig.ctl("inject", os.path.join(rig.tmp, "jammer.toml"))
    assert "jammer kind=cw" in reply["injected"][0], reply
    t_inj = time.monotonic()
    seen = []
    while time.monotonic() - t_inj < 14 and not (2 in [s for _, s, _, _ in seen] and seen and seen[-1][1] == 3):
        seen += rig.mon_rf(wait_s=1.0)
    states = [s for _, s, _, _ in seen]
    assert 2 in states, f"no warning under the ramp: {seen}"
    assert 3 in states and states.index(2) < states.index(3), f"no critical after the warning: {seen}"
    jam1 = max(j for _, _, j, _ in seen)
    assert jam1 >= jam0 + 100, f"jamInd {jam0} -> {jam1}"
    assert min(a for _, _, _, a in seen) < min(a for _, _, _, a in clean), (clean, seen)

    # 4. clear: the interference is gone, the monitor reports ok again
    assert rig.ctl("clear")["ok"] is True
    t_clr = time.monotonic()
    after = []
    while time.monotonic() - t_clr < 6 and not (after and after[-1][1] == 1):
        after += rig.mon_rf(wait_s=1.0)
    assert after and after[-1][1] == 1, f"MON-RF after clear {after}"
    print(f"  MON-RF via gpsd (ubxtool): first fix {t_fix:.1f} s; clean jammingState 1 jamInd {jam0}; "
          f"ramp states {''.join(str(s) for s in states)} jamInd up to {jam1}; "
          f"after clear {after[-1][1]} within {time.monotonic() - t_clr:.1f} s; run {time.monotonic() - t0:.1f} s")
    rig.stop(rig.daemon)
    assert rig.daemon.returncode == 0, f"gnssemud exit {rig.daemon.returncode}"


def main():
    return gpsd_daemon_main(Rig, run, LIMIT_S)


if __name__ == "__main__":
    sys.exit(main())
