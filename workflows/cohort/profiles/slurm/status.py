#!/usr/bin/env python3
"""Snakemake --cluster-status for Slurm: prints running, success or failed for one job id.

Asks the controller (scontrol, which knows jobs until MinJobAge after they end), then the accounting
database (sacct, where there is one). A job neither knows is reported failed: Snakemake then retries it
or, with --keep-going, goes on with the others.
"""
import re
import subprocess
import sys

RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "REQUEUE_HOLD",
           "REQUEUE_FED", "RESIZING", "SIGNALING", "STAGE_OUT", "STOPPED", "PREEMPTED", "RESV_DEL_HOLD"}


def state(jobid: str) -> str:
    try:
        out = subprocess.run(["scontrol", "show", "job", "-o", jobid], capture_output=True, text=True,
                             timeout=30).stdout
        m = re.search(r"\bJobState=(\S+)", out)
        if m:
            return m.group(1)
    except (OSError, subprocess.TimeoutExpired):
        pass
    try:
        out = subprocess.run(["sacct", "-j", jobid, "-X", "-n", "-P", "-o", "State"], capture_output=True,
                             text=True, timeout=30).stdout.split()
        if out:
            return out[0].split()[0]  # "CANCELLED by 0" -> CANCELLED
    except (OSError, subprocess.TimeoutExpired):
        pass
    return "UNKNOWN"


if __name__ == "__main__":
    s = state(sys.argv[1].split(";")[0])
    print("success" if s == "COMPLETED" else "running" if s in RUNNING else "failed")
