"""The scans of a cohort: a folder of scans, or a CSV sheet naming each scan and its optional label map.

Folder: every scan file (.nii.gz .nii .nrrd .nhdr .mha .mhd) and every sub-folder (a DICOM series) is a
scan, named after its file name without the extension. A label map of scan NAME is the file NAME<suffix>
with a scan extension beside it (suffix ".organs" by default: ct01.nii.gz, ct01.organs.nii.gz), its label
table NAME<suffix>.tsv if there is one (else vesalius looks beside the map).

Sheet (.csv): a header with the columns scan, path and optionally organs, organ_table; relative paths are
taken from the sheet's folder. Lines starting with # are comments.

Names are checked here, before any job runs: unique, and of letters, digits, '.', '_' and '-' (they become
folder and Slurm job names).
"""
import csv
import os
import re
from dataclasses import dataclass
from typing import Dict, Optional

NAME_PATTERN = r"[A-Za-z0-9][A-Za-z0-9._-]*"
SCAN_EXTENSIONS = (".nii.gz", ".nii", ".nrrd", ".nhdr", ".mha", ".mhd")


@dataclass
class Scan:
    path: str
    organs: Optional[str] = None
    organ_table: Optional[str] = None


class CohortError(ValueError):
    pass


def _scan_stem(file_name: str) -> Optional[str]:
    for ext in SCAN_EXTENSIONS:
        if file_name.lower().endswith(ext):
            return file_name[: -len(ext)]
    return None


def _check_name(name: str, where: str, scans: Dict[str, Scan]) -> None:
    if not re.fullmatch(NAME_PATTERN, name):
        raise CohortError(f"{where}: scan name {name!r} must be letters, digits, '.', '_' or '-'")
    if name in scans:
        raise CohortError(f"{where}: scan name {name!r} appears twice")


def read_folder(folder: str, suffix: str = ".organs") -> Dict[str, Scan]:
    entries = sorted(os.listdir(folder))
    scans: Dict[str, Scan] = {}
    maps: Dict[str, str] = {}
    tables: Dict[str, str] = {}
    for entry in entries:
        path = os.path.abspath(os.path.join(folder, entry))
        if entry.startswith("."):
            continue
        if os.path.isdir(path):
            _check_name(entry, folder, scans)
            scans[entry] = Scan(path)
            continue
        if suffix and entry.endswith(suffix + ".tsv"):
            tables[entry[: -len(suffix + ".tsv")]] = path
            continue
        stem = _scan_stem(entry)
        if stem is None:
            continue
        if suffix and stem.endswith(suffix):
            maps[stem[: -len(suffix)]] = path
            continue
        _check_name(stem, folder, scans)
        scans[stem] = Scan(path)
    for name, path in maps.items():
        if name not in scans:
            raise CohortError(f"{path}: a label map of no scan (no {name} with a scan extension beside it)")
        scans[name].organs = path
    for name, path in tables.items():
        if name not in maps:
            raise CohortError(f"{path}: a label table of no label map")
        scans[name].organ_table = path
    return scans


def read_sheet(sheet: str) -> Dict[str, Scan]:
    base = os.path.dirname(os.path.abspath(sheet))

    def resolve(p: str) -> Optional[str]:
        p = (p or "").strip()
        return os.path.normpath(os.path.join(base, p)) if p else None

    scans: Dict[str, Scan] = {}
    with open(sheet, newline="") as f:
        rows = csv.DictReader(line for line in f if line.strip() and not line.lstrip().startswith("#"))
        missing = {"scan", "path"} - set(rows.fieldnames or [])
        if missing:
            raise CohortError(f"{sheet}: the header needs the columns scan and path (missing {', '.join(sorted(missing))})")
        for i, row in enumerate(rows, start=2):
            name = (row.get("scan") or "").strip()
            _check_name(name, f"{sheet} line {i}", scans)
            path = resolve(row.get("path"))
            if not path:
                raise CohortError(f"{sheet} line {i}: scan {name} has no path")
            organs, table = resolve(row.get("organs")), resolve(row.get("organ_table"))
            if table and not organs:
                raise CohortError(f"{sheet} line {i}: scan {name} has an organ_table but no organs")
            scans[name] = Scan(path, organs, table)
    return scans


def read_cohort(source: str, suffix: str = ".organs") -> Dict[str, Scan]:
    """The scans of a folder or a .csv sheet, by name. Missing files are left to Snakemake, which names them."""
    if os.path.isdir(source):
        scans = read_folder(source, suffix)
    elif source.lower().endswith(".csv") and os.path.isfile(source):
        scans = read_sheet(source)
    else:
        raise CohortError(f"{source}: neither a folder of scans nor a .csv sheet")
    if not scans:
        raise CohortError(f"{source}: no scans")
    return scans
