"""Metrics of the paper (§IV) from run directories: runs.py, formulas.py, calibration.py."""
