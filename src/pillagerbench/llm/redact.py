"""Keep API keys out of every text we write: ledger lines, cache files, error messages.

Clients register the key they read from the environment; `redact` replaces every registered
key in a text. The registry is per process, so any module can redact its own output too.
"""

from __future__ import annotations

import threading

MASK = "***"
_MIN_LEN = 6  # shorter values are placeholders, not secrets; replacing them would garble text
_secrets: set[str] = set()
_lock = threading.Lock()


def register_secret(value: str | None) -> None:
    if value and len(value) >= _MIN_LEN:
        with _lock:
            _secrets.add(value)


def redact(text: str) -> str:
    for secret in _secrets:
        if secret in text:
            text = text.replace(secret, MASK)
    return text
