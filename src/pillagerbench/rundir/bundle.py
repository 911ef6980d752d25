"""Results bundles: run directories in one archive (tar.gz) with checksums and the suite they were played
under, written by `pillagerbench export` and read back as run directories (`pillagerbench report`,
`league`, `symmetry`, `verify`).

    bundle.json          format, when and by which suite it was written, the runs (archive name and the
                         path they were exported from), whether replays are in, the harness failures
    checksums.sha256     "<sha256>  <path>" for every other file
    runs/NN/<name>/      each run directory's results (under its own name: a plain run's series is named so): manifests, episodes.jsonl, the ledger, every
                         episode's files (timelines, events, chat, team artefacts); replays only when
                         asked; never the teams' state, checkpoints, logs or what a resume discarded

A bundle is read by unpacking it once into a temporary directory (removed when the process ends).
"""

from __future__ import annotations

import atexit
import hashlib
import io
import json
import shutil
import tarfile
import tempfile
import time
import zlib
from pathlib import Path
from typing import Any

from pillagerbench.rundir import names as N
from pillagerbench.rundir.directory import RunDir

INFO = "bundle.json"
CHECKSUMS = "checksums.sha256"
RUNS = "runs"
FORMAT = 1
REPLAY = N.REPLAY
# what a bundle leaves out of a run directory: folders (anywhere in a path) and file names
_LEFT_OUT_DIRS = {N.STATE, N.CHECKPOINTS, N.LOGS, N.DISCARDED, N.REPORT}
_LEFT_OUT_FILES = (N.LIVE, N.REPLAY_PAGE, f"{N.SERVER_LOG}*.log")


class BundleError(ValueError):
    """Not a bundle, or a damaged one; the message says which file and why."""


def is_bundle(path: Path) -> bool:
    return path.is_file()


def result_files(run: RunDir, replays: bool) -> list[Path]:
    """The files of a run directory that a bundle carries, sorted."""
    out = []
    for path in sorted(p for p in run.path.rglob("*") if p.is_file()):
        rel = path.relative_to(run.path)
        if _LEFT_OUT_DIRS & set(rel.parts[:-1]) or any(path.match(n) for n in _LEFT_OUT_FILES):
            continue
        if path.name == REPLAY and not replays:
            continue
        out.append(path)
    return out


def sha256_of(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def write_bundle(runs: list[tuple[Path, Path]], out: Path, info: dict[str, Any], replays: bool = False) -> int:
    """Write the bundle of `runs` ((directory on disk, its name) each) to `out` (tar.gz); `info` goes
    into bundle.json beside the runs' names. Returns the number of files."""
    sums: list[str] = []
    names = [f"{i:02d}/{Path(name).resolve().name}" for i, (_, name) in enumerate(runs)]
    info = {"format": FORMAT, "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **info, "replays": replays}
    info["runs"] = [{"name": n, "source": str(source)} for n, (_, source) in zip(names, runs)]
    out.parent.mkdir(parents=True, exist_ok=True)
    with tarfile.open(out, "w:gz", compresslevel=6) as tar:
        for name, (run, _) in zip(names, runs):
            for path in result_files(RunDir(run), replays):
                arcname = f"{RUNS}/{name}/{path.relative_to(run).as_posix()}"
                data = path.read_bytes()
                sums.append(f"{sha256_of(data)}  {arcname}")
                _add(tar, arcname, data)
        _add(tar, INFO, json.dumps(info, indent=1).encode())
        _add(tar, CHECKSUMS, ("\n".join(sums) + "\n").encode())
    return len(sums)


def _add(tar: tarfile.TarFile, name: str, data: bytes) -> None:
    member = tarfile.TarInfo(name)
    member.size, member.mtime, member.mode = len(data), int(time.time()), 0o644
    tar.addfile(member, io.BytesIO(data))


_opened: dict[tuple[Path, int, int], tuple[Path, dict]] = {}


def unpack(bundle: Path) -> tuple[Path, dict[str, Any]]:
    """The bundle unpacked into a temporary directory (once per process and version of the file) and
    its bundle.json."""
    if not bundle.exists():
        raise FileNotFoundError(f"{bundle}: no such bundle or run directory")
    stat = bundle.stat()
    key = (bundle.resolve(), stat.st_mtime_ns, stat.st_size)
    if key not in _opened:
        root = Path(tempfile.mkdtemp(prefix="pillagerbench-bundle-"))
        atexit.register(shutil.rmtree, root, True)
        try:
            with tarfile.open(bundle, "r:gz") as tar:
                tar.extractall(root, filter="data")
            info = json.loads((root / INFO).read_text())
        except (tarfile.TarError, EOFError, zlib.error, OSError, ValueError) as exc:
            shutil.rmtree(root, True)
            raise BundleError(f"{bundle}: not a readable results bundle ({type(exc).__name__}: {exc})") from None
        if not (root / CHECKSUMS).is_file():
            raise BundleError(f"{bundle}: not a results bundle (no {CHECKSUMS})")
        if info.get("format") != FORMAT:
            raise BundleError(f"{bundle}: bundle format {info.get('format')!r}, this version reads {FORMAT}")
        _opened[key] = (root, info)
    return _opened[key]


def bundle_runs(bundle: Path) -> list[tuple[Path, str]]:
    """(unpacked run directory, the path it was exported from) of every run in a bundle."""
    root, info = unpack(bundle)
    return [(root / RUNS / r["name"], r["source"]) for r in info["runs"]]


def checksum_problems(root: Path) -> list[str]:
    """Every file of an unpacked bundle whose content differs from its checksum, that is listed but
    missing, or that is not listed."""
    listed = {}
    for line in (root / CHECKSUMS).read_text().splitlines():
        digest, _, name = line.partition("  ")
        listed[name] = digest
    problems = []
    for name, digest in listed.items():
        path = root / name
        if not path.is_file():
            problems.append(f"{name}: listed in {CHECKSUMS} but missing")
        elif sha256_of(path.read_bytes()) != digest:
            problems.append(f"{name}: content differs from its checksum")
    for path in sorted(p for p in (root / RUNS).rglob("*") if p.is_file()):
        name = path.relative_to(root).as_posix()
        if name not in listed:
            problems.append(f"{name}: not in {CHECKSUMS}")
    return problems
