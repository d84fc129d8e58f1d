#!/usr/bin/env python3
"""Runs a command and prints its CPU time and memory peaks (docs/performance.md).

    python3 scripts/memory_peaks.py [--runs N] -- COMMAND [ARGS...]

Per run: user and system CPU seconds and the peak resident set (from wait4's resource usage, as
/usr/bin/time -v reports it), and the peaks of private (RssAnon) and file-backed (RssFile) memory,
sampled from /proc/PID/status every millisecond. With --runs N the medians follow.
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
    if args[:1] == ["--runs"]:
        runs = int(args[1])
        args = args[2:]
    if args[:1] == ["--"]:
        args = args[1:]
    if not args:
        sys.exit(__doc__)
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
