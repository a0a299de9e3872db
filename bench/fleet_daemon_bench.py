#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The daemon under a fleet's load (issue 23 "Speed and memory"): gnssemud
with `[fleet] count = N` at --rate Hz, every vehicle's truth sent over UDP at
that rate by tools/senders/swarm_truth.py, and one reader timestamping each
vehicle's sentences as they leave the daemon.

  fleet_daemon_bench.py --gnssemud build/daemon/gnssemud --count 100 --rate 10 --seconds 600

The config is config/default.toml with its [[output]] replaced by one
`[[fleet.output]]` udp template (vehicle k sends to 127.0.0.1:port_base + k),
`[receiver] generation = "m9"` (its factory CFG-GNSS tracks every system)
and `constellations = --systems`, the status page off. Outputs are udp, not
ptys: a datagram carries whole sentences and the kernel stamps its arrival
(SO_TIMESTAMPNS), so one Python reader on N sockets measures when the daemon
sent, not when the reader got round to it; a udp port has no line budget
(baud 0), so a large epoch is neither cut nor delayed by the emulated UART.

Per vehicle and epoch the arrival of the datagram holding RMC is compared
with the epoch in the wall clock: in realtime the epoch clock is GPS time
from the system clock and the sentences' UTC is GPS time minus the leap
seconds, i.e. the system clock (docs/daemon.md §Time), so

  lateness = arrival - (RMC's UTC as a wall-clock time + [time] output_delay_s).

Over the measured window (after --warmup s of truth) it prints epochs
expected and received per vehicle (missed = gaps), lateness p50/p99/max,
the spread of one epoch over the vehicles, the daemon's CPU ticks
(/proc/PID/stat utime + stime) as a share of one core and per receiver
epoch, VmHWM and VmRSS, kernel drops on the truth and reader sockets
(/proc/net/udp), /proc/loadavg at start and end, and the daemon's exit
summary. A benchmark: figures, no pass/fail.
"""
import argparse
import datetime
import math
import os
import resource
import selectors
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SO_TIMESTAMPNS = getattr(socket, "SO_TIMESTAMPNS", 35)  # Linux asm-generic/socket.h
CLK_TCK = os.sysconf("SC_CLK_TCK")


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (datetime.datetime, datetime.date, datetime.time)):
        return v.isoformat()
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f'"{k}" = {toml_value(x)}' for k, x in v.items()) + " }"
    raise TypeError(f"no TOML for {v!r}")


def is_table_array(v):
    return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)


def toml_dump(d, prefix=""):
    """Scalars first, then sub-tables, then arrays of tables (TOML's order rules)."""
    out = []
    for k, v in d.items():
        if not isinstance(v, dict) and not is_table_array(v):
            out.append(f"{k} = {toml_value(v)}")
    for k, v in d.items():
        if isinstance(v, dict):
            name = f"{prefix}{k}"
            out.append(f"\n[{name}]")
            out.append(toml_dump(v, name + "."))
    for k, v in d.items():
        if is_table_array(v):
            for item in v:
                out.append(f"\n[[{prefix}{k}]]")
                out.append(toml_dump(item, f"{prefix}{k}."))
    return "\n".join(x for x in out if x)


def write_config(path, a, truth_port, port_base):
    src = os.path.join(ROOT, "config", "default.toml")
    with open(src, "rb") as f:
        cfg = tomllib.load(f)
    cfg["nav"]["file"] = os.path.join(ROOT, "config", cfg["nav"]["file"])
    cfg.pop("output", None)
    cfg["time"]["output_delay_s"] = a.output_delay
    r = cfg["receiver"]
    r["rate_hz"] = float(a.rate)
    r["generation"] = a.generation
    r["constellations"] = a.systems.split(",")
    cfg["truth"]["port"] = truth_port
    cfg["status"]["port"] = 0
    out = {"type": "udp", "name": "u{index}", "address": "127.0.0.1", "port_base": port_base}
    if a.sentences:
        out["sentences"] = a.sentences.split(",")
    cfg["fleet"] = {"count": a.count, "output": [out]}
    with open(path, "w") as f:
        f.write(f"# written by bench/fleet_daemon_bench.py from {src}\n")
        f.write(toml_dump(cfg) + "\n")


def free_udp_port():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def bind_block(n, first_base):
    """n reader sockets on consecutive ports; the first block that binds whole."""
    for base in range(first_base, 65536 - n, n + 7):
        socks = []
        try:
            for k in range(n):
                s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                socks.append(s)
                s.bind(("127.0.0.1", base + k))
        except OSError:
            for s in socks:
                s.close()
            continue
        for s in socks:
            s.setsockopt(socket.SOL_SOCKET, SO_TIMESTAMPNS, 1)
            s.setblocking(False)
            try:  # root may go past net.core.rmem_max
                s.setsockopt(socket.SOL_SOCKET, getattr(socket, "SO_RCVBUFFORCE", 33), 1 << 20)
            except OSError:
                s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 20)
        return base, socks
    sys.exit(f"fleet_daemon_bench: no block of {n} free udp ports")


def cpu_ticks(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return int(fields[11]) + int(fields[12])  # utime, stime (fields 14, 15)


def proc_status(pid, key):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])  # kB
    return 0


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def udp_drops(ports):
    """Kernel drops of the 127.0.0.1 udp sockets bound to these ports."""
    want = {f"0100007F:{p:04X}" for p in ports}
    total = 0
    with open("/proc/net/udp") as f:
        next(f)
        for line in f:
            cols = line.split()
            if cols[1] in want:
                total += int(cols[-1])
    return total


def rmc_utc_s(data):
    """Seconds of the UTC day in the datagram's RMC, or None."""
    i = data.find(b"RMC,")
    if i < 0:
        return None
    j = data.find(b",", i + 4)
    t = data[i + 4:j]
    if len(t) < 6:
        return None  # no time yet (u-blox leaves it empty)
    return int(t[0:2]) * 3600 + int(t[2:4]) * 60 + float(t[4:])


def pct(sorted_v, p):
    return sorted_v[min(len(sorted_v) - 1, int(p * len(sorted_v)))] if sorted_v else float("nan")


class Reader:
    def __init__(self, socks, rate):
        self.socks, self.rate = socks, rate
        self.sel = selectors.DefaultSelector()
        for k, s in enumerate(socks):
            self.sel.register(s, selectors.EVENT_READ, k)
        self.arrival = [dict() for _ in socks]  # per vehicle: epoch index -> first arrival, s
        self.datagrams = 0
        self.untimed = 0
        self.talkers = set()
        self.cmsg = socket.CMSG_SPACE(16)

    def poll(self, until):
        while True:
            left = until - time.monotonic()
            if left <= 0:
                return
            for key, _ in self.sel.select(left):
                s, k = key.fileobj, key.data
                while True:
                    try:
                        data, anc, _, _ = s.recvmsg(4096, self.cmsg)
                    except BlockingIOError:
                        break
                    self.take(k, data, anc)

    def take(self, k, data, anc):
        self.datagrams += 1
        ts = None
        for level, kind, raw in anc:
            if level == socket.SOL_SOCKET and kind == SO_TIMESTAMPNS:
                sec, nsec = struct.unpack("qq", raw[:16])
                ts = sec + nsec * 1e-9
        if ts is None:
            ts = time.time()
        if k == 0 and len(self.talkers) < 8:
            for i in range(len(data) - 6):
                if data[i] == 36 and data[i + 3:i + 6] == b"GSV":  # '$'
                    self.talkers.add(data[i + 1:i + 3].decode())
        tod = rmc_utc_s(data)
        if tod is None:
            if b"RMC," in data:
                self.untimed += 1
            return
        day = math.floor(ts / 86400.0) * 86400.0
        wall = day + tod
        if wall - ts > 43200:
            wall -= 86400
        elif ts - wall > 43200:
            wall += 86400
        e = round(wall * self.rate)
        d = self.arrival[k]
        if e not in d or ts < d[e]:
            d[e] = ts


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--gnssemud", default=os.path.join(ROOT, "build", "daemon", "gnssemud"))
    p.add_argument("--sender", default=os.path.join(ROOT, "tools", "senders", "swarm_truth.py"))
    p.add_argument("--count", type=int, default=100, help="fleet vehicles v0 .. v{count-1}")
    p.add_argument("--rate", type=float, default=10.0, help="Hz: epochs and truth packets per vehicle")
    p.add_argument("--seconds", type=float, default=60.0, help="measured window")
    p.add_argument("--warmup", type=float, default=5.0, help="s of truth before the window")
    p.add_argument("--output-delay", type=float, default=0.1, help="[time] output_delay_s")
    p.add_argument("--systems", default="G,R,E,C,J", help="[receiver] constellations")
    p.add_argument("--generation", default="m9", help="[receiver] generation (m9 tracks every system)")
    p.add_argument("--sentences", default="", help="comma list; default: the daemon's default set")
    p.add_argument("--formation", default="grid", choices=["line", "vee", "grid"])
    p.add_argument("--port-base", type=int, default=42000, help="first port tried for the reader block")
    p.add_argument("--keep", action="store_true", help="keep the temp folder (config, daemon log)")
    a = p.parse_args()
    if not 1 <= a.count <= 1000 or a.rate <= 0 or a.seconds <= 0:
        sys.exit("fleet_daemon_bench: --count in [1, 1000], --rate > 0, --seconds > 0")
    if not os.access(a.gnssemud, os.X_OK):
        sys.exit(f"fleet_daemon_bench: {a.gnssemud}: not an executable (build gnssemud or give --gnssemud)")

    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    need = 2 * a.count + 64
    if soft < need:
        resource.setrlimit(resource.RLIMIT_NOFILE, (min(max(need, soft), hard), hard))

    tmp = tempfile.mkdtemp(prefix="gnssemu-fleetbench-")
    try:
        return run(a, tmp)
    finally:
        if a.keep:
            print(f"kept {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)


def run(a, tmp):
    """Starts, measures and stops everything; prints the figures."""
    procs = []
    socks = []
    try:
        port_base, socks = bind_block(a.count, a.port_base)
        truth_port = free_udp_port()
        cfg = os.path.join(tmp, "fleet.toml")
        write_config(cfg, a, truth_port, port_base)
        reader = Reader(socks, a.rate)
        load_start = loadavg()
        log = open(os.path.join(tmp, "gnssemud.log"), "w")
        daemon = subprocess.Popen([a.gnssemud, "--config", cfg], stdout=log, stderr=subprocess.STDOUT)
        procs.append(daemon)
        t_launch = time.monotonic()
        reader.poll(t_launch + 1.0)
        if daemon.poll() is not None:
            sys.exit(f"fleet_daemon_bench: gnssemud exited ({daemon.returncode}); log: "
                     + open(os.path.join(tmp, "gnssemud.log")).read()[-2000:])
        sender = subprocess.Popen([sys.executable, a.sender, "--count", str(a.count), "--rate", str(a.rate),
                                   "--formation", a.formation, "--port", str(truth_port)])
        procs.append(sender)
        reader.poll(time.monotonic() + a.warmup)
        w0_wall, w0_mono = time.time(), time.monotonic()
        ticks0, sticks0 = cpu_ticks(daemon.pid), cpu_ticks(sender.pid)
        r0 = os.times()
        reader.poll(w0_mono + a.seconds)
        w1_wall, w1_mono = time.time(), time.monotonic()
        ticks1, sticks1 = cpu_ticks(daemon.pid), cpu_ticks(sender.pid)
        r1 = os.times()
        hwm_kb, rss_kb = proc_status(daemon.pid, "VmHWM"), proc_status(daemon.pid, "VmRSS")
        truth_drops = udp_drops([truth_port])
        # The window's last epochs are still on their way: read on, then stop.
        reader.poll(time.monotonic() + a.output_delay + 0.5)
        reader_drops = udp_drops(range(port_base, port_base + a.count))
        load_end = loadavg()
        sender.send_signal(signal.SIGTERM)
        sender.wait(timeout=10)
        daemon.send_signal(signal.SIGINT)
        daemon.wait(timeout=30)
        log.close()
    finally:
        for pr in procs:
            if pr.poll() is None:
                pr.kill()
                pr.wait()
        for s in socks:
            s.close()

    wall_s = w1_mono - w0_mono
    e_first = math.ceil(w0_wall * a.rate)
    e_last = math.floor((w1_wall - a.output_delay) * a.rate) - 1
    expected = e_last - e_first + 1
    late_ms, missed, per_epoch = [], [], {}
    for k, d in enumerate(reader.arrival):
        got = 0
        for e in range(e_first, e_last + 1):
            ts = d.get(e)
            if ts is None:
                continue
            got += 1
            lm = (ts - (e / a.rate + a.output_delay)) * 1e3
            late_ms.append(lm)
            per_epoch.setdefault(e, []).append(lm)
        missed.append(expected - got)
    late_ms.sort()
    spread = sorted(max(v) - min(v) for v in per_epoch.values())
    cpu_s = (ticks1 - ticks0) / CLK_TCK
    n_recv_epochs = expected * a.count

    with open(os.path.join(tmp, "gnssemud.log")) as f:
        lines = f.read().splitlines()
    down = next((i for i, l in enumerate(lines) if "shutting down" in l), len(lines))
    summary = lines[down:]
    late_lines = [l for l in lines[:down] if "late" in l or "skipped" in l]
    ports = [l for l in summary if ": output " in l]
    written = sum(int(l.split("epochs written")[0].split()[-1]) for l in ports)
    dropped = sum(int(l.split(" dropped;")[0].split()[-1]) for l in ports)

    print(f"gnssemud {a.gnssemud}: {a.count} vehicle(s) x 1 receiver, {a.rate:g} Hz, "
          f"systems {a.systems} ({a.generation}; GSV talkers seen on v0: {','.join(sorted(reader.talkers))}), "
          f"udp outputs 127.0.0.1:{port_base}..{port_base + a.count - 1}, output_delay_s {a.output_delay}")
    print(f"window: {wall_s:.1f} s after {a.warmup:g} s of truth; load (1/5/15 min) at start {load_start}, "
          f"at end {load_end}; {os.cpu_count()} CPUs")
    print(f"epochs: expected {expected} per vehicle; received min {expected - max(missed)}, "
          f"max {expected - min(missed)}; missed total {sum(missed)} over {sum(1 for m in missed if m)} vehicle(s)")
    print(f"lateness beyond the epoch + output_delay, ms ({len(late_ms)} vehicle-epochs): "
          f"p50 {pct(late_ms, 0.5):.2f}, p99 {pct(late_ms, 0.99):.2f}, max {late_ms[-1] if late_ms else float('nan'):.2f}, "
          f"min {late_ms[0] if late_ms else float('nan'):.2f}")
    print(f"one epoch's spread over the vehicles (last - first), ms: p50 {pct(spread, 0.5):.2f}, "
          f"p99 {pct(spread, 0.99):.2f}, max {spread[-1] if spread else float('nan'):.2f}")
    print(f"daemon CPU: {ticks1 - ticks0} ticks ({cpu_s:.2f} s) over {wall_s:.1f} s = "
          f"{100 * cpu_s / wall_s:.1f} % of one core; {1e6 * cpu_s / max(1, n_recv_epochs):.1f} us per receiver-epoch")
    print(f"daemon memory: VmHWM {hwm_kb / 1024:.1f} MB, VmRSS {rss_kb / 1024:.1f} MB "
          f"({rss_kb / 1024 / a.count:.2f} MB per vehicle)")
    print(f"load generator: sender {100 * (sticks1 - sticks0) / CLK_TCK / wall_s:.1f} % of one core, reader "
          f"{100 * ((r1.user + r1.system) - (r0.user + r0.system)) / wall_s:.1f} %; "
          f"{reader.datagrams} datagrams read, {reader.untimed} RMC without time")
    print(f"kernel udp drops: truth socket {truth_drops}, reader sockets {reader_drops}")
    print(f"daemon log during the run: {len(late_lines)} line(s) on lateness/skips"
          + ("".join("\n  " + l for l in late_lines[:5])))
    print(f"daemon exit summary: {len(ports)} port(s), {written} epochs written, {dropped} dropped; "
          f"rc {daemon.returncode}")
    for l in summary:
        if ": output " in l and l is not ports[0] and l is not ports[-1]:
            continue
        if "truth: vehicle" in l and a.count > 3 and "v0'" not in l:
            continue
        print("  " + l)
    return 0


if __name__ == "__main__":
    sys.exit(main())
