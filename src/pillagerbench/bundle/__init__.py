"""Results bundles as commands: `pillagerbench export` (export.py) and `pillagerbench verify`
(verify.py); the archive itself is rundir/bundle.py."""
