"""Inspect's mock model counts the tokens of its default answers with tiktoken's o200k_base, which
tiktoken downloads on first use; the tests have no network. Put this directory on PYTHONPATH (the
subprocess tests do) and tiktoken's encodings count about four characters a token instead. Only the
mock model's token count is faked; no code of ours is."""

from tests.inspect_tasks.offline_tokens import patch_tiktoken

patch_tiktoken()
