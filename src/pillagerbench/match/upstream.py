"""Upstream's timing quirks that `scoring=upstream` and `protocol=upstream` reproduce, in one place
(docs/faithful.md says what each changes; docs/fidelity.md has the evidence).

- UPSTREAM_WAIT_S: upstream's judge started its code after an 80-tick wait (4 s) and wrote a rewards
  line each 1 s after that (the first one 1 s in), so line k (from 1) was written at 4 + k s; its
  analysis read line index L (k = L + 1): about L + 5 s after the clock started (scoring=upstream).
- UPSTREAM_STEP_WAIT_S: upstream's /step waited 80 ticks before each player's code and 80 after it:
  with protocol=upstream every run of every team pays them (a restart costs 8 s; the first code
  starts 4 s in).
"""

from __future__ import annotations

UPSTREAM_WAIT_S = 4.0
UPSTREAM_STEP_WAIT_S = 80 / 20


def step_wait_s(protocol: str) -> float:
    """Seconds of waiting before and after every code run under this team protocol."""
    return UPSTREAM_STEP_WAIT_S if protocol == "upstream" else 0.0
