"""Whose fault a bad episode is: ours (the harness: the server died, a bot crashed, the LLM provider did
not answer, the machine lagged) or the team's own (its code's errors, its team server's, its budget
spent). Harness failures are counted apart, so that no team's score carries our faults.

The rules are data. An episode that failed is ours (its error names what failed, `FAILED`), unless its
error is a team's budget spent (`BudgetExceeded`): a failed episode is never scored, and one whose cause
is not named (a team's pre-game raising is one) is not put on the team. An episode played under lag is
ours. A side's problem is ours when it starts with one of `HARNESS_PROBLEMS`; every other is the team's.
"""

from __future__ import annotations

from typing import Any

import pandas as pd

HARNESS = "harness"
TEAM = "team"
# a recorded problem's start -> the harness failure it is (llm/budget.py: every call of the episode failed)
HARNESS_PROBLEMS: dict[str, str] = {"llm failed on all": "provider unreachable"}
# a failed episode's error type -> (whose, kind); any other type: ours, "failed (cause not named)"
FAILED: dict[str, tuple[str, str]] = {
    "ArenaServerError": (HARNESS, "failed: the server"),
    "ControlError": (HARNESS, "failed: the server"),
    "ChannelClosed": (HARNESS, "failed: the server"),
    "PlayerError": (HARNESS, "failed: a bot"),
    "LLMConnectionError": (HARNESS, "provider unreachable"),
    "LLMTimeout": (HARNESS, "provider unreachable"),
    "ProviderError": (HARNESS, "provider unreachable"),
    "BudgetExceeded": (TEAM, "the team's budget spent"),
}


def faults(data: dict[str, Any]) -> list[dict[str, str]]:
    """One row per fault of an episode's record: whose (harness | team), kind, side ('' for both), what."""
    out = []
    if data.get("status", "ok") != "ok":  # a line may hold no more than its status (a killed run's)
        what = str(data.get("error") or data.get("status"))
        whose, kind = FAILED.get(what.partition(":")[0], (HARNESS, "failed (cause not named)"))
        out.append({"whose": whose, "kind": kind, "side": "", "what": what})
    if data.get("lagged"):
        out.append({"whose": HARNESS, "kind": "lagged", "side": "", "what": str(data.get("lag_reason"))})
    for side, problems in (data.get("problems") or {}).items():
        for problem in problems:
            ours = next((k for start, k in HARNESS_PROBLEMS.items() if problem.startswith(start)), None)
            whose = HARNESS if ours else TEAM
            out.append({"whose": whose, "kind": ours or "the team's own", "side": side, "what": problem})
    return out


def tally(rows: list[dict[str, Any]]) -> dict[str, Any]:
    """Episodes with a harness failure and with a team's own failure, and harness failures by kind."""
    harness = {(r["run"], r["series"], r["episode"]) for r in rows if r["whose"] == HARNESS}
    team = {(r["run"], r["series"], r["episode"]) for r in rows if r["whose"] == TEAM}
    kinds: dict[str, int] = {}
    for r in rows:
        if r["whose"] == HARNESS:
            kinds[r["kind"]] = kinds.get(r["kind"], 0) + 1
    return {"harness_episodes": len(harness), "team_episodes": len(team), "harness_by_kind": kinds}


COLUMNS = ["whose", "kind", "run", "series", "episode", "side", "what"]


def faults_table(rows: list[dict[str, Any]]) -> pd.DataFrame:
    """The report's table: ours first, then the teams' own, each in run order."""
    frame = pd.DataFrame(rows, columns=COLUMNS)
    return frame.sort_values("whose", key=lambda w: w != HARNESS, kind="stable").reset_index(drop=True)


def fault_note(rows: list[dict[str, Any]]) -> list[str]:
    """One line counting both kinds apart ([] when no episode had either)."""
    if not rows:
        return []
    t = tally(rows)
    kinds = ", ".join(f"{kind} {n}" for kind, n in t["harness_by_kind"].items()) or "none"
    return [
        f"failures: ours (the harness) in {t['harness_episodes']} episode(s) ({kinds}), counted against no team; "
        f"the teams' own (their code, their team server, their budget) in {t['team_episodes']} episode(s)"
    ]
