#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemu sweep end to end (docs/sweep.md), a few tasks of 30 simulated
seconds each.

`local`: plan, run --jobs 2, status, resume (nothing to do), collect twice
(same bytes), the worst case's reproduce command gives its errors.csv byte
for byte, and `--executor slurm` without Slurm on PATH exits 2.

`slurm`: starts a one-node Slurm on loopback (tools/slurm-local.sh), plans
four tasks, removes the truth file of one before the run (a deliberately
failing task), runs through `--executor slurm`, checks `sweep status`
(Slurm's state: one failed with its id, three done), restores the file,
`--resume` resubmits only that task, collects, compares every result file
with a local run of the same plan, and stops the cluster: no munged,
slurmctld, slurmd or slurmstepd of it left, no zombies. Exit 77 (skip)
without Slurm's packages or root."""
import argparse
import filecmp
import os
import shutil
import subprocess
import sys
import tempfile

WEEK = 2190
TOW0_S = 522000.0  # 2022-01-01 01:00 GPST, inside brdc0010.22n


def run(args, ok=(0,), env=None):
    p = subprocess.run(args, capture_output=True, text=True, env=env, timeout=120)
    if p.returncode not in ok:
        sys.exit(f"FAIL: {' '.join(args)} -> {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p


def write_truth(path, lat, seconds=30):
    with open(path, "w") as f:
        f.write("gps_week,tow_s,lat_deg,lon_deg,height_m\n")
        for k in range(seconds + 1):
            f.write(f"{WEEK},{TOW0_S + k:.1f},{lat:.6f},2.295000,100.000\n")


def make_sweep(tmp, nav, scenarios):
    with open(os.path.join(tmp, "base.toml"), "w") as f:
        f.write(f'[origin]\nlat_deg = 48.8738\nlon_deg = 2.2950\nheight_m = 100.0\n\n[nav]\nfile = "{nav}"\n\n'
                "[receiver]\nrate_hz = 1.0\nseed = 1\n")
    write_truth(os.path.join(tmp, "a.csv"), 48.8738)
    write_truth(os.path.join(tmp, "b.csv"), 48.9)
    with open(os.path.join(tmp, "sweep.toml"), "w") as f:
        f.write('config = "base.toml"\noutputs = ["errors"]\n\n[axes]\ntruth = "a.csv"\nseed = [1, 2, 3]\n'
                f'scenario = "{os.path.join(scenarios, "tunnel.toml")}"\n\n'
                '[[case]]\n\n[[case]]\ntruth = "b.csv"\nseed = 9\n'
                f'scenario = "{os.path.join(scenarios, "drone_drag_off.toml")}"\n')
    return os.path.join(tmp, "sweep.toml")


def same_results(a, b, n):
    for i in range(n):
        da, db = os.path.join(a, "tasks", str(i)), os.path.join(b, "tasks", str(i))
        names = sorted(x for x in os.listdir(da) if x != "task.log")
        if names != sorted(x for x in os.listdir(db) if x != "task.log"):
            sys.exit(f"FAIL: task {i}: files differ: {names} vs {os.listdir(db)}")
        for name in names:
            if not filecmp.cmp(os.path.join(da, name), os.path.join(db, name), shallow=False):
                sys.exit(f"FAIL: task {i}: {name} differs between {a} and {b}")


def collect_twice(g, d):
    out = run([g, "sweep", "collect", d]).stdout
    first = open(os.path.join(d, "results.csv"), "rb").read() + open(os.path.join(d, "report.html"), "rb").read()
    run([g, "sweep", "collect", d])
    second = open(os.path.join(d, "results.csv"), "rb").read() + open(os.path.join(d, "report.html"), "rb").read()
    if first != second:
        sys.exit("FAIL: sweep collect twice gave different bytes")
    return out


def local_case(g, tmp, sweep):
    d = os.path.join(tmp, "local")
    run([g, "sweep", "plan", sweep, "--out", d])
    run([g, "sweep", "run", d, "--jobs", "2"])
    st = run([g, "sweep", "status", d]).stdout
    if "done 4, failed 0" not in st:
        sys.exit(f"FAIL: status: {st}")
    again = run([g, "sweep", "run", d, "--resume"]).stdout
    if "nothing to run" not in again:
        sys.exit(f"FAIL: resume of a finished sweep ran something: {again}")
    out = collect_twice(g, d)
    cmd = next(line for line in out.splitlines() if line.startswith("reproduce: ")).split(" ", 1)[1].split()
    task = next(line for line in out.splitlines() if line.startswith("worst: ")).split()[2].rstrip(",")
    cmd[0] = g
    cmd[-1] = os.path.join(tmp, "again.csv")
    run(cmd)
    if not filecmp.cmp(cmd[-1], os.path.join(d, "tasks", task, "errors.csv"), shallow=False):
        sys.exit("FAIL: the reproduce command does not give the task's errors.csv")
    env = dict(os.environ, PATH="/nonexistent")
    p = run([g, "sweep", "run", d, "--executor", "slurm"], ok=(2,), env=env)
    if "no Slurm" not in p.stderr:
        sys.exit(f"FAIL: without Slurm: {p.stderr}")
    print(f"local: 4 tasks, worst task {task}; {out.strip()}")


def slurm_case(g, tmp, sweep, script):
    for prog in ("slurmctld", "slurmd", "munged", "sbatch"):
        if shutil.which(prog) is None:
            print(f"SKIP: {prog} not installed (tools/install-deps.sh)")
            sys.exit(77)
    if os.geteuid() != 0:
        print("SKIP: the local Slurm cluster needs root")
        sys.exit(77)
    sdir = os.path.join(tmp, "slurm-cluster")
    env = dict(os.environ, GNSSEMU_SLURM_DIR=sdir, SLURM_CONF=os.path.join(sdir, "slurm.conf"),
               GNSSEMU_SLURM_PORT="16917")
    pids = []
    try:
        p = subprocess.run([script, "start"], env=env, capture_output=True, text=True, timeout=60)
        if p.returncode != 0 and "not 127.x" in p.stderr:
            print(f"SKIP: {p.stderr.strip()}")
            sys.exit(77)
        if p.returncode != 0:
            sys.exit(f"FAIL: slurm-local.sh start -> {p.returncode}\n{p.stderr}")
        for name in ("munge/munged.pid", "slurmctld.pid", "slurmd.pid"):
            pids.append(int(open(os.path.join(sdir, name)).read().split()[0]))
        d = os.path.join(tmp, "slurm")
        run([g, "sweep", "plan", sweep, "--out", d, "--no-calibrate"], env=env)
        # Task 3 reads b.csv: gone at run time, as on a flaky shared filesystem.
        os.rename(os.path.join(tmp, "b.csv"), os.path.join(tmp, "b.csv.away"))
        run([g, "sweep", "run", d, "--executor", "slurm", "--array-limit", "2", "--time", "5", "--wait"], ok=(1,), env=env)
        st = run([g, "sweep", "status", d, "--list"], env=env)
        rows = [line.split(",", 2) for line in st.stdout.splitlines()[1:]]
        states = {int(r[0]): r[1] for r in rows}
        if states != {0: "done", 1: "done", 2: "done", 3: "failed"}:
            sys.exit(f"FAIL: status after the first run: {states}\n{st.stdout}")
        if "failed: task 3: " not in st.stderr or "Slurm job" not in st.stderr or "b.csv" not in st.stderr:
            sys.exit(f"FAIL: the failed task's report lacks its id, Slurm state or log: {st.stderr}")
        os.rename(os.path.join(tmp, "b.csv.away"), os.path.join(tmp, "b.csv"))
        run([g, "sweep", "run", d, "--executor", "slurm", "--resume", "--wait"], env=env)
        jobs = open(os.path.join(d, "slurm", "jobs.csv")).read().splitlines()
        if len(jobs) != 3 or jobs[2].split(",")[1] != "3":
            sys.exit(f"FAIL: --resume should submit task 3 alone: {jobs}")
        st = run([g, "sweep", "status", d], env=env).stdout
        if "done 4, failed 0" not in st:
            sys.exit(f"FAIL: status after resume: {st}")
        out = collect_twice(g, d)
        rows = open(os.path.join(d, "results.csv")).read().splitlines()
        if len(rows) != 5:
            sys.exit(f"FAIL: results.csv has {len(rows) - 1} rows, want 4")
        local = os.path.join(tmp, "local")
        run([g, "sweep", "plan", sweep, "--out", local, "--no-calibrate"])
        run([g, "sweep", "run", local, "--jobs", "2"])
        same_results(d, local, 4)
        print(f"slurm: 4 tasks, one failed then resumed; results equal the local run's; {out.strip()}")
    finally:
        subprocess.run([script, "stop"], env=env, capture_output=True, timeout=60)
    for pid in pids:
        state = proc_state(pid)
        # A zombie has stopped; reaping it is its parent's (PID 1's) business.
        if state not in (None, "Z"):
            sys.exit(f"FAIL: process {pid} still running after stop (state {state})")
    left = [p for p in subprocess.run(["pgrep", "-f", sdir], capture_output=True, text=True).stdout.split()
            if proc_state(p) not in (None, "Z")]
    if left:
        sys.exit(f"FAIL: processes of the cluster left: {left}")


def proc_state(pid):
    """The state letter of /proc/PID/stat, or None when the process is gone."""
    try:
        return open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[0]
    except OSError:
        return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--scenarios", required=True)
    ap.add_argument("--slurm-local", required=True)
    ap.add_argument("case", choices=["local", "slurm"])
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix=f"gnssemu-sweep-{a.case}-")
    try:
        sweep = make_sweep(tmp, os.path.abspath(a.nav), os.path.abspath(a.scenarios))
        if a.case == "local":
            local_case(a.gnssemu, tmp, sweep)
        else:
            slurm_case(a.gnssemu, tmp, sweep, a.slurm_local)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("PASS")


if __name__ == "__main__":
    main()
