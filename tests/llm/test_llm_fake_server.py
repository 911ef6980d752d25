"""The fake server itself, over plain HTTP (what other teams' tests rely on)."""

import json
import urllib.error
import urllib.request

from pillagerbench.llm.fake_server import FakeLLMServer, Rule


def post(url, body, headers=None):
    req = urllib.request.Request(
        url + "/chat/completions", json.dumps(body).encode(), {"Content-Type": "application/json", **(headers or {})}
    )
    try:
        with urllib.request.urlopen(req, timeout=5) as resp:
            return resp.status, dict(resp.headers), resp.read()
    except urllib.error.HTTPError as exc:
        return exc.code, dict(exc.headers), exc.read()


def test_models_and_completion_shape():
    with FakeLLMServer(default_reply="hello") as server:
        with urllib.request.urlopen(server.url + "/models", timeout=5) as resp:
            assert json.load(resp)["data"][0]["id"] == "fake-model"
        status, _, raw = post(server.url, {"model": "m", "messages": [{"role": "user", "content": "hi"}]})
        data = json.loads(raw)
        assert status == 200 and data["choices"][0]["message"]["content"] == "hello"
        assert data["usage"]["total_tokens"] == data["usage"]["prompt_tokens"] + data["usage"]["completion_tokens"]
        assert server.count == 1 and server.requests[0].prompt == "hi"


def test_rule_times_and_429_headers():
    with FakeLLMServer() as server:
        server.add(Rule(status=429, retry_after=0.25, times=1, role="action"))
        body = {"model": "m", "messages": [{"role": "user", "content": "x"}]}
        status, headers, _ = post(server.url, body, {"X-PillagerBench-Role": "action"})
        assert status == 429 and headers["retry-after-ms"] == "250"
        assert post(server.url, body, {"X-PillagerBench-Role": "action"})[0] == 200  # used up
        assert server.rules[0].used == 1


def test_unknown_route_is_404():
    with FakeLLMServer() as server:
        req = urllib.request.Request(server.url + "/embeddings", b"{}", {"Content-Type": "application/json"})
        try:
            urllib.request.urlopen(req, timeout=5)
            raise AssertionError("expected 404")
        except urllib.error.HTTPError as exc:
            assert exc.code == 404
        assert server.count == 0
