#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Forward a base's RTCM 3 bytes into a rover's port (docs/rtk.md). Stdlib only.

What a radio link, an NTRIP client or an autopilot's RTCM injection does:
bytes from a TCP server (gnssemud's [[base.output]] of type tcp, or any
RTCM source) are written unchanged to a serial device or pty (gnssemud's
rover output with protocols_in = ["ubx", "nmea", "rtcm3"]).

  rtcm_forward.py --from 127.0.0.1:2102 --to /tmp/gnssemu/rover
  rtcm_forward.py --from 127.0.0.1:2102 --to /tmp/gnssemu/rover --duration 60

The port is opened write-only, so a reader of the rover's output (gpsd, an
autopilot) keeps every byte it sends. A lost connection is retried each
second. Prints a line of totals every --report seconds (0 = never).
"""
import argparse
import os
import socket
import sys
import time


def parse_address(text):
    host, sep, port = text.rpartition(":")
    if not sep or not port.isdigit():
        raise argparse.ArgumentTypeError(f"{text!r}: expected HOST:PORT")
    return host.strip("[]") or "127.0.0.1", int(port)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--from", dest="source", type=parse_address, required=True, help="HOST:PORT of the RTCM stream")
    ap.add_argument("--to", dest="port", required=True, help="serial device or pty of the rover")
    ap.add_argument("--duration", type=float, default=0.0, help="stop after this many seconds (0: forever)")
    ap.add_argument("--report", type=float, default=10.0, help="seconds between totals (0: never)")
    a = ap.parse_args()

    start = time.monotonic()
    end = start + a.duration if a.duration > 0 else None
    total = 0
    last_report = start
    out = None
    while end is None or time.monotonic() < end:
        try:
            if out is None:
                out = os.open(a.port, os.O_WRONLY | os.O_NOCTTY)
            with socket.create_connection(a.source, timeout=2.0) as s:
                print(f"rtcm_forward: {a.source[0]}:{a.source[1]} -> {a.port}", flush=True)
                s.settimeout(0.5)
                while end is None or time.monotonic() < end:
                    try:
                        data = s.recv(4096)
                    except socket.timeout:
                        data = None
                    if data == b"":
                        break  # the server closed: reconnect
                    if data:
                        view = memoryview(data)
                        while view:
                            view = view[os.write(out, view):]
                        total += len(data)
                    now = time.monotonic()
                    if a.report > 0 and now - last_report >= a.report:
                        print(f"rtcm_forward: {total} bytes forwarded", flush=True)
                        last_report = now
        except OSError as e:
            print(f"rtcm_forward: {e}; retrying", file=sys.stderr, flush=True)
            if out is not None:
                os.close(out)
                out = None
            time.sleep(1.0)
        except KeyboardInterrupt:
            break
    print(f"rtcm_forward: {total} bytes forwarded", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
