# SPDX-License-Identifier: BSD-3-Clause
"""Timing helpers shared by the benchmark scripts of this folder (imported by path: the scripts
run from here, so Python finds this module beside them)."""
import os
import re
import subprocess
import sys
import time


def run(cmd, env=None):
    """Runs cmd under /usr/bin/time; returns (stdout, wall seconds, peak RSS MiB). Exits the
    script with the command's output when it fails."""
    p = subprocess.run(["/usr/bin/time", "-f", "TIME %e %M"] + cmd, capture_output=True,
                       text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{p.stdout}{p.stderr}")
    wall, rss = re.search(r"TIME ([\d.]+) (\d+)", p.stderr).groups()
    return p.stdout, float(wall), int(rss) / 1024.0


def run_wall(cmd, env=None):
    """Runs cmd; returns (stdout, wall seconds from a monotonic clock: finer than /usr/bin/time's
    10 ms, for sub-second commands). Exits the script with the command's output when it fails."""
    start = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    seconds = time.monotonic() - start
    if p.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{p.stdout}{p.stderr}")
    return p.stdout, seconds


def fresh(output):
    """Removes an earlier output and flushes dirty pages, so a timed run neither pays for
    replacing a file (ext4 flushes the new one on rename-over) nor competes with write-back."""
    if os.path.exists(output):
        os.remove(output)
    os.sync()


def warm(path):
    """Reads a file once so that timed runs find it in the page cache."""
    with open(path, "rb") as f:
        while f.read(1 << 24):
            pass
