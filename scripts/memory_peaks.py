#!/usr/bin/env python3
"""Runs a command and prints its CPU time and memory peaks (docs/performance.md).

    python3 scripts/memory_peaks.py [--runs N] [--together K] -- COMMAND [ARGS...]

Per run: user and system CPU seconds and the peak resident set (from wait4's resource usage, as
/usr/bin/time -v reports it), and the peaks of private (RssAnon) and file-backed (RssFile) memory,
sampled from /proc/PID/status every millisecond. With --runs N the medians follow. With
--together K, K copies of the command run at once: a line per process, then the peak of their
summed private memory and of their summed proportional set size (Pss from /proc/PID/smaps_rollup:
a page shared by the K processes counts 1/K in each), which is what they take together.
"""
import os
import statistics
import subprocess
import sys
import time


def status_kib(pid):
    values = {}
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                key, _, rest = line.partition(":")
                if key in ("RssAnon", "RssFile", "RssShmem"):
                    values[key] = int(rest.split()[0])
    except (FileNotFoundError, ProcessLookupError, ValueError):
        return None
    return values


def pss_kib(pid):
    try:
        with open(f"/proc/{pid}/smaps_rollup") as f:
            for line in f:
                if line.startswith("Pss:"):
                    return int(line.split()[1])
    except (FileNotFoundError, ProcessLookupError, ValueError):
        return None
    return None


def run_together(cmd, k):
    procs = [subprocess.Popen(cmd, stdout=subprocess.DEVNULL) for _ in range(k)]
    alive = {p.pid: p for p in procs}
    peaks = {p.pid: [0, 0] for p in procs}
    usage = {}
    sum_anon = sum_pss = 0
    while alive:
        anon_now = pss_now = 0
        for pid in list(alive):
            done, status, ru = os.wait4(pid, os.WNOHANG)
            if done:
                usage[pid] = ru
                del alive[pid]
                continue
            s = status_kib(pid)
            if s:
                peaks[pid][0] = max(peaks[pid][0], s.get("RssAnon", 0))
                peaks[pid][1] = max(peaks[pid][1], s.get("RssFile", 0))
                anon_now += s.get("RssAnon", 0)
            pss = pss_kib(pid)
            pss_now += pss or 0
        sum_anon = max(sum_anon, anon_now)
        sum_pss = max(sum_pss, pss_now)
        time.sleep(0.002)
    print("process user_s sys_s cpu_s peak_rss_MiB private_MiB file_MiB")
    for i, p in enumerate(procs):
        ru = usage[p.pid]
        print(f"{i + 1} {ru.ru_utime:.3f} {ru.ru_stime:.3f} {ru.ru_utime + ru.ru_stime:.3f} {ru.ru_maxrss / 1024:.1f} "
              f"{peaks[p.pid][0] / 1024:.1f} {peaks[p.pid][1] / 1024:.1f}")
    print(f"together: peak private {sum_anon / 1024:.1f} MiB, peak Pss {sum_pss / 1024:.1f} MiB")


def run(cmd):
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
    anon = file_backed = 0
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            break
        s = status_kib(proc.pid)
        if s:
            anon = max(anon, s.get("RssAnon", 0))
            file_backed = max(file_backed, s.get("RssFile", 0))
        time.sleep(0.001)
    if os.WEXITSTATUS(status) != 0:
        sys.exit(f"{cmd[0]} exited with {os.WEXITSTATUS(status)}")
    return usage.ru_utime, usage.ru_stime, usage.ru_maxrss / 1024, anon / 1024, file_backed / 1024


def main():
    args = sys.argv[1:]
    runs = 1
    together = 0
    while args[:1] in (["--runs"], ["--together"]):
        if args[0] == "--runs":
            runs = int(args[1])
        else:
            together = int(args[1])
        args = args[2:]
    if args[:1] == ["--"]:
        args = args[1:]
    if not args:
        sys.exit(__doc__)
    if together > 0:
        run_together(args, together)
        return
    rows = []
    print("user_s sys_s cpu_s peak_rss_MiB private_MiB file_MiB")
    for _ in range(runs):
        u, s, rss, anon, fb = run(args)
        rows.append((u, s, u + s, rss, anon, fb))
        print(f"{u:.3f} {s:.3f} {u + s:.3f} {rss:.1f} {anon:.1f} {fb:.1f}", flush=True)
    if runs > 1:
        med = [statistics.median(c) for c in zip(*rows)]
        print("median " + " ".join(f"{v:.3f}" if i < 3 else f"{v:.1f}" for i, v in enumerate(med)))


if __name__ == "__main__":
    main()
