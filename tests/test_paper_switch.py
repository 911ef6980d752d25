"""paper=true: one switch for numbers to put beside the paper's (upstream's scoring and step
protocol), carried into every series of an experiment, refused when contradicted, and named in the
header of every experiment config that reproduces one of the paper's tables."""

from __future__ import annotations

from importlib import resources

import pytest

from pillagerbench.config.compose import PAPER_SWITCHES, ConfigError, config_options, load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments.spec import build_series

OURS = {"symmetry", "generalization"}  # experiments of our own, not the paper's


def test_paper_true_sets_upstreams_scoring_and_protocol_and_the_default_is_ours():
    cfg = load_config(["paper=true"])
    assert {k: cfg[k] for k in PAPER_SWITCHES} == {"scoring": "upstream", "protocol": "upstream"}
    cfg = load_config([])
    assert (cfg.paper, cfg.scoring, cfg.protocol) == (False, "clean", "pillagerbench")


def test_every_series_of_an_experiment_plays_with_the_papers_settings():
    argv = ["experiment=main_benchmark", "experiment.team=passive", "paper=true"]
    specs = build_series(RunConfig.of(load_config(argv)), argv)
    assert len(specs) == 30
    assert {(s.config.scoring, s.config.protocol) for s in specs} == {("upstream", "upstream")}


@pytest.mark.parametrize("contradiction", ["scoring=clean", "protocol=pillagerbench"])
def test_paper_true_contradicted_is_refused_in_one_line(contradiction):
    with pytest.raises(ConfigError) as err:
        load_config(["paper=true", contradiction])
    key, value = contradiction.split("=")
    assert str(err.value) == (
        f"paper=true plays with {key}=upstream (as the paper's tables); drop {contradiction} or paper=true"
    )


@pytest.mark.parametrize("name", sorted(set(config_options("experiment")) - OURS))
def test_each_papers_experiment_names_the_switch_in_its_header(name):
    text = (resources.files("pillagerbench.conf") / "experiment" / f"{name}.yaml").read_text()
    header = text.split("\nname:")[0]
    assert "paper=true" in header
