#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""A host flooding one output port with garbage starves neither the other
ports nor the truth socket (docs/robustness.md): tools/soak/soak.py flood
with --host-garbage (a TCP client writing the UBX/NMEA decoder's worst-case
input as fast as the daemon reads it) while flood_truth sends good truth at
--pps. Each port's input has a budget (daemon/ports/input_budget.hpp) and the
truth socket drains up to 64 datagrams per wake-up, so: the daemon accepts
at least 90 % of the truth packets, the pty and TCP readers miss no epoch,
and the garbage is held to the port's budget (well under 1 MB/s).

usage: input_flood_integration.py --build DIR [--duration S] [--pps N]
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOAK = os.path.join(HERE, "..", "..", "..", "tools", "soak", "soak.py")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True)
    ap.add_argument("--duration", type=float, default=15.0)
    ap.add_argument("--pps", type=float, default=20000.0)
    a = ap.parse_args()
    out = subprocess.run([sys.executable, SOAK, "flood", "--build", a.build, "--duration", str(a.duration),
                          "--pps", str(a.pps), "--good-fraction", "1", "--host-garbage", "--warmup-s", "3"],
                         capture_output=True, text=True, timeout=a.duration + 120)
    print(out.stdout)
    if out.returncode == 2:
        print(out.stderr)
        return 1
    accepted = re.search(r"truth accepted (\d+)", out.stdout)
    garbage = re.search(r"host garbage: ([\d.]+) MB written .* \(([\d.]+) MB/s\)", out.stdout)
    missed = re.search(r"verdict: .*\(missed (\d+), skipped (\d+)", out.stdout)
    if not (accepted and garbage and missed):
        print("FAIL: soak.py printed no figures")
        return 1
    sent = a.pps * a.duration
    share = int(accepted[1]) / sent
    failed = []
    if share < 0.9:
        failed.append(f"truth accepted {accepted[1]} of ~{sent:.0f} sent ({100 * share:.1f} %)")
    if float(garbage[2]) > 1.0:
        failed.append(f"the garbage host got {garbage[2]} MB/s through (the port's budget is 0.13 MB/s)")
    if int(missed[1]) or int(missed[2]):
        failed.append(f"readers missed {missed[1]} epochs, the daemon skipped {missed[2]}")
    print(f"truth accepted {100 * share:.1f} % of ~{sent:.0f}; garbage taken {garbage[2]} MB/s; "
          f"missed {missed[1]}, skipped {missed[2]}")
    for f in failed:
        print("FAIL: " + f)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
