"""What this machine gives a run: the pinned Node runtime (node.py) and its cores, load and lag (machine.py)."""
