#!/usr/bin/env python3
"""One scan of the cohort: `vesalius patient ... --out DIR`, measured, its outcome in DIR/status.json.

    run_patient.py --vesalius BIN --out DIR --log LOG -- PATIENT_ARGUMENTS...

status.json holds the exit code, the error line (vesalius's last `vesalius: ...` line), the wall time,
the CPU time (user + system) and the peak resident memory of the process (getrusage of the child; the
process is single, so its peak is the job's).

Exit codes 3 (bad input) and 4 (numerical failure) are the scan's: DIR is made holding status.json alone
and this script exits 0, so the cohort goes on and the summary lists the error. Any other failure (a usage
error of the workflow's options, a crash, a kill for memory or time) is the job's: this script exits
non-zero and Snakemake treats the job as failed (retried on the next run, or with --restart-times).
"""
import argparse
import json
import os
import resource
import shlex
import signal
import subprocess
import sys
import time

SCAN_FAILURES = {3: "bad input", 4: "numerical failure"}


def error_line(log_path: str) -> str:
    """The last line vesalius wrote as its error, else the log's last line."""
    try:
        with open(log_path, errors="replace") as f:
            lines = [line.strip() for line in f if line.strip() and not line.startswith("$ ") and
                     not line.startswith("Run with --help")]  # CLI11's hint after a usage error
    except OSError:
        return ""
    for line in reversed(lines):
        if line.startswith("vesalius:"):
            return line
    return lines[-1] if lines else ""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vesalius", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--log", required=True)
    parser.add_argument("patient_args", nargs=argparse.REMAINDER)
    a = parser.parse_args()
    args = a.patient_args[1:] if a.patient_args[:1] == ["--"] else a.patient_args
    command = [a.vesalius, "patient", *args, "--out", a.out, "--progress", "none"]

    os.makedirs(os.path.dirname(os.path.abspath(a.log)), exist_ok=True)
    with open(a.log, "w") as log:
        log.write("$ " + " ".join(shlex.quote(c) for c in command) + "\n")
        log.flush()
        start = time.monotonic()
        returncode = subprocess.call(command, stdout=log, stderr=subprocess.STDOUT)
        wall = time.monotonic() - start
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    status = {
        "exit_code": returncode,
        "wall_s": round(wall, 3),
        "cpu_s": round(usage.ru_utime + usage.ru_stime, 3),
        "peak_rss_mb": round(usage.ru_maxrss / 1024.0, 1),  # Linux reports kilobytes
        "host": os.uname().nodename,
        "slurm_job": os.environ.get("SLURM_JOB_ID", ""),
    }
    if returncode == 0:
        status.update(status="ok", error="")
    elif returncode in SCAN_FAILURES:
        status.update(status="failed", error=error_line(a.log), failure=SCAN_FAILURES[returncode])
        os.makedirs(a.out, exist_ok=True)
    else:
        what = f"killed by {signal.Signals(-returncode).name}" if returncode < 0 else f"exit code {returncode}"
        message = f"vesalius patient {what}: {error_line(a.log)}"
        with open(a.log, "a") as log:
            log.write(message + "\n")
        print(f"{message} (log {a.log})", file=sys.stderr)
        return returncode if returncode > 0 else 128 - returncode
    with open(os.path.join(a.out, "status.json"), "w") as f:
        json.dump(status, f, indent=2)
        f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
