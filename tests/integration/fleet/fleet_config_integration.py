#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemud and the vehicle forms of the configuration (docs/configuration.md
"Vehicles and receivers: three forms"): --check-config lists every vehicle,
receiver and port of config/examples/fleet.toml with the fleet's templates
expanded; a template whose ports collide is refused with its file:line; and
one of a single [[vehicle]] receiver runs (several receivers in one daemon:
fleet_run_integration.py).

Usage: fleet_config_integration.py --gnssemud PATH --source DIR
Opens no socket but the one-receiver run's (loopback, free ports); stops by
itself within 30 s."""
import argparse
import os
import subprocess
import sys
import tempfile
import time


def run(cmd, timeout=20):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)


def expect(cond, what):
    if not cond:
        print("FAIL:", what)
        sys.exit(1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--source", required=True)
    a = ap.parse_args()
    example = os.path.join(a.source, "config/examples/fleet.toml")
    nav = os.path.join(a.source, "config/nav/brdc0010.22n")

    out = run([a.gnssemud, "--check-config", "--config", example])
    expect(out.returncode == 0, "check-config of the example: rc %d %s" % (out.returncode, out.stderr))
    for line in ["vehicle: ego", "receiver: ego/gps1: lever arm [0.200, 0.000, -0.100] m",
                 "receiver: ego/gps2:", "output:  gps2: pty /tmp/gnssemu/ego/gps2",
                 "vehicle: v1", "output:  gps-v1: pty /tmp/gnssemu/v1/gps1",
                 "output:  nmea-1: udp to 127.0.0.1:10111",
                 "fleet:   3 vehicle(s), 4 receiver(s), 6 port(s)", "configuration OK"]:
        expect(line in out.stdout, "check-config lists %r:\n%s" % (line, out.stdout))

    with tempfile.TemporaryDirectory() as d:
        head = ('[origin]\nlat_deg = 48.8738\nlon_deg = 2.2950\nheight_m = 100.0\n'
                '[nav]\nfile = "%s"\n[demo]\nenabled = false\n[status]\nport = 0\n[truth]\nport = 0\n' % nav)
        bad = os.path.join(d, "bad.toml")
        with open(bad, "w") as f:  # line 18: the first template's port_base
            f.write(head + '[fleet]\ncount = 4\n[[fleet.output]]\nname = "a"\ntype = "tcp"\nport_base = 7000\n'
                    '[[fleet.output]]\nname = "b"\ntype = "tcp"\nport_base = 7002\n')
        out = run([a.gnssemud, "--check-config", "--config", bad])
        expect(out.returncode == 2, "colliding templates: rc %d" % out.returncode)
        expect(bad + ":18: vehicle 'v2' receiver 'gps1' output 'a': port_base: tcp port 7002 is already used by "
               "vehicle 'v0' receiver 'gps1' output 'b'" in out.stderr, "collision message: " + out.stderr)

        one = os.path.join(d, "one.toml")
        pty = os.path.join(d, "ego-gps1")
        with open(one, "w") as f:
            f.write(head + '[[vehicle]]\nid = "ego"\n[[vehicle.receiver]]\nname = "gps1"\nseed = 5\n'
                    '[[vehicle.receiver.output]]\nname = "gps1"\npath = "%s"\n' % pty)
        p = subprocess.Popen([a.gnssemud, "--config", one], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            deadline = time.time() + 15
            while time.time() < deadline and not os.path.exists(pty) and p.poll() is None:
                time.sleep(0.1)
            expect(os.path.exists(pty), "the one-receiver vehicle's pty appears")
        finally:
            p.terminate()
            p.wait(timeout=10)
        expect(p.returncode == 0, "clean stop: rc %s" % p.returncode)
    print("fleet config: 3 checks passed")
    print("3 passed, 0 failed")


if __name__ == "__main__":
    main()
