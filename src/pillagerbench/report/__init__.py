"""The report: tables.py, plots.py, html.py; build.py is `pillagerbench report`."""
