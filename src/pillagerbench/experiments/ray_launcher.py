"""Series as Ray tasks: `pillagerbench run experiment=... launcher=ray [ray_address=auto]`.

Each series is one Ray task (one CPU) that plays all its episodes in its worker process, with its
own arena server on a free port of that machine, so the team objects stay in one place. The task
writes to the run directory, which must be on storage every node sees (NFS, ...); the driver's
progress display and resume read the same files. With ray_address=null a local Ray instance is
started (the test uses this). Ray is an optional extra: pip install -e '.[ray]'.
"""

from __future__ import annotations

import asyncio
from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.experiments.spec import SeriesSpec


def _play_series(spec: dict, series_dir: str, run_dir: str) -> dict:
    """Runs in a Ray worker: one series to its end."""
    from pillagerbench.experiments.series import run_series

    return asyncio.run(run_series(SeriesSpec.from_dict(spec), Path(series_dir), Path(run_dir)))


class RayLauncher:
    def __init__(self, address: str | None = None, cpus_per_series: float = 1.0):
        try:
            import ray
        except ImportError:
            raise ConfigError("launcher=ray needs Ray: pip install -e '.[ray]'") from None
        self.ray = ray
        self.started = not ray.is_initialized()
        if self.started:
            ray.init(address=address or None, include_dashboard=False, log_to_driver=True, configure_logging=False)
        self.remote = ray.remote(num_cpus=cpus_per_series, max_retries=0)(_play_series)

    def cpus(self) -> int:
        return max(1, int(self.ray.cluster_resources().get("CPU", 1)))

    def launch_factory(self, run_dir: Path):
        run_dir = Path(run_dir).resolve()

        async def launch(spec: SeriesSpec, series_dir: Path) -> dict:
            ref = self.remote.remote(spec.to_dict(), str(Path(series_dir).resolve()), str(run_dir))
            try:
                return await ref
            except asyncio.CancelledError:
                self.ray.cancel(ref, force=True)
                raise

        return launch

    def close(self) -> None:
        if self.started:
            self.ray.shutdown()
