"""The PNG plots lab.plots draws with matplotlib, for the views that use them."""

from __future__ import annotations

from collections.abc import Callable

from lab.views import PlotJob


def matplotlib_plot(view: str) -> Callable[[PlotJob], None]:
    """The `render --view` plot of `view` (matplotlib is imported only when it runs)."""

    def plot(job: PlotJob) -> None:
        from lab.plots import save_view

        save_view(
            job.renderer, view, job.model, job.values, job.theta_i, job.phi_i, job.out, job.size
        )

    return plot
