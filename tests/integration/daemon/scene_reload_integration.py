#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""SIGHUP with a changed [scene] in the single-vehicle form (docs/daemon.md
§Reload): the receiver restarts in the new scene, its faults go with it,
and gnssemud goes on emitting on its pty (it used to drop the running
receiver before taking its faults, and crash). Loopback only, free port,
temp dir; stops itself in 60 s.

usage: scene_reload_integration.py --gnssemud PATH --nav FILE --mesh FILE
"""
import argparse
import os
import re
import signal
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, run_rig  # noqa: E402


class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-scene-reload-")
        self.args = args
        self.cfg = os.path.join(self.tmp, "scene.toml")
        self.pty = os.path.join(self.tmp, "gps0")
        self.udp_port = free_port(socket.SOCK_DGRAM)

    def write_config(self, loss_db):
        with open(self.cfg + ".new", "w") as f:
            f.write(f"""
[origin]
lat_deg = 48.8738
lon_deg = 2.2950
height_m = 100.0
[nav]
file = "{os.path.abspath(self.args.nav)}"
[time]
start = "2022-01-01T01:00:00"
[truth]
bind = "127.0.0.1"
port = {self.udp_port}
[status]
port = 0
[scene]
mesh = "{os.path.abspath(self.args.mesh)}"
reflection_loss_db = {loss_db}
[[output]]
name = "gps0"
type = "pty"
path = "{self.pty}"
""")
        os.replace(self.cfg + ".new", self.cfg)

    def log(self):
        self.daemon_log.flush()
        return open(self.daemon_log_path, errors="replace").read()


def ggas_for(path, seconds):
    fd = os.open(path, os.O_RDONLY | os.O_NOCTTY | os.O_NONBLOCK)
    data = b""
    end = time.monotonic() + seconds
    try:
        while time.monotonic() < end:
            try:
                data += os.read(fd, 65536)
            except BlockingIOError:
                time.sleep(0.01)
    finally:
        os.close(fd)
    return data.count(b"GGA,")


def body(rig):
    rig.write_config(3.0)
    rig.daemon_log_path = os.path.join(rig.tmp, "gnssemud.log")
    rig.daemon_log = open(rig.daemon_log_path, "w")
    rig.daemon = rig.spawn([rig.args.gnssemud, "--config", rig.cfg], stdout=subprocess.DEVNULL, stderr=rig.daemon_log)
    deadline = time.monotonic() + 20
    while not os.path.exists(rig.pty):
        assert time.monotonic() < deadline and rig.daemon.poll() is None, "the pty did not appear"
        time.sleep(0.1)
    assert ggas_for(rig.pty, 2.5) >= 2, "no GGA before the reload"
    rig.write_config(6.0)
    mark = len(rig.log())
    rig.daemon.send_signal(signal.SIGHUP)
    deadline = time.monotonic() + 10
    while not re.search(r"reload: \S+ applied in [\d.]+ ms \(\[scene\] \(receiver restarted\)\)", rig.log()[mark:]):
        assert rig.daemon.poll() is None, f"gnssemud exited ({rig.daemon.returncode}) on the [scene] reload"
        assert time.monotonic() < deadline, "no reload line"
        time.sleep(0.05)
    n = ggas_for(rig.pty, 2.5)
    assert rig.daemon.poll() is None and n >= 2, f"after the [scene] reload: {n} GGA, exit {rig.daemon.poll()}"
    print(f"  [scene] reloaded, gnssemud running, {n} GGA in the 2.5 s after")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--mesh", required=True)
    return run_rig(Rig(ap.parse_args()), body, 60)


if __name__ == "__main__":
    sys.exit(main())
