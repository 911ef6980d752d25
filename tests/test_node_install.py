"""The lighter install: the live view's package (prismarine-viewer) is the lock's one optional
dependency, left out of the base install and added on the first use of watch=. What the server and
the bots require must never be one of the packages only the viewer brings (but a person's view, made
only for a person's bot and only when the viewer is there: js/bot/view.js)."""

from __future__ import annotations

import json
import re

from pillagerbench.cli.commands import main as cli_main
from pillagerbench.host.node import JS_DIR, _npm

REQUIRE = re.compile(r"require\('([^'./][^']*)'\)")


def optional_packages() -> set[str]:
    packages = json.loads((JS_DIR / "package-lock.json").read_text())["packages"]
    return {path.rsplit("node_modules/", 1)[1] for path, p in packages.items() if path and p.get("optional")}


def test_the_viewer_is_the_one_optional_dependency_and_only_the_live_view_requires_its_packages():
    package = json.loads((JS_DIR / "package.json").read_text())
    assert list(package["optionalDependencies"]) == ["prismarine-viewer"]
    optional = optional_packages()
    assert {"prismarine-viewer", "express", "socket.io", "three"} <= optional
    assert not optional & set(package["dependencies"])
    # a person's first-person view needs the viewer too: a bot makes it only when it plays a person
    # (settings.view), and says why there is none when the viewer is not installed (docs/people.md)
    assert "if (settings.view) view.load(bot)" in (JS_DIR / "bot" / "main.js").read_text()
    assert "MODULE_NOT_FOUND" in (JS_DIR / "bot" / "view.js").read_text()
    for path in JS_DIR.rglob("*.js"):
        if "node_modules" in path.parts or path.parent.name == "watch" or path == JS_DIR / "bot" / "view.js":
            continue
        wrong = optional & set(REQUIRE.findall(path.read_text()))
        assert not wrong, f"{path.relative_to(JS_DIR)} requires {wrong}, which the base install leaves out"


def test_setup_refuses_an_unknown_argument_in_one_line(capsys):
    assert cli_main(["setup", "--viewer"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [
        "pillagerbench setup: unknown argument '--viewer'; setup takes only --watch (the live view's packages too)"
    ]


def test_npm_and_the_scripts_it_runs_get_no_key(tmp_path, monkeypatch):
    """npm runs the packages' install scripts: they see the allow-listed environment, not the user's
    keys (docs/security.md, layer 6). A real npm runs a package script that writes its environment."""
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test-secret-npm")
    monkeypatch.setenv("TZ", "UTC")
    script = "node -e \"require('fs').writeFileSync('env.json', JSON.stringify(process.env))\""
    (tmp_path / "package.json").write_text(
        json.dumps({"name": "probe", "version": "1.0.0", "scripts": {"probe": script}})
    )
    _npm(tmp_path, (".probed", ("run", "probe"), "a probe"), quiet=True)
    env = json.loads((tmp_path / "env.json").read_text())
    assert env.get("TZ") == "UTC" and "PATH" in env  # the script ran with what npm passed on
    assert "OPENAI_API_KEY" not in env and "sk-test-secret-npm" not in json.dumps(env)
