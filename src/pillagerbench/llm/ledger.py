"""The LLM call ledger: one JSON line per call in a run's `llm_calls.jsonl`, failed calls included.

Fields of a record: ts (UTC, ISO 8601), team, role, provider, model, latency_s (this call,
retries and waits included), input_tokens, output_tokens, retries, finish_reason, cache_hit,
cache_key, sample, cost_usd (null when unknown: no price for the model, or no usage reported; 0 for
a failed call), price (input_per_1m, output_per_1m and source: where the price came from, see
prices.py), error_type and error (null on success), and either request and
response in full (content="full") or request_sha256 and response_sha256 (content="hash").
A cache hit also carries orig_latency_s, the latency of the call that produced the answer.

`read_ledger` yields records back; `summarize` computes the metrics later code reports:
T_resp (mean latency), N_out (mean output tokens) and R_tps (output tokens / latency, summed).
"""

from __future__ import annotations

import hashlib
import json
import threading
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

from pillagerbench.rundir import LEDGER

from .redact import redact

LEDGER_NAME = LEDGER
CONTENT_MODES = ("full", "hash")


def sha256_json(value: Any) -> str:
    return hashlib.sha256(json.dumps(value, sort_keys=True, ensure_ascii=False).encode()).hexdigest()


class Ledger:
    """Appends records to a JSONL file (a directory means `<dir>/llm_calls.jsonl`)."""

    def __init__(self, path: str | Path, content: str = "hash"):
        if content not in CONTENT_MODES:
            raise ValueError(f"ledger content must be one of {CONTENT_MODES}, not {content!r}")
        path = Path(path)
        self.path = path / LEDGER_NAME if path.is_dir() or not path.suffix else path
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.content = content
        self._lock = threading.Lock()
        self._file = open(self.path, "a", encoding="utf-8")

    def __repr__(self) -> str:
        return f"Ledger({str(self.path)!r}, content={self.content!r})"

    def record(self, *, request: Any, response: Any, **fields: Any) -> dict:
        """Write one record; request/response are stored in full or hashed as configured."""
        rec: dict[str, Any] = {"ts": datetime.now(timezone.utc).isoformat(timespec="milliseconds")}
        rec.update(fields)
        if self.content == "full":
            rec["request"], rec["response"] = request, response
        else:
            rec["request_sha256"] = sha256_json(request)
            rec["response_sha256"] = None if response is None else sha256_json(response)
        line = redact(json.dumps(rec, ensure_ascii=False, default=str))
        with self._lock:
            self._file.write(line + "\n")
            self._file.flush()
        return rec

    def close(self) -> None:
        with self._lock:
            if not self._file.closed:
                self._file.close()


def read_ledger(path: str | Path) -> Iterator[dict]:
    """Yield the records of a ledger file (or of `<dir>/llm_calls.jsonl`); skips a torn last line."""
    path = Path(path)
    if path.is_dir():
        path = path / LEDGER_NAME
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            try:
                yield json.loads(line)
            except ValueError:  # a line cut by a crash
                continue


@dataclass(frozen=True)
class LedgerStats:
    calls: int  # all records
    ok: int  # calls that returned an answer (cache hits included)
    errors: int
    cache_hits: int
    retries: int
    input_tokens: int
    output_tokens: int
    cost_usd: float  # of the calls whose cost is known (see `unpriced`)
    t_resp: float | None  # mean latency (s) of successful calls
    n_out: float | None  # mean output tokens of successful calls
    r_tps: float | None  # sum output tokens / sum latency (tokens per second)
    unpriced: int = 0  # calls whose cost is unknown (cost_usd null): cost_usd is then a lower bound

    def cost_text(self) -> str:
        """The cost as it is known: "$0.0123", "≥ $0.0123 (4 calls unpriced)" or "unknown (4 calls unpriced)"."""
        from .prices import format_cost

        return format_cost(self.cost_usd, self.unpriced)


def summarize(
    records: Iterable[dict], *, team: str | None = None, role: str | None = None, original_latency: bool = True
) -> LedgerStats:
    """Metrics over successful calls (optionally of one team and/or role).

    With original_latency (the default), a cache hit counts with the latency of the call that
    produced its answer, so a replayed run reports the same T_resp and R_tps as the original.
    Calls with unknown usage count as 0 tokens.
    """
    calls = ok = errors = hits = retries = tin = tout = unpriced = 0
    cost = latency = ok_out = 0.0
    for r in records:
        if (team is not None and r.get("team") != team) or (role is not None and r.get("role") != role):
            continue
        calls += 1
        retries += int(r.get("retries") or 0)
        if "cost_usd" in r and r["cost_usd"] is None:
            unpriced += 1
        else:
            cost += float(r.get("cost_usd") or 0.0)
        if r.get("error_type"):
            errors += 1
            continue
        ok += 1
        hits += bool(r.get("cache_hit"))
        n_in, n_out = int(r.get("input_tokens") or 0), int(r.get("output_tokens") or 0)
        tin, tout, ok_out = tin + n_in, tout + n_out, ok_out + n_out
        lat = r.get("orig_latency_s") if original_latency and r.get("cache_hit") else r.get("latency_s")
        latency += float(lat or 0.0)
    return LedgerStats(
        calls=calls,
        ok=ok,
        errors=errors,
        cache_hits=hits,
        retries=retries,
        input_tokens=tin,
        output_tokens=tout,
        cost_usd=cost,
        t_resp=latency / ok if ok else None,
        n_out=ok_out / ok if ok else None,
        r_tps=tout / latency if latency > 0 else None,
        unpriced=unpriced,
    )
