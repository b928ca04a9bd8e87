#!/usr/bin/env python3
"""The cohort's summary: every scan's status.json and report.json in one table, cohort.tsv, and one plot,
cohort.png (per-scan stage times and peak memory; the distribution of CPU time, peak memory and organ fit
error over the scans that completed).

cohort.tsv has one line per scan of the cohort: scan, status (ok; failed: vesalius refused the scan; crashed:
the job failed, see its log; not run), the error line, exit code, wall and CPU seconds, peak memory (MB),
host, then `stage:<name>` seconds for each stage of report.json, then every scalar of report.json's metrics
under its dotted path (organ_fits.liver.error_after_mm.mean, rig.tets, completion.*, pose.*: the fit errors,
the checks and any Dice a report carries). A cell is empty where a scan has no such value.

Run by the workflow's summary rule (Snakemake's `script:`), by its onerror handler, or by hand:
    summarize.py COHORT_OUTPUT_DIR    (reads patients/*/ and logs/patient/*.log, writes cohort.tsv and .png)
"""
import csv
import json
import math
import os
import re
import sys
from typing import Dict, List

FIXED = ["scan", "status", "error", "exit_code", "wall_s", "cpu_s", "peak_rss_mb", "host", "slurm_job"]


def _read_json(path: str):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def _last_error(log_path: str) -> str:
    try:
        with open(log_path, errors="replace") as f:
            lines = [line.strip() for line in f if line.strip() and not line.startswith("$ ")]
    except OSError:
        return ""
    for line in reversed(lines):
        if line.startswith("vesalius"):
            return line
    return lines[-1] if lines else ""


def _flatten(value, prefix: str, out: Dict[str, object]) -> None:
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(v, f"{prefix}.{k}" if prefix else str(k), out)
    elif isinstance(value, bool):
        out[prefix] = int(value)
    elif isinstance(value, (int, float, str)):
        out[prefix] = value
    # lists (per-round errors, file lists) stay in report.json


def scan_row(name: str, folder: str, log: str) -> Dict[str, object]:
    row: Dict[str, object] = {"scan": name}
    status = _read_json(os.path.join(folder, "status.json"))
    if status is None:
        ran = os.path.exists(log)
        row.update(status="crashed" if ran else "not run", error=_last_error(log) if ran else "")
        return row
    row.update({k: status.get(k, "") for k in FIXED if k != "scan"})
    report = _read_json(os.path.join(folder, "report.json"))
    if report is not None:
        for stage in report.get("stages", []):
            key = f"stage:{stage['name']}"
            row[key] = round(float(row.get(key, 0.0)) + float(stage["seconds"]), 3)
        metrics: Dict[str, object] = {}
        _flatten(report.get("metrics", {}), "", metrics)
        row.update(metrics)
    return row


def columns(rows: List[Dict[str, object]]) -> List[str]:
    stages: List[str] = []
    metrics = set()
    for row in rows:
        for k in row:
            if k.startswith("stage:") and k not in stages:
                stages.append(k)
            elif k not in FIXED and not k.startswith("stage:"):
                metrics.add(k)
    return FIXED + stages + sorted(metrics)


def _cell(v) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v).replace("\t", " ").replace("\n", " ")


def write_tsv(rows: List[Dict[str, object]], path: str) -> None:
    cols = columns(rows)
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f, delimiter="\t", lineterminator="\n", quoting=csv.QUOTE_NONE, escapechar="\\")
        w.writerow(cols)
        for row in rows:
            w.writerow([_cell(row.get(c, "")) for c in cols])
    os.replace(tmp, path)


def _numbers(rows, key) -> List[float]:
    out = []
    for r in rows:
        v = r.get(key)
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v):
            out.append(float(v))
    return out


def write_png(rows: List[Dict[str, object]], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cols = columns(rows)
    stages = [c for c in cols if c.startswith("stage:")]
    names = [str(r["scan"]) for r in rows]
    y = list(range(len(rows)))
    height = max(4.0, 0.35 * len(rows) + 1.5)
    fig, axes = plt.subplots(2, 2, figsize=(13, 2 * height), gridspec_kw={"width_ratios": [3, 2]})

    ax = axes[0][0]
    left = [0.0] * len(rows)
    cmap = plt.get_cmap("tab20")
    for i, stage in enumerate(stages):
        widths = [float(r.get(stage) or 0.0) for r in rows]
        ax.barh(y, widths, left=left, color=cmap(i % 20), label=stage[len("stage:"):])
        left = [a + b for a, b in zip(left, widths)]
    for i, r in enumerate(rows):
        if r.get("status") != "ok":
            # vesalius names the file first; the scan's name is on the axis, so the folder is left out
            error = re.sub(r"(/[^/:\s]+)+/", "", str(r.get("error", "")).removeprefix("vesalius: "))
            ax.text(left[i], i, f"  {r.get('status')}: {error[:80]}", va="center", color="firebrick", fontsize=8)
    ax.set_yticks(y, names)
    ax.invert_yaxis()
    ax.set_xlabel("stage time (s, report.json)")
    ax.set_title("per scan: stage times")
    if stages:
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=4)

    ax = axes[0][1]
    mem = [float(r.get("peak_rss_mb") or 0.0) for r in rows]
    ax.barh(y, mem, color=["steelblue" if r.get("status") == "ok" else "firebrick" for r in rows])
    ax.set_yticks(y, names)
    ax.invert_yaxis()
    ax.set_xlabel("peak resident memory (MB)")
    ax.set_title("per scan: peak memory")

    ok = [r for r in rows if r.get("status") == "ok"]
    ax = axes[1][0]
    cpu = _numbers(ok, "cpu_s")
    wall = _numbers(ok, "wall_s")
    if cpu:
        bins = min(20, max(3, len(cpu)))
        ax.hist([cpu, wall], bins=bins, label=["CPU (user + system)", "wall"], color=["darkorange", "grey"])
        ax.legend(fontsize=8)
    ax.set_xlabel("seconds per scan")
    ax.set_ylabel("scans")
    ax.set_title(f"distribution over {len(ok)} completed of {len(rows)} scans")

    ax = axes[1][1]
    fit_keys = [c for c in cols if c.startswith("organ_fits.") and c.endswith("error_after_mm.mean")]
    errors = [v for k in fit_keys for v in _numbers(ok, k)]
    if errors:
        ax.hist(errors, bins=min(20, max(3, len(errors))), color="seagreen")
        ax.set_xlabel("organ fit: mean marker error after the fit (mm)")
        ax.set_ylabel("organ fits")
        ax.set_title(f"{len(errors)} organ fits")
    else:
        ax.hist(_numbers(ok, "peak_rss_mb"), bins=min(20, max(3, len(ok))), color="steelblue")
        ax.set_xlabel("peak resident memory (MB)")
        ax.set_ylabel("scans")
        ax.set_title("no organ fits in this cohort; peak memory")
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=90)
    plt.close(fig)
    os.replace(tmp, path)


def summarize(patients: Dict[str, str], logs: Dict[str, str], tsv: str, png: str) -> List[Dict[str, object]]:
    rows = [scan_row(name, patients[name], logs.get(name, "")) for name in sorted(patients)]
    write_tsv(rows, tsv)
    write_png(rows, png)
    return rows


def _print_counts(rows) -> None:
    counts: Dict[str, int] = {}
    for r in rows:
        counts[str(r["status"])] = counts.get(str(r["status"]), 0) + 1
    print(f"{len(rows)} scans: " + ", ".join(f"{n} {s}" for s, n in sorted(counts.items())))
    for r in rows:
        if r["status"] != "ok":
            print(f"  {r['scan']}: {r['status']}: {r.get('error', '')}")


def _from_snakemake(smk) -> None:
    with open(smk.log[0], "w") as log:
        sys.stdout = sys.stderr = log
        patients = {os.path.basename(os.path.normpath(p)): p for p in smk.input}
        rows = summarize(patients, dict(smk.params.logs), smk.output.tsv, smk.output.png)
        _print_counts(rows)


def _from_command_line(argv: List[str]) -> int:
    if len(argv) != 2 or argv[1].startswith("-"):
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    out = argv[1]
    folder = os.path.join(out, "patients")
    names = sorted(os.listdir(folder)) if os.path.isdir(folder) else []
    log_folder = os.path.join(out, "logs", "patient")
    if os.path.isdir(log_folder):
        names = sorted(set(names) | {f[:-4] for f in os.listdir(log_folder) if f.endswith(".log")})
    rows = summarize({n: os.path.join(folder, n) for n in names},
                     {n: os.path.join(log_folder, n + ".log") for n in names},
                     os.path.join(out, "cohort.tsv"), os.path.join(out, "cohort.png"))
    _print_counts(rows)
    return 0


if "snakemake" in globals():
    _from_snakemake(snakemake)  # noqa: F821 (defined by Snakemake's script directive)
elif __name__ == "__main__":
    sys.exit(_from_command_line(sys.argv))
