"""Replays: what happened in an episode, recorded from the server's truth (`record.py`), read back
tolerantly (`read.py`) and shown as one self-contained HTML page (`page.py`). Format: docs/replays.md."""
