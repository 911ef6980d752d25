"""`pillagerbench llm-ping` against the fake server (through the real CLI dispatch)."""

from pillagerbench.cli.commands import main as cli_main
from pillagerbench.llm.fake_server import FakeLLMServer, Rule


def test_ping_prints_answer(fake_llm, capsys):
    fake_llm.default_reply = "pong"
    code = cli_main(["llm-ping", "llm=openai_compatible", f"llm.base_url={fake_llm.url}", "llm.model=tiny"])
    out = capsys.readouterr().out
    assert code == 0
    assert "answer: 'pong'" in out and "latency:" in out and "tokens: input" in out
    assert fake_llm.requests[0].body["model"] == "tiny" and fake_llm.requests[0].role == "ping"


def test_ping_401_exits_nonzero_with_message(monkeypatch, capsys):
    monkeypatch.setenv("PB_PING_KEY", "sk-ping-wrong-123456")
    with FakeLLMServer(api_key="sk-ping-right-654321") as server:
        code = cli_main(["llm-ping", "llm=fake", f"llm.base_url={server.url}", "llm.api_key_env=PB_PING_KEY"])
    err = capsys.readouterr().err
    assert code == 1
    assert "AuthenticationFailed" in err and "HTTP 401" in err and server.url in err
    assert "sk-ping-wrong-123456" not in err


def test_ping_provider_error_and_refused(fake_llm, closed_port, capsys):
    fake_llm.add(Rule(status=500, message="boom"))
    assert cli_main(["llm-ping", "llm=fake", f"llm.base_url={fake_llm.url}"]) == 1
    assert "boom" in capsys.readouterr().err
    assert (
        cli_main(["llm-ping", "llm=fake", f"llm.base_url=http://127.0.0.1:{closed_port}/v1", "llm.max_retries=0"]) == 1
    )
    assert "LLMConnectionError" in capsys.readouterr().err


def test_ping_missing_key_variable_is_a_user_error(monkeypatch, capsys):
    """The user's settings, not the provider: exit 2 and the prefix of every command's user errors
    (exit 1 stays for what the check is for: a provider that cannot be reached, refuses or fails)."""
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    assert cli_main(["llm-ping", "llm=openai"]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("pillagerbench llm-ping: openai: ") and "OPENAI_API_KEY is not set" in line


def test_ping_bad_preset_is_config_error(capsys):
    assert cli_main(["llm-ping", "llm=nosuch"]) == 2
