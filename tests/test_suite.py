"""The suite version (pillagerbench/suite/version.py): the files that can move a score hash to the newest
recorded version, or this suite fails with one line saying what to do; a change to one built-in
opponent's script (on a copy of the package's score files) moves the hash, a file that moves no score
does not; re-recording is one command; `pillagerbench suite` prints it."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.suite import version as suite


def test_the_files_that_can_move_a_score_hash_to_the_recorded_suite_version():
    problem = suite.check()
    if problem:  # one line: what changed and what to do
        pytest.fail(problem, pytrace=False)


@pytest.fixture
def copy(tmp_path: Path) -> tuple[Path, Path]:
    """The package's score files (and one file that moves no score) copied, with a versions file
    recording their hash as 'suite 1.0'."""
    root = tmp_path / "pillagerbench"
    conf = [
        suite.PACKAGE / "conf" / "config.yaml",
        *sorted((suite.PACKAGE / "conf" / "scenario").glob("*.yaml")),
        *sorted((suite.PACKAGE / "conf" / "clock").glob("*.yaml")),
    ]
    for path in suite.score_files() + [suite.PACKAGE / "teams" / "cot" / "team.py", *conf]:
        target = root / path.relative_to(suite.PACKAGE)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(path, target)
    versions = tmp_path / "suite_versions.json"
    versions.write_text(json.dumps({"versions": [{"name": "suite 1.0", "sha256": suite.suite_hash(root)}]}))
    return root, versions


def test_changing_one_opponents_script_without_a_new_version_fails_the_check(copy):
    root, versions = copy
    assert suite.check(root, versions) is None
    script = sorted((root / "teams" / "scripts" / "mushroom_war").glob("*"))[0]
    script.write_text(script.read_text() + "\n// one more line\n")
    problem = suite.check(root, versions)
    assert problem is not None and "\n" not in problem
    assert problem.startswith("files that can move scores changed without a new suite version (suite 1.0 recorded")
    assert "scores may move" in problem and "docs/suite-versions.md" in problem and "--record" in problem
    assert suite.record("suite 1.1", versions, root).startswith("recorded suite 1.1@")
    assert suite.check(root, versions) is None and list(suite.recorded(versions)) == ["suite 1.0", "suite 1.1"]


def test_a_new_layout_file_under_scenarios_moves_the_hash_and_a_team_that_is_not_an_opponent_does_not(copy):
    root, versions = copy
    (root / "teams" / "cot" / "team.py").write_text("# moves no built-in opponent's score\n")
    assert suite.check(root, versions) is None
    (root / "scenarios" / "layouts").mkdir(exist_ok=True)
    (root / "scenarios" / "layouts" / "new.yaml").write_text("seed: 7\n")
    assert suite.check(root, versions) is not None


def test_the_suite_is_named_by_its_recorded_hash_else_the_newest_name_plus_dev():
    versions = {"suite 1.0": "a" * 64, "suite 1.1": "b" * 64}
    assert suite.name_of("a" * 64, versions) == "suite 1.0"
    assert suite.name_of("c" * 64, versions) == "suite 1.1+dev"
    assert suite.label("suite 1.0", "a" * 64) == "suite 1.0@" + "a" * 16


def test_the_command_prints_the_name_and_hash(capsys):
    assert cli.main(["suite", "--hash"]) == 0
    assert capsys.readouterr().out.strip() == suite.suite_hash()
    assert cli.main(["suite"]) == 0
    assert capsys.readouterr().out.startswith(f"{suite.current()['name']} sha256:{suite.suite_hash()}")


def test_docs_suite_versions_has_a_section_per_version_and_the_shipped_reference_figures():
    from pillagerbench.suite.figures import reference_figures

    doc = (Path(__file__).resolve().parents[1] / "docs" / "suite-versions.md").read_text(encoding="utf-8")
    for name in suite.recorded():
        assert f"\n### {name} (" in doc, f"docs/suite-versions.md has no section for {name}"
    figures = reference_figures()
    section = doc.split(f"\n### {figures.suite} (")[1].split("\n### ")[0]
    titles = {"mushroom_war": "Mushroom War", "dash_and_dine": "Dash & Dine"}
    for scenario, teams in figures.scenarios.items():
        for team, by in teams.items():
            row = f"| {titles[scenario]} | {team} | " + " | ".join(
                f"{by[s].mean:.2f} ± {by[s].ci:.2f}" for s in ("clean", "upstream")
            )
            assert row + " |" in section, row


def test_re_recording_the_same_version_keeps_its_earlier_hash_as_the_same_version(copy):
    root, versions = copy
    before = suite.suite_hash(root)
    (root / "match" / "scoring.py").write_text((root / "match" / "scoring.py").read_text() + "\n# restructured\n")
    after = suite.suite_hash(root)
    assert after != before and suite.check(root, versions) is not None
    assert suite.record(None, versions, root) == f"recorded {suite.label('suite 1.0', after)} in {versions.name}"
    assert suite.check(root, versions) is None and list(suite.recorded(versions)) == ["suite 1.0"]
    assert suite.same_version(versions) == {before: after, after: after}
    assert suite.name_of(before, suite.recorded(versions), suite.same_version(versions)) == "suite 1.0"
    assert suite.one_version(before[:16], versions) == suite.one_version(after[:16], versions) == after[:16]
    assert suite.one_version("c" * 16, versions) == "c" * 16  # not a recorded hash: as given
    suite.record("suite 1.1", versions, root)  # a new version starts without earlier hashes
    assert json.loads(versions.read_text())["versions"][-1] == {"name": "suite 1.1", "sha256": after}
