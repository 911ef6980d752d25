"""The configuration at the edge: Hydra composition (compose.py), its schema (schema.py), the
commands' argument parser (args.py) and the one registry type (registry.py)."""
