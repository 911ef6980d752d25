"""A disk cache of LLM answers keyed on the whole request, so a later process can replay a run.

Key = sha256 of {provider, model, messages, parameters (temperature, max tokens, extra body,
...), sample}. Headers and the base_url are not part of it (they hold keys or change between
machines without changing the answer).

Sample index: within one cache object (one run), the n-th identical request with a temperature
above 0 (or none, i.e. the provider's default) gets sample n = 0, 1, 2, ..., so repeated
identical requests are not merged into one answer and a replay hands out the same answers in
the same order. At temperature 0 every identical request has sample 0 and shares one answer.

Modes:
  off        no lookup, no store
  read       a hit is returned; a miss calls the provider and does not store
  write      always calls the provider and stores (overwrites) the answer
  readwrite  a hit is returned; a miss calls the provider and stores
  replay     a hit is returned; a miss raises CacheMiss (no request is ever sent)

Storage: one JSON file per entry, `<dir>/<key[:2]>/<key>.json`, written atomically.
"""

from __future__ import annotations

import json
import os
import tempfile
import threading
from collections import defaultdict
from pathlib import Path
from typing import Any

from .ledger import sha256_json
from .redact import redact

MODES = ("off", "read", "write", "readwrite", "replay")


def normalize_mode(mode: Any) -> str:
    if mode is False or mode is None:  # YAML 1.1 reads a bare `off` as false
        return "off"
    mode = str(mode).lower()
    if mode not in MODES:
        raise ValueError(f"llm_cache.mode must be one of {MODES}, not {mode!r}")
    return mode


class LLMCache:
    def __init__(self, directory: str | Path | None, mode: Any = "readwrite"):
        self.mode = normalize_mode(mode)
        if self.mode != "off" and directory is None:
            raise ValueError(f"llm cache mode {self.mode!r} needs a directory")
        self.dir = Path(directory) if directory is not None else None
        if self.dir is not None and self.mode != "off":
            self.dir.mkdir(parents=True, exist_ok=True)
        self._samples: dict[str, int] = defaultdict(int)
        self._lock = threading.Lock()

    def __repr__(self) -> str:
        return f"LLMCache({str(self.dir)!r}, mode={self.mode!r})"

    @property
    def reads(self) -> bool:
        return self.mode in ("read", "readwrite", "replay")

    @property
    def writes(self) -> bool:
        return self.mode in ("write", "readwrite")

    def key(self, provider: str, request: dict) -> tuple[str, int]:
        """(cache key, sample index) for this request; advances the request's sample counter."""
        base = sha256_json({"provider": provider, "request": request})
        temperature = request.get("temperature", None)
        if temperature is not None and float(temperature) == 0.0:
            sample = 0
        else:
            with self._lock:
                sample = self._samples[base]
                self._samples[base] += 1
        return sha256_json({"request_key": base, "sample": sample}), sample

    def _path(self, key: str) -> Path:
        assert self.dir is not None
        return self.dir / key[:2] / f"{key}.json"

    def get(self, key: str) -> dict | None:
        if not self.reads:
            return None
        try:
            with open(self._path(key), encoding="utf-8") as f:
                return json.load(f)
        except FileNotFoundError:
            return None
        except ValueError:  # a damaged entry is a miss
            return None

    def put(self, key: str, entry: dict) -> None:
        if not self.writes:
            return
        path = self._path(key)
        path.parent.mkdir(parents=True, exist_ok=True)
        text = redact(json.dumps(entry, ensure_ascii=False, sort_keys=True))
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(text)
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
