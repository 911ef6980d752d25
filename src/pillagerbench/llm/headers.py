"""Headers our client adds to every request, so servers (the fake one, proxies, logs) can tell
which team and which role (action, critic, tactics, ...) a request comes from."""

ROLE_HEADER = "X-PillagerBench-Role"
TEAM_HEADER = "X-PillagerBench-Team"
