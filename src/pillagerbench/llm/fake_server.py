"""A scripted OpenAI-compatible server on 127.0.0.1 for tests and benchmarks (never the network).

    with FakeLLMServer(default_reply="ok") as server:
        server.add(Rule(role="critic", reply='{"success": true}'))
        server.add(Rule(match="attack", status=429, retry_after=0.1, times=1))
        ... point a client at server.url ...
        assert server.count == 2 and server.requests[0].role == "critic"

Routes: POST /v1/chat/completions, GET /v1/models.
Matching: the first rule whose conditions all hold and whose `times` is not used up answers.
Conditions: `role` equals the `X-PillagerBench-Role` header that our client sends with every
request; `match` is a substring, `regex` a regular expression searched in the prompt (all
message contents joined by newlines); `model` equals the requested model. No rule matching means
the default reply. Faults a rule can inject: any `status` (429 sends `retry-after` and
`retry-after-ms`), `delay` seconds of sleep before answering (longer than the client timeout =
a timeout), `malformed` (200 with a body that is not JSON), `empty` (an empty answer),
`finish_reason`. Answers longer than the request's max_tokens are cut and get
finish_reason="length", as a real server does. `usage` counts about 4 characters per token.

Tool calls (function calling): `Rule(tool_calls=[{"name": "mineBlock", "arguments": {"name": "oak_log"}}])`
answers one assistant message with those calls (ids generated unless a call gives "id"; `arguments`
a JSON value, or a string sent as it is, e.g. malformed JSON), content null unless `reply` is given,
finish_reason "tool_calls"; `tool_calls` may also be a function of the request body. A sequence
across calls is rules with `times`: `Rule(tool_calls=[...], times=1)` then `Rule(reply="done")`.
The request's `tools` (and its messages, tool results included) are in `server.requests[i].tools`
(`.messages`, `.body`).

Auth: with `api_key` set, a request without `Authorization: Bearer <api_key>` gets a 401 whose
message quotes the key it received, like some providers do (so tests can check redaction).
Models: with `models` set, any other model gets a 404.

Run standalone (for benchmarks or manual tries): python -m pillagerbench.llm.fake_server --port 0
"""

from __future__ import annotations

import argparse
import json
import re
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

from pillagerbench.llm.headers import ROLE_HEADER, TEAM_HEADER
from pillagerbench.llm.tokens import count_tokens


@dataclass
class Rule:
    reply: str | Callable[[dict], str] | None = None  # None = the server's default reply
    role: str | None = None
    match: str | None = None
    regex: str | None = None
    model: str | None = None
    status: int | None = None  # inject an HTTP error
    message: str | None = None  # error message for `status`
    retry_after: float | None = None  # seconds, sent with a 429
    delay: float = 0.0
    malformed: bool = False
    empty: bool = False
    finish_reason: str | None = None
    tool_calls: list[dict] | Callable[[dict], list[dict]] | None = None  # answer with these calls (see above)
    times: int | None = None  # how many requests this rule answers; None = unlimited
    used: int = 0

    def matches(self, req: Received) -> bool:
        if self.times is not None and self.used >= self.times:
            return False
        if self.role is not None and req.role != self.role:
            return False
        if self.model is not None and req.body.get("model") != self.model:
            return False
        if self.match is not None and self.match not in req.prompt:
            return False
        return self.regex is None or re.search(self.regex, req.prompt) is not None


@dataclass
class Received:
    """One request as the server saw it (for assertions)."""

    path: str
    headers: dict[str, str]
    body: dict[str, Any]
    raw: bytes = b""

    @property
    def role(self) -> str | None:
        return self.headers.get(ROLE_HEADER.lower())

    @property
    def team(self) -> str | None:
        return self.headers.get(TEAM_HEADER.lower())

    @property
    def messages(self) -> list[dict]:
        return list(self.body.get("messages") or [])

    @property
    def tools(self) -> list[dict]:
        """The tools the request offered (OpenAI shape), none: []."""
        return list(self.body.get("tools") or [])

    @property
    def prompt(self) -> str:
        return "\n".join(str(m.get("content") or "") for m in self.messages)


@dataclass
class FakeLLMServer:
    default_reply: str = "OK"
    api_key: str | None = None
    models: list[str] | None = None
    rules: list[Rule] = field(default_factory=list)
    requests: list[Received] = field(default_factory=list)
    host: str = "127.0.0.1"
    port: int = 0

    def __post_init__(self) -> None:
        self._lock = threading.Lock()
        self._httpd: ThreadingHTTPServer | None = None
        self._thread: threading.Thread | None = None
        self._next_id = 0

    # -- lifecycle -------------------------------------------------------------------------------
    def start(self) -> FakeLLMServer:
        server = self

        class Handler(_Handler):
            fake = server

        self._httpd = ThreadingHTTPServer((self.host, self.port), Handler)
        self._httpd.daemon_threads = True
        self.port = self._httpd.server_address[1]
        self._thread = threading.Thread(
            target=self._httpd.serve_forever, kwargs={"poll_interval": 0.05}, name="fake-llm-server", daemon=True
        )
        self._thread.start()
        return self

    def stop(self) -> None:
        if self._httpd is not None:
            self._httpd.shutdown()
            self._httpd.server_close()
            self._httpd = None

    def __enter__(self) -> FakeLLMServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    @property
    def url(self) -> str:
        """The base_url for clients, ending in /v1."""
        return f"http://{self.host}:{self.port}/v1"

    # -- script ----------------------------------------------------------------------------------
    def add(self, *rules: Rule) -> FakeLLMServer:
        with self._lock:
            self.rules.extend(rules)
        return self

    def reset(self) -> None:
        with self._lock:
            self.rules.clear()
            self.requests.clear()

    @property
    def count(self) -> int:
        """Number of chat completion requests received."""
        return sum(1 for r in self.requests if r.path.endswith("/chat/completions"))

    def _pick(self, req: Received) -> Rule | None:
        with self._lock:
            self.requests.append(req)
            self._next_id += 1
            for rule in self.rules:
                if rule.matches(req):
                    rule.used += 1
                    return rule
        return None

    # -- answers ---------------------------------------------------------------------------------
    def completion(self, req: Received, rule: Rule | None) -> dict:
        rule = rule or Rule()
        scripted = rule.tool_calls(req.body) if callable(rule.tool_calls) else rule.tool_calls
        calls = _wire_calls(scripted or [], self._next_id)
        reply = rule.reply if rule.reply is not None else ("" if calls else self.default_reply)
        text = "" if rule.empty else (reply(req.body) if callable(reply) else str(reply))
        finish = rule.finish_reason or ("tool_calls" if calls else "stop")
        limit = req.body.get("max_tokens") or req.body.get("max_completion_tokens")
        if limit and count_tokens(text) > int(limit):
            text, finish = text[: int(limit) * 4], "length"
        message: dict[str, Any] = {"role": "assistant", "content": text if text or not calls else None}
        if calls:
            message["tool_calls"] = calls
        prompt_tokens = sum(count_tokens(str(m.get("content") or "")) + 4 for m in req.messages)
        prompt_tokens += count_tokens(json.dumps(req.tools)) if req.tools else 0
        completion_tokens = count_tokens(text) + sum(count_tokens(json.dumps(c["function"])) for c in calls)
        return {
            "id": f"chatcmpl-fake-{self._next_id}",
            "object": "chat.completion",
            "created": int(time.time()),
            "model": req.body.get("model", "fake"),
            "choices": [{"index": 0, "finish_reason": finish, "message": message}],
            "usage": {
                "prompt_tokens": prompt_tokens,
                "completion_tokens": completion_tokens,
                "total_tokens": prompt_tokens + completion_tokens,
            },
        }


def _wire_calls(calls: list[dict], request_id: int) -> list[dict]:
    """Scripted calls ({"name", "arguments": a JSON value or the raw string to send, "id"?}) in the wire shape."""
    wire = []
    for i, call in enumerate(calls):
        arguments = call.get("arguments", {})
        raw = arguments if isinstance(arguments, str) else json.dumps(arguments)
        call_id = call.get("id") or f"call_fake_{request_id}_{i}"
        wire.append({"id": call_id, "type": "function", "function": {"name": call["name"], "arguments": raw}})
    return wire


def _error(status: int, message: str, kind: str) -> dict:
    return {"error": {"message": message, "type": kind, "code": status}}


class _Handler(BaseHTTPRequestHandler):
    fake: FakeLLMServer
    protocol_version = "HTTP/1.1"  # keep-alive, like real providers
    disable_nagle_algorithm = True  # headers and body are separate writes: no 40 ms delayed-ACK stall

    def log_message(self, *args: object) -> None:  # quiet
        pass

    def _send(self, status: int, payload: bytes, headers: dict[str, str] | None = None) -> None:
        try:
            self.send_response(status)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(payload)))
            for k, v in (headers or {}).items():
                self.send_header(k, v)
            self.end_headers()
            self.wfile.write(payload)
        except (BrokenPipeError, ConnectionResetError):  # the client gave up (timeout)
            self.close_connection = True

    def _auth_failure(self) -> bytes | None:
        key = self.fake.api_key
        got = self.headers.get("Authorization", "")
        if key is None or got == f"Bearer {key}":
            return None
        received = got.removeprefix("Bearer ")
        return json.dumps(_error(401, f"Incorrect API key provided: {received}", "invalid_request_error")).encode()

    def do_GET(self) -> None:
        if self.path.rstrip("/").endswith("/models"):
            names = self.fake.models or ["fake-model"]
            data = [{"id": n, "object": "model", "owned_by": "fake"} for n in names]
            self._send(200, json.dumps({"object": "list", "data": data}).encode())
        else:
            self._send(404, json.dumps(_error(404, f"no route {self.path}", "not_found")).encode())

    def do_POST(self) -> None:
        raw = self.rfile.read(int(self.headers.get("Content-Length") or 0))
        try:
            body = json.loads(raw or b"{}")
        except ValueError:
            body = {}
        req = Received(self.path, {k.lower(): v for k, v in self.headers.items()}, body, raw)
        if not self.path.rstrip("/").endswith("/chat/completions"):
            with self.fake._lock:
                self.fake.requests.append(req)
            self._send(404, json.dumps(_error(404, f"no route {self.path}", "not_found")).encode())
            return
        rule = self.fake._pick(req)
        if rule is not None and rule.delay:
            time.sleep(rule.delay)
        if (failure := self._auth_failure()) is not None:
            self._send(401, failure)
        elif self.fake.models is not None and body.get("model") not in self.fake.models:
            msg = f"The model `{body.get('model')}` does not exist"
            self._send(404, json.dumps(_error(404, msg, "invalid_request_error")).encode())
        elif rule is not None and rule.status is not None:
            headers = {}
            if rule.retry_after is not None:
                headers = {
                    "retry-after": str(max(1, round(rule.retry_after))),
                    "retry-after-ms": str(int(rule.retry_after * 1000)),
                }
            msg = rule.message or f"injected error {rule.status}"
            self._send(rule.status, json.dumps(_error(rule.status, msg, "fake_error")).encode(), headers)
        elif rule is not None and rule.malformed:
            self._send(200, b"<html>this is not a chat completion")
        else:
            self._send(200, json.dumps(self.fake.completion(req, rule)).encode())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--port", type=int, default=0)
    parser.add_argument("--reply", default="OK", help="default answer")
    args = parser.parse_args(argv)
    server = FakeLLMServer(default_reply=args.reply, port=args.port).start()
    print(server.url, flush=True)
    try:
        threading.Event().wait()
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
