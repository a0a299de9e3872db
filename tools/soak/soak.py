#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Soak and flood runs of gnssemud (docs/robustness.md). Prints figures; not a test.

  soak.py soak  [--duration S] [--rate-hz 10] [--truth-hz 100] [--sample-s S]
  soak.py flood [--duration S] [--pps 100000] [--good-fraction 0.5] [--host-garbage] [--sample-s S]
  common: [--build DIR] [--keep]

Both start gnssemud on a private config (free ports, a temp dir), two readers
that hold the daemon's outputs open for the whole run -- a pty (NMEA+UBX) and
a TCP client (NMEA+UBX) -- and sample the daemon's RSS and CPU. soak sends
truth with build/tools/senders/send_truth (binary records on a circle);
flood with build/tools/soak/flood_truth (good and bad packets), and with
--host-garbage a third TCP client that writes, as fast as the daemon reads,
the input that costs the port's UBX/NMEA decoder most per byte (a UBX
header announcing 1 KiB, then '$' filler: every '$' is rescanned).

Missed epochs are counted by each reader from the epoch times it receives:
UBX NAV-PVT iTOW (an epoch is missed when iTOW advances by more than one
period) and NMEA RMC times; the daemon's own count of late, skipped epochs
and of epochs a port dropped comes from its log. A pty drops queued epochs
when its reader falls over 2 kB behind (docs/daemon.md), so each reader
also reports its longest pause between reads: a pause on one reader only
is the reader's (a loaded machine), one on both the daemon's. Exit 0 when the run is clean: no missed or skipped
epoch, no epoch dropped by a port, RSS growth after warm-up within
--max-rss-growth-kb; 1 otherwise; 2 on a setup error.
"""
import argparse
import datetime
import os
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import termios
import threading
import time
import tty

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ORIGIN = (48.8738, 2.2950, 100.0)  # Paris, as config/default.toml


sys.path.insert(0, os.path.join(ROOT, "tests", "integration"))
from itlib import free_port  # noqa: E402  (the integration tests' loopback port picker)


def config_text(tmp, rate_hz, truth_port, tcp_port):
    nav = os.path.join(ROOT, "tests/data/nav/brdc0010.22n")
    return f"""# soak.py: {rate_hz} Hz, a pty and a TCP output with NMEA and UBX
[origin]
lat_deg = {ORIGIN[0]}
lon_deg = {ORIGIN[1]}
height_m = {ORIGIN[2]}

[nav]
file = "{nav}"

[time]
mode = "realtime"
start = "2022-01-01T08:00:00"

[receiver]
rate_hz = {rate_hz}

[truth]
port = {truth_port}
timeout_s = 1.0
max_extrapolation_s = 0.2

[demo]
enabled = false

[[output]]
name = "pty"
type = "pty"
path = "{tmp}/gps0"
baud = 921600
sentences = ["RMC", "VTG", "GGA", "GSA", "GSV", "GLL", "GST", "ZDA"]
ubx_messages = ["NAV-PVT", "NAV-DOP", "NAV-SAT"]

[[output]]
name = "tcp"
type = "tcp"
bind = "127.0.0.1"
port = {tcp_port}
sentences = ["RMC", "GGA", "GSA", "GSV"]
ubx_messages = ["NAV-PVT", "NAV-STATUS", "NAV-SAT", "MON-HW"]

[log]
level = "info"
"""


class Reader(threading.Thread):
    """Reads one output for the whole run and counts bytes, epochs (NAV-PVT
    iTOW and NMEA RMC time) and the gaps between them."""

    def __init__(self, name, period_s, open_fn):
        super().__init__(daemon=True)
        self.name_ = name
        self.period_ms = round(period_s * 1000)
        self.open_fn = open_fn
        self.stop = threading.Event()
        self.lock = threading.Lock()
        self.bytes = 0
        self.pvt = 0
        self.pvt_fix = 0
        self.pvt_missed = 0
        self.rmc = 0
        self.rmc_missed = 0
        self.jumps = 0  # time going back or forward by more than a minute (not counted as missed)
        self.last_itow = None
        self.last_rmc = None
        self.error = None
        self.buf = bytearray()
        self.last_read = None
        self.max_gap_s = 0.0   # longest time between two reads that returned data
        self.long_gaps = 0     # gaps longer than 2.5 periods: the reader (or the daemon) stalled

    def snapshot(self):
        with self.lock:
            return dict(bytes=self.bytes, pvt=self.pvt, pvt_fix=self.pvt_fix, pvt_missed=self.pvt_missed,
                        rmc=self.rmc, rmc_missed=self.rmc_missed, jumps=self.jumps, max_gap_s=self.max_gap_s,
                        long_gaps=self.long_gaps)

    def gap(self, last, now_ms):
        """Epochs missed between two epoch times (ms); None for a jump."""
        d = now_ms - last
        if d <= 0 or d > 60_000:
            return None
        return max(0, round(d / self.period_ms) - 1)

    def missed_since(self, last_ms, now_ms):
        """Epochs missed between two epoch times (ms); a jump counts in jumps, not as missed."""
        if last_ms is None:
            return 0
        g = self.gap(last_ms, now_ms)
        if g is None:
            self.jumps += 1
            return 0
        return g

    def on_pvt(self, payload):
        itow, = struct.unpack_from("<I", payload, 0)
        fix_ok = payload[21] & 1
        with self.lock:
            self.pvt += 1
            self.pvt_fix += bool(fix_ok)
            self.pvt_missed += self.missed_since(self.last_itow, itow)
            self.last_itow = itow

    def on_rmc(self, fields):
        try:
            hhmmss, ddmmyy = fields[1], fields[9]
            t = datetime.datetime.strptime(ddmmyy + hhmmss.split(".")[0], "%d%m%y%H%M%S")
            ms = int(t.replace(tzinfo=datetime.timezone.utc).timestamp()) * 1000
            ms += round(float("0." + hhmmss.split(".")[1]) * 1000) if "." in hhmmss else 0
        except (ValueError, IndexError):
            return  # no time yet
        with self.lock:
            self.rmc += 1
            self.rmc_missed += self.missed_since(self.last_rmc, ms)
            self.last_rmc = ms

    def parse(self):
        b = self.buf
        while True:
            hits = [k for k in (b.find(b"\xb5"), b.find(b"$")) if k >= 0]
            if not hits:
                b.clear()
                return
            i = min(hits)
            del b[:i]
            if b[0] == 0xB5:
                if len(b) < 8:
                    return
                if b[1] != 0x62:
                    del b[:1]
                    continue
                n = b[4] | b[5] << 8
                if len(b) < n + 8:
                    return
                if b[2] == 0x01 and b[3] == 0x07 and n >= 92:
                    self.on_pvt(bytes(b[6:6 + n]))
                del b[:n + 8]
            else:
                end = b.find(b"\r\n")
                if end < 0:
                    if len(b) > 200:
                        del b[:1]
                        continue
                    return
                line = bytes(b[:end]).decode("ascii", "replace")
                del b[:end + 2]
                fields = line.split("*")[0].split(",")
                if fields[0].endswith("RMC"):
                    self.on_rmc(fields)

    def run(self):
        try:
            read = self.open_fn()
            while not self.stop.is_set():
                data = read()
                if data is None:
                    continue
                if not data:
                    raise OSError("output closed")
                now = time.monotonic()
                with self.lock:
                    self.bytes += len(data)
                    if self.last_read is not None:
                        gap = now - self.last_read
                        self.max_gap_s = max(self.max_gap_s, gap)
                        self.long_gaps += gap > 2.5 * self.period_ms / 1000.0
                    self.last_read = now
                self.buf += data
                self.parse()
        except OSError as e:
            if not self.stop.is_set():
                self.error = str(e)


def pty_opener(path, deadline):
    def open_fn():
        while not os.path.exists(path):
            if time.monotonic() > deadline:
                raise OSError(f"{path} did not appear")
            time.sleep(0.05)
        fd = os.open(path, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(fd)
        termios.tcflush(fd, termios.TCIFLUSH)

        def read():
            import select
            r, _, _ = select.select([fd], [], [], 0.5)
            return os.read(fd, 65536) if r else None
        return read
    return open_fn


def tcp_opener(port, deadline):
    def open_fn():
        while True:
            try:
                s = socket.create_connection(("127.0.0.1", port), timeout=1.0)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        s.settimeout(0.5)

        def read():
            try:
                return s.recv(65536)
            except socket.timeout:
                return None
        return read
    return open_fn


class GarbageHost(threading.Thread):
    """A host on the TCP output writing worst-case input for the decoder."""

    def __init__(self, port):
        super().__init__(daemon=True)
        self.port = port
        self.stop = threading.Event()
        self.sent = 0
        self.error = None

    def run(self):
        block = (b"\xb5\x62\x06\x01\x00\x04" + b"$" * 1026) * 64
        try:
            s = socket.create_connection(("127.0.0.1", self.port), timeout=1.0)
            s.settimeout(0.5)
            while not self.stop.is_set():
                try:
                    self.sent += s.send(block)
                except socket.timeout:
                    pass
                # Drain what the daemon sends this client so it is not dropped as a slow reader.
                try:
                    s.setblocking(False)
                    while s.recv(65536):
                        pass
                except (BlockingIOError, OSError):
                    pass
                finally:
                    s.settimeout(0.5)
        except OSError as e:
            if not self.stop.is_set():
                self.error = str(e)


def proc_stats(pid):
    """(RSS kB, CPU seconds) of a process."""
    with open(f"/proc/{pid}/status") as f:
        rss = int(next(l for l in f if l.startswith("VmRSS:")).split()[1])
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    return rss, (int(fields[11]) + int(fields[12])) / ticks


def udp_drops(port):
    """Datagrams the kernel dropped on the UDP socket bound to port (receive buffer full)."""
    try:
        with open("/proc/net/udp") as f:
            next(f)
            for line in f:
                p = line.split()
                if int(p[1].split(":")[1], 16) == port:
                    return int(p[-1])
    except (OSError, ValueError, IndexError):
        pass
    return None


def slope_kb_per_h(samples):
    """Least-squares slope of RSS over time, kB/h."""
    if len(samples) < 2:
        return 0.0
    ts = [s[0] for s in samples]
    rs = [s[1] for s in samples]
    mt, mr = sum(ts) / len(ts), sum(rs) / len(rs)
    den = sum((t - mt) ** 2 for t in ts)
    return 0.0 if den == 0 else sum((t - mt) * (r - mr) for t, r in zip(ts, rs)) / den * 3600.0


def log_figures(text):
    """What the daemon's log says about skipped epochs, truth and ports."""
    out = {"late_warnings": len(re.findall(r"epoch loop late", text)),
           "drop_warnings": len(re.findall(r"truth: dropped", text))}
    m = re.search(r"truth: (\d+) packets accepted, (\d+) dropped; (\d+) epochs, (\d+) skipped", text)
    if m:
        out.update(accepted=int(m[1]), dropped=int(m[2]), epochs=int(m[3]), skipped=int(m[4]))
    for m in re.finditer(r"output (\S+): (\d+) epochs written, (\d+) dropped", text):
        out[f"port {m[1]}"] = (int(m[2]), int(m[3]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=["soak", "flood"])
    ap.add_argument("--duration", type=float, default=None, help="s (soak: 3600, flood: 60)")
    ap.add_argument("--rate-hz", type=float, default=10.0, help="epoch rate, Hz")
    ap.add_argument("--truth-hz", type=float, default=100.0, help="soak: truth rate, Hz (send_truth: up to 1000)")
    ap.add_argument("--pps", type=float, default=100000.0, help="flood: packets per second")
    ap.add_argument("--good-fraction", type=float, default=0.5, help="flood: fraction of good packets")
    ap.add_argument("--host-garbage", action="store_true", help="flood: a TCP host writing worst-case decoder input")
    ap.add_argument("--sample-s", type=float, default=None, help="s between figure lines (default duration/12)")
    ap.add_argument("--warmup-s", type=float, default=None, help="s before RSS counts (default min(60, duration/6))")
    ap.add_argument("--max-rss-growth-kb", type=float, default=1024.0, help="allowed RSS growth after warm-up, kB")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder")
    ap.add_argument("--keep", action="store_true", help="keep the temp dir (config, logs)")
    a = ap.parse_args()
    duration = a.duration if a.duration is not None else (3600.0 if a.mode == "soak" else 60.0)
    sample_s = a.sample_s if a.sample_s is not None else max(1.0, duration / 12.0)
    warmup_s = a.warmup_s if a.warmup_s is not None else min(60.0, duration / 6.0)

    daemon_bin = os.path.join(a.build, "daemon/gnssemud")
    sender_bin = os.path.join(a.build, "tools/senders/send_truth" if a.mode == "soak" else "tools/soak/flood_truth")
    for b in (daemon_bin, sender_bin):
        if not os.access(b, os.X_OK):
            print(f"soak: {b} not built (cmake --build {a.build} --target gnssemud send_truth flood_truth)",
                  file=sys.stderr)
            return 2

    tmp = tempfile.mkdtemp(prefix="gnssemu-soak-")
    truth_port, tcp_port = free_port(socket.SOCK_DGRAM), free_port(socket.SOCK_STREAM)
    cfg = os.path.join(tmp, "soak.toml")
    with open(cfg, "w") as f:
        f.write(config_text(tmp, a.rate_hz, truth_port, tcp_port))
    log_path = os.path.join(tmp, "gnssemud.log")
    procs = []
    readers = []
    clean = False
    try:
        log = open(log_path, "w")
        daemon = subprocess.Popen([daemon_bin, "--config", cfg], stdout=log, stderr=subprocess.STDOUT,
                                  start_new_session=True)
        procs.append(daemon)
        deadline = time.monotonic() + 15
        period = 1.0 / a.rate_hz
        readers = [Reader("pty", period, pty_opener(os.path.join(tmp, "gps0"), deadline)),
                   Reader("tcp", period, tcp_opener(tcp_port, deadline))]
        for r in readers:
            r.start()
        while time.monotonic() < deadline and not all(r.snapshot()["bytes"] for r in readers):
            if daemon.poll() is not None:
                print(open(log_path).read(), file=sys.stderr)
                print(f"soak: gnssemud exited with {daemon.returncode}", file=sys.stderr)
                return 2
            time.sleep(0.1)
        if a.mode == "soak":
            sender = [sender_bin, "--port", str(truth_port), "--rate", str(a.truth_hz), "--duration",
                      str(duration + 2), "circle", "--radius", "50", "--speed", "10"]
        else:
            sender = [sender_bin, "--port", str(truth_port), "--rate", str(a.pps), "--duration", str(duration),
                      "--good-fraction", str(a.good_fraction)]
        garbage = None
        if a.mode == "flood" and a.host_garbage:
            garbage = GarbageHost(tcp_port)
            garbage.start()
        sender_out = open(os.path.join(tmp, "sender.log"), "w")
        sender_p = subprocess.Popen(sender, stdout=sender_out, stderr=subprocess.STDOUT, start_new_session=True)
        procs.append(sender_p)

        what = (f"{a.rate_hz:g} Hz epochs, truth {a.truth_hz:g} Hz" if a.mode == "soak"
                else f"{a.rate_hz:g} Hz epochs, flood {a.pps:g} packets/s ({a.good_fraction:g} good)")
        print(f"soak: {a.mode} for {duration:g} s: {what}; readers on the pty and TCP; temp {tmp}")
        print(f"{'t_s':>7} {'rss_kB':>7} {'cpu_%':>6} {'epochs pty/tcp':>15} {'fixes pty':>9} "
              f"{'missed pty/tcp':>14} {'MB pty/tcp':>13} {'udp drops':>9}")
        t0 = time.monotonic()
        rss_samples = []
        _, cpu0 = proc_stats(daemon.pid)
        cpu_prev, t_prev = cpu0, t0
        next_sample = t0 + sample_s
        end = t0 + duration
        while True:
            now = time.monotonic()
            if daemon.poll() is not None:
                print(f"soak: gnssemud exited with {daemon.returncode} during the run", file=sys.stderr)
                break
            if now >= next_sample or now >= end:
                rss, cpu = proc_stats(daemon.pid)
                t = now - t0
                if t >= warmup_s:
                    rss_samples.append((t, rss))
                s = [r.snapshot() for r in readers]
                cpu_pct = 100.0 * (cpu - cpu_prev) / max(now - t_prev, 1e-9)
                cpu_prev, t_prev = cpu, now
                drops = udp_drops(truth_port)
                print(f"{t:7.0f} {rss:7d} {cpu_pct:6.1f} {s[0]['pvt']:>7d}/{s[1]['pvt']:<7d} {s[0]['pvt_fix']:9d} "
                      f"{s[0]['pvt_missed']:>6d}/{s[1]['pvt_missed']:<7d} "
                      f"{s[0]['bytes'] / 1e6:6.1f}/{s[1]['bytes'] / 1e6:<6.1f} {drops if drops is not None else '-':>9}",
                      flush=True)
                next_sample += sample_s
                if now >= end:
                    break
            time.sleep(min(0.5, max(0.0, min(next_sample, end) - time.monotonic())))
        run_s = time.monotonic() - t0
        _, cpu_end = proc_stats(daemon.pid) if daemon.poll() is None else (0, cpu_prev)
        kernel_drops = udp_drops(truth_port)
        if a.mode == "flood":
            try:
                sender_p.wait(timeout=10)  # it stops after --duration and prints its counts
            except subprocess.TimeoutExpired:
                pass
        # Stop the readers (a closed output is then no error), the sender,
        # then the daemon (its summary goes to the log).
        for r in readers:
            r.stop.set()
        if garbage:
            garbage.stop.set()
        for p in (sender_p, daemon):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
                    p.wait()
        for r in readers:
            r.join(2)
        log.close()
        sender_out.close()
        figures = log_figures(open(log_path, errors="replace").read())
        s = [r.snapshot() for r in readers]
        expected = round(run_s * a.rate_hz)

        print()
        print(f"run:        {run_s:.0f} s, {expected} epochs expected at {a.rate_hz:g} Hz; "
              f"daemon CPU {100.0 * (cpu_end - cpu0) / run_s:.1f} % of one core on average")
        if rss_samples:
            rss_vals = [r for _, r in rss_samples]
            growth = rss_vals[-1] - rss_vals[0]
            print(f"RSS:        {rss_vals[0]} kB after {warmup_s:.0f} s warm-up, {rss_vals[-1]} kB at the end "
                  f"(growth {growth:+d} kB, max {max(rss_vals)} kB, slope {slope_kb_per_h(rss_samples):+.0f} kB/h)")
        else:
            growth = 0
        for r, x in zip(readers, s):
            print(f"reader {r.name_}: {x['bytes']} bytes; NAV-PVT {x['pvt']} ({x['pvt_fix']} with gnssFixOK), "
                  f"missed {x['pvt_missed']}; RMC {x['rmc']}, missed {x['rmc_missed']}; time jumps {x['jumps']}; "
                  f"longest pause between reads {1000 * x['max_gap_s']:.0f} ms ({x['long_gaps']} over "
                  f"{2.5 * 1000 / a.rate_hz:.0f} ms)"
                  + (f"; error: {r.error}" if r.error else ""))
        print(f"daemon:     epochs {figures.get('epochs', 'n/a')}, skipped {figures.get('skipped', 'n/a')} "
              f"({figures['late_warnings']} 'epoch loop late' lines); truth accepted {figures.get('accepted', 'n/a')}, "
              f"dropped {figures.get('dropped', 'n/a')} ({figures['drop_warnings']} drop log lines); "
              f"kernel UDP drops {kernel_drops if kernel_drops is not None else 'n/a'}")
        for k, v in figures.items():
            if k.startswith("port "):
                print(f"{k}:   {v[0]} epochs written, {v[1]} dropped")
        for line in open(os.path.join(tmp, "sender.log"), errors="replace").read().splitlines()[:40]:
            print(f"sender:     {line}")
        if garbage:
            print(f"host garbage: {garbage.sent / 1e6:.1f} MB written to the TCP output in {run_s:.0f} s "
                  f"({garbage.sent / 1e6 / run_s:.2f} MB/s)" + (f"; error: {garbage.error}" if garbage.error else ""))
        port_drops = sum(v[1] for k, v in figures.items() if k.startswith("port "))
        missed = sum(x["pvt_missed"] + x["rmc_missed"] for x in s)
        clean = (missed == 0 and figures.get("skipped", 0) == 0 and port_drops == 0 and growth <= a.max_rss_growth_kb
                 and all(r.error is None for r in readers) and all(x["pvt"] > 0 for x in s))
        print(f"verdict:    {'clean' if clean else 'NOT clean'} (missed {missed}, skipped {figures.get('skipped', 'n/a')}, "
              f"port drops {port_drops}, RSS growth {growth:+d} kB <= {a.max_rss_growth_kb:g})")
    finally:
        for p in procs:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        for r in readers:
            r.stop.set()
        if a.keep:
            print(f"soak: kept {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)
    return 0 if clean else 1


if __name__ == "__main__":
    sys.exit(main())
