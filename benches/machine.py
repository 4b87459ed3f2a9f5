"""What a benchmark's table states about where it ran: the cores this process may use, the CPU model and the
git commit (imported by the benchmark scripts beside it)."""

from __future__ import annotations

import os
import platform
import subprocess
from pathlib import Path


def machine() -> str:
    """'N cores, CPU model; commit abc1234' (the cores as nproc counts them: this process's affinity)."""
    cpu = next(
        (
            line.split(":", 1)[1].strip()
            for line in Path("/proc/cpuinfo").read_text().splitlines()
            if "model name" in line
        ),
        platform.processor(),
    )
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=False
    )
    return f"{len(os.sched_getaffinity(0))} cores, {cpu}; commit {commit.stdout.strip() or 'unknown'}"
