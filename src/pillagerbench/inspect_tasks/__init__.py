"""PillagerBench inside Inspect (UK AISI's evaluation framework; the optional extra
`pip install 'pillagerbench[inspect]'`, docs/inspect.md): the tasks `pillagerbench/mushroom_war`,
`pillagerbench/dash_and_dine` and `pillagerbench/generalization`, found through Inspect's package
entry point (`registry.py`).

A sample is one series (opponent, side, arena) built by our experiments (`experiments/spec.py`,
the generalization design) and played by our series runner (`experiments/series.py`), its run
directory written as any other; the LLM teams ask Inspect's models (llm=inspect,
`llm/inspect_model.py`). `args.py`: the task arguments and the series they make; `solver.py`: one
series played; `scorer.py`: win, points, sabotage, dominance from our metrics; `transcript.py`:
what each episode adds to the sample's transcript; `experiment_dir.py`: the Inspect run as one
experiment directory (`pillagerbench report` reads it whole). With `-T team=agent` an Inspect agent
plays the team through the game's tools: `seated.py` (the setup step: the sample's seat and its series in
the background; its end before scoring), `tools.py` (the tools as Inspect tools, `pillagerbench_tools()`),
`default_agent.py` (react() when no --solver is given). Its modules import Inspect: nothing of the
default install imports it (tests/inspect_tasks/test_optional.py).
"""
