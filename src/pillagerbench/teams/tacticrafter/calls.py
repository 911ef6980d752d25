"""What TactiCrafter's LLM calls took, per role: the totals written to tacticrafter.json (calls,
failed calls, unusable answers, tokens, latency) and the recent latencies from which a base agent
judges whether a call still fits before the whistle (they carry over from episode to episode)."""

from __future__ import annotations

from typing import Any

from pillagerbench.agents.asking import Asked

RECENT = 5  # calls a role's expected latency is the mean of


class CallStats:
    def __init__(self) -> None:
        self.latency: dict[str, list[float]] = {}

    def expected_latency(self, role: str) -> float:
        """The mean latency of the role's last RECENT answered calls (0 before its first)."""
        seen = self.latency.get(role) or []
        return sum(seen[-RECENT:]) / len(seen[-RECENT:]) if seen else 0.0

    def add(self, totals: dict[str, Any], role: str, asked: Asked) -> None:
        """Count the calls of one `ask` into `totals` (the record's `llm` part) and the role's latencies."""
        for a in asked.attempts:
            if "answer" in a and a.get("latency_s") is not None:
                self.latency.setdefault(role, []).append(float(a["latency_s"]))
        stats = totals.setdefault(
            role,
            {"calls": 0, "failed_calls": 0, "unusable": 0, "input_tokens": 0, "output_tokens": 0, "latency_s": 0.0},
        )
        for a in asked.attempts:
            stats["calls"] += 1
            if "error" in a:
                stats["failed_calls"] += 1
            if "problem" in a:
                stats["unusable"] += 1
            stats["input_tokens"] += a.get("input_tokens") or 0
            stats["output_tokens"] += a.get("output_tokens") or 0
            stats["latency_s"] = round(stats["latency_s"] + (a.get("latency_s") or 0.0), 3)
