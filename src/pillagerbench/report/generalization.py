"""The report's section "Unseen arenas": every team's P, S, D, W on the paper's layout and on
generated layouts of a held-out split (test, dev), each ± its 95 % interval, and the gap (unseen −
paper), as metrics/generalization.py `unseen_arenas` computed them; here its title and notes. Only
runs with episodes on such layouts have it.
"""

from __future__ import annotations

import pandas as pd

from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.generalization import UNSEEN

NAME = "unseen_arenas"
TITLE = "Unseen arenas: each team on the paper's layout and on layouts it has never met (gap = unseen − paper)"


def unseen_notes(df: pd.DataFrame) -> list[str]:
    """What the section rests on and how to read it (nothing without unseen layouts)."""
    if not len(df) or Col.SPLIT not in df or not df[Col.SPLIT].isin(UNSEEN).any():
        return []
    counts = ", ".join(
        f"{int((df[Col.SPLIT] == s).sum())} on {df.loc[df[Col.SPLIT] == s, Col.LAYOUT].nunique()} {s} layout(s)"
        for s in UNSEEN
        if (df[Col.SPLIT] == s).any()
    )
    return [
        f"unseen arenas: {counts}, {int((df[Col.SPLIT] == 'paper').sum())} on the paper's layout; gap = unseen − "
        "paper, its 95 % interval Welch's (normal approximation, Welch–Satterthwaite df) from the two standard "
        "errors; the other tables pool every layout"
    ]
