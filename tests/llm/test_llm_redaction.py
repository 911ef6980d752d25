"""The API key never appears in ledger lines, cache files, error texts or reprs."""

import pytest

from pillagerbench.llm import AuthenticationFailed, LLMClient
from pillagerbench.llm.fake_server import FakeLLMServer

KEY = "sk-test-SECRET-4f2a9c71e0"


def all_text(root) -> str:
    return "".join(p.read_text(errors="replace") for p in root.rglob("*") if p.is_file())


async def test_key_never_written(monkeypatch, make_client, tmp_path):
    monkeypatch.setenv("PB_REDACT_KEY", KEY)
    with FakeLLMServer(api_key=KEY, default_reply="fine") as server:
        client = make_client(
            "llm.api_key_env=PB_REDACT_KEY",
            "llm_ledger.content=full",
            "llm_cache.mode=readwrite",
            f"llm_cache.dir={tmp_path / 'cache'}",
            url=server.url,
        )
        # A prompt that quotes the key by mistake must not leak it either.
        answer = await client.complete(f"my key is {KEY}", role="action")
        assert answer.text == "fine"
        assert server.requests[0].headers["authorization"] == f"Bearer {KEY}"  # it was sent
        assert KEY not in repr(client) and KEY not in repr(client.settings)
    text = all_text(tmp_path)
    assert "my key is ***" in text
    assert KEY not in text


async def test_key_not_in_401_error(monkeypatch, make_client, tmp_path):
    monkeypatch.setenv("PB_REDACT_KEY", KEY)
    with FakeLLMServer(api_key="sk-the-other-key-000") as server:  # echoes the key it got
        client = make_client("llm.api_key_env=PB_REDACT_KEY", "llm_ledger.content=full", url=server.url)
        with pytest.raises(AuthenticationFailed) as info:
            await client.complete("hi", role="action")
    assert "Incorrect API key provided: ***" in str(info.value)
    assert KEY not in str(info.value) and info.value.__cause__ is None
    assert KEY not in all_text(tmp_path)


async def test_local_servers_never_get_openai_key(monkeypatch, make_client, fake_llm):
    monkeypatch.setenv("OPENAI_API_KEY", KEY)
    client = make_client()  # fake preset: api_key_env null
    await client.complete("hi", role="action")
    assert KEY not in fake_llm.requests[0].headers.get("authorization", "")
    assert isinstance(client, LLMClient)
