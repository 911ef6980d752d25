"""What a run cost: each entrant's LLM calls, tokens and dollars, from the ledgers of its series
(`pillagerbench run` prints it at the end of a match and of an experiment)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path

from .ledger import LedgerStats, read_ledger, summarize


def spend(sources: Iterable[tuple[Path, Mapping[str, str]]]) -> dict[str, LedgerStats]:
    """Entrant label -> its calls' stats, over (ledger file, {side: entrant label}) pairs; a label
    without a model (`@`) gets the calls' model; a ledger that does not exist (no LLM team) adds nothing."""
    calls: dict[str, list[dict]] = {}
    for path, names in sources:
        if not path.exists():
            continue
        for call in read_ledger(path):
            side = str(call.get("team"))
            if side in names:
                label = names[side] if "@" in names[side] else f"{names[side]}@{call.get('model') or '?'}"
                calls.setdefault(label, []).append(call)
    return {label: summarize(found) for label, found in calls.items()}


def spend_lines(sources: Iterable[tuple[Path, Mapping[str, str]]]) -> list[str]:
    """One line per entrant: calls (failed), tokens in and out, and the cost or what is unpriced."""
    return [
        f"LLM cost of {label}: {s.calls} call(s) ({s.errors} failed), {s.input_tokens:,} tokens in, "
        f"{s.output_tokens:,} out, {s.cost_text()}"
        for label, s in spend(sources).items()
    ]
