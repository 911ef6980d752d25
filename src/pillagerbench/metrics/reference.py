"""Upstream's reference scores: each built-in opponent's mean score (blue) against a do_nothing red
team, hard-coded in upstream's analysis script (issue 11; Dash & Dine ×0.1, as reported). The
fidelity check compares with them; `--calibration reference` uses them as σ_blue for the sabotage
metric, as upstream's analysis did. Upstream measured blue only; the red side is compared with the
same values.

The suite's own reference (suite/figures.py) holds the same opponents' points against do_nothing
with their 95 % intervals, per scoring, under a named suite version, for putting a run beside the
benchmark's own figures as well."""

from __future__ import annotations

REFERENCE_SCORES: dict[str, dict[str, float]] = {
    "mushroom_war": {"aggressive": 20.27, "balanced": 16.75, "passive": 25.23, "slimy": 22.18},
    "dash_and_dine": {"berries": 34.73, "cake_beetroot": 7.83, "melon_pumpkin": 15.82, "potato_cookie": 13.12},
}
# the conditions both references were measured under (suite/conditions.py), besides the scoring each column
# names: upstream's step protocol, 120 s episodes (the suite's default length), the paper's layout
REFERENCE_CONDITIONS: dict[str, object] = {"protocol": "upstream"}
REFERENCE_LENGTH = 120.0
REFERENCE_SPLIT = "paper"
# the value of --calibration that selects them
REFERENCE_CALIBRATION = "reference"
