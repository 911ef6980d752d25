"""The LLM layer: one client for every team (see docs/llm.md).

from pillagerbench.llm import LLMClient, LLMError, BudgetExceeded
"""

from .budget import Budget
from .cache import LLMCache
from .client import LLMClient, LLMResponse
from .errors import (
    AuthenticationFailed,
    BadRequest,
    BudgetExceeded,
    CacheMiss,
    EmptyResponse,
    InvalidJSON,
    LLMConfigError,
    LLMConnectionError,
    LLMError,
    LLMTimeout,
    MalformedResponse,
    ModelNotFound,
    ProviderError,
    RateLimited,
)
from .ledger import Ledger, LedgerStats, read_ledger, summarize
from .settings import LLMSettings

__all__ = [
    "AuthenticationFailed",
    "BadRequest",
    "Budget",
    "BudgetExceeded",
    "CacheMiss",
    "EmptyResponse",
    "InvalidJSON",
    "LLMCache",
    "LLMClient",
    "LLMConfigError",
    "LLMConnectionError",
    "LLMError",
    "LLMResponse",
    "LLMSettings",
    "LLMTimeout",
    "Ledger",
    "LedgerStats",
    "MalformedResponse",
    "ModelNotFound",
    "ProviderError",
    "RateLimited",
    "read_ledger",
    "summarize",
]
