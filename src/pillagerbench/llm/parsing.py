"""Cleaning model answers: <think> blocks out, JSON out of chatty or fenced answers."""

from __future__ import annotations

import json
import re
from typing import Any

_THINK = re.compile(r"<think>.*?</think>", re.DOTALL | re.IGNORECASE)
_FENCE = re.compile(r"```(?:json|JSON)?\s*\n?(.*?)```", re.DOTALL)


def strip_think(text: str) -> str:
    """Remove reasoning blocks: closed <think>...</think> pairs; everything before a lone
    </think> (templates that open the block in the prompt); everything after an unclosed <think>
    (an answer cut while thinking)."""
    text = _THINK.sub("", text)
    low = text.lower()
    if (end := low.rfind("</think>")) >= 0:
        text, low = text[end + len("</think>") :], low[end + len("</think>") :]
    if (start := low.find("<think>")) >= 0:
        text = text[:start]
    return text.strip()


def parse_json(text: str) -> Any:
    """The JSON value in an answer: the whole text, a ```json fenced block, or the first {...} or
    [...] span. Raises ValueError (json.JSONDecodeError) when there is none."""
    text = text.strip()
    try:
        return json.loads(text)
    except ValueError as first:
        candidates = [m.group(1) for m in _FENCE.finditer(text)]
        decoder = json.JSONDecoder()
        for candidate in candidates:
            try:
                return json.loads(candidate.strip())
            except ValueError:
                pass
        for i, ch in enumerate(text):
            if ch in "{[":
                try:
                    return decoder.raw_decode(text, i)[0]
                except ValueError:
                    continue
        raise first
