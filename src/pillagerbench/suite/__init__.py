"""What a result is comparable under: the suite version (version.py, the hash of every file that can
move a score) and the conditions of play (conditions.py, every config key declared as moving a score
or not)."""
