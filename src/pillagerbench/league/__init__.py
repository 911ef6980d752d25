"""A league (`pillagerbench league LEAGUE_DIR ...`): entrants in league.yaml, matches chosen by the
ratings' uncertainty and played through the experiment runner, a leaderboard rebuilt from the
episodes (docs/league.md)."""
