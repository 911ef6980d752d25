"""A stand-in for tiktoken's encodings (which it downloads on first use) for the tests, offline: about
four characters a token. Only the mock model's token count uses it (inspect_ai/model/_tokens.py)."""

from __future__ import annotations


class ApproximateEncoding:
    def encode(self, text: str, **_: object) -> list[int]:
        return [0] * max(1, len(text) // 4)


def patch_tiktoken() -> None:
    try:
        import tiktoken
    except ImportError:  # no Inspect installed: nothing counts tokens
        return
    tiktoken.get_encoding = lambda name: ApproximateEncoding()  # type: ignore[assignment]
    tiktoken.encoding_for_model = lambda name: ApproximateEncoding()  # type: ignore[assignment]
