"""Upstream's quirks that PillagerBench reproduces, in one place: each says what upstream did and
which switch applies it (docs/faithful.md: `scoring=upstream`, `protocol=upstream`, or both with
`paper=true`; docs/fidelity.md has the evidence). The code that applies each one names it from here.

- UPSTREAM_WAIT_S (scoring=upstream): upstream's judge started its code after an 80-tick wait (4 s)
  and wrote a rewards line each 1 s after that (the first one 1 s in), so line k (from 1) was written
  at 4 + k s; its analysis read line index L (k = L + 1): about L + 5 s after the clock started
  (match/scoring.py).
- UPSTREAM_STEP_WAIT_S (protocol=upstream): upstream's /step waited 80 ticks before each player's
  code and 80 after it: every run of every team pays them (a restart costs 8 s; the first code starts
  4 s in) (match/player.py, through `step_wait_s`).
- UPSTREAM_STEPS: upstream's runner gave a player at most 10 steps (program runs) an episode: the
  built-in opponents always (teams/scripted.py), the CoT baseline with protocol=upstream
  (teams/cot/team.py), and Mushroom War's upstream scoring counts a player's held mushrooms once per
  step started, at most this many times (scenarios/mushroom_war.py).
- UPSTREAM_ATTEMPTS (protocol=upstream): upstream asked the model once per step; an unusable answer
  cost the step instead of being asked again (teams/cot/team.py, teams/tacticrafter/base_agent.py).
"""

from __future__ import annotations

UPSTREAM_WAIT_S = 4.0
UPSTREAM_STEP_WAIT_S = 80 / 20
UPSTREAM_STEPS = 10
UPSTREAM_ATTEMPTS = 1


def step_wait_s(protocol: str) -> float:
    """Seconds of waiting before and after every code run under this team protocol."""
    return UPSTREAM_STEP_WAIT_S if protocol == "upstream" else 0.0
