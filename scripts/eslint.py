"""eslint over src/pillagerbench/js (from the current directory, the repository's root) with the
pinned development packages of package.json, installed on first use into their own cache directory.

    .venv/bin/python scripts/eslint.py          # check
    .venv/bin/python scripts/eslint.py --fix    # and rewrite what it can
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from pillagerbench.host.node import NODE_ENV_ALLOWED, allowed_env, ensure_node_modules, node_binary


def main(argv: list[str]) -> int:
    dev = ensure_node_modules(quiet=True, dev=True)
    js = Path.cwd() / "src" / "pillagerbench" / "js"
    cmd = [str(node_binary()), str(dev / "eslint" / "bin" / "eslint.js"), "--config", "eslint.config.js"]
    cmd += ["--max-warnings", "0", *argv, "."]
    env = {**allowed_env(NODE_ENV_ALLOWED), "NODE_PATH": str(dev)}  # no key of the user's (docs/security.md)
    return subprocess.run(cmd, cwd=js, env=env).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
