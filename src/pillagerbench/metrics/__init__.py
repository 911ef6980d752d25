"""Metrics of the paper (§IV) from run directories: load.py, formulas.py, calibration.py."""
