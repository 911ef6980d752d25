"""A rough token count, about 4 characters a token: the fake provider's usage figures and the plan's
estimates of prompt and answer sizes use the same rule."""

from __future__ import annotations


def count_tokens(text: str) -> int:
    """Rough token count (about 4 characters per token), at least 1 for a non-empty text."""
    return (len(text) + 3) // 4
