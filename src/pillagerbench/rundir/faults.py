"""Whose fault a bad episode is: ours (the harness: the server died, a bot crashed, the LLM provider did
not answer, the machine lagged) or the team's own (its code's errors, its team server's, its budget
spent). An episode with a fault of ours is spoiled: it is kept on disk and listed, never scored, and a
series plays another episode in its place (rundir/schedule.py).

The rules are data. An episode that failed is ours (its error names what failed, `FAILED`), unless its
error is a team's budget spent (`BudgetExceeded`); one whose cause is not named (a team's pre-game
raising is one) is not put on the team. An episode played under lag is ours, and so is one our machine
stalled (`stalled`: the lockstep world went on without an idle bot at the server's wall-clock limit, or
a bot was restarted because it was starved of CPU or did not stop in time). A side's problem is the
team's when it holds one of `TEAM_PROBLEMS` (every call refused by the team's own budget), else ours
when it starts with one of `HARNESS_PROBLEMS`; every other is the team's.
"""

from __future__ import annotations

from dataclasses import dataclass

from pillagerbench.rundir.episode import EpisodeRecord

HARNESS = "harness"
TEAM = "team"
# a recorded problem's start -> the harness failure it is (llm/budget.py: every call of the episode failed)
# (a "provider outage" line: the provider answered no probe after the episode either, experiments/outage.py)
HARNESS_PROBLEMS: dict[str, str] = {"llm failed on all": "provider unreachable", "provider outage": "provider outage"}
# a recorded problem holding this -> the team's own, whatever its start (its budget refused every call)
TEAM_PROBLEMS: dict[str, str] = {"last: BudgetExceeded": "the team's budget spent"}
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


@dataclass(frozen=True)
class Fault:
    """One fault of an episode's record."""

    whose: str  # HARNESS | TEAM
    kind: str  # e.g. "failed: the server", "lagged", "stalled", "the team's own"
    side: str  # "red", "blue", or "" for the whole episode
    what: str  # the error, the lag's or the stall's reason, or the side's problem as recorded


def _problem(problem: str) -> tuple[str, str]:
    """(whose, kind) of one side's recorded problem."""
    own = next((kind for part, kind in TEAM_PROBLEMS.items() if part in problem), None)
    if own:
        return TEAM, own
    ours = next((kind for start, kind in HARNESS_PROBLEMS.items() if problem.startswith(start)), None)
    return (HARNESS, ours) if ours else (TEAM, "the team's own")


def faults(rec: EpisodeRecord) -> list[Fault]:
    """Every fault of an episode's record: its failure, its lag, its stall, each side's problems."""
    out = []
    if not rec.ok:  # a line may hold no more than its status (a killed run's)
        what = str(rec.error or rec.status)
        out.append(Fault(*FAILED.get(what.partition(":")[0], (HARNESS, "failed (cause not named)")), "", what))
    if rec.lagged:
        out.append(Fault(HARNESS, "lagged", "", str(rec.lag_reason)))
    if rec.stalled:
        out.append(Fault(HARNESS, "stalled", "", str(rec.stall_reason)))
    for side, problems in rec.problems.items():
        out += [Fault(*_problem(problem), side, problem) for problem in problems]
    return out


def spoiled(rec: EpisodeRecord) -> str | None:
    """The kind of our first fault in an episode's record (it is spoiled: not a result), or None."""
    return next((f.kind for f in faults(rec) if f.whose == HARNESS), None)
