"""Statistics that decide with fewer episodes (issue 41): a sequential test on paired outcomes
(sprt.py), paired differences (paired.py), Bradley–Terry ratings with bootstrap intervals
(bradley_terry.py), the pool's maximal lottery (lottery.py) and how many episodes a question needs
(sample_size.py). Plain numpy, no game knowledge: the callers hand in numbers."""
