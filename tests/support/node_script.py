"""Run a small script in the package's real Node with the js/ folder as argv[1]; parse its JSON output."""

from __future__ import annotations

import json
import subprocess

from pillagerbench.host.node import JS_DIR, node_binary, node_env


def run_node_script(script: str):
    proc = subprocess.run(
        [str(node_binary()), "-e", script, str(JS_DIR)], capture_output=True, text=True, env=node_env(), timeout=60
    )
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)
