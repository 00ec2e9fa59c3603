"""Tracking pipelines: session -> per-step table + trajectory.

``get_pipeline(name)(session, **options) -> TrackResult``; :data:`PIPELINES` maps every name (``plasys``,
``waist-pll``, ``waist-pendulum``) to its function, and :func:`get_pipeline`'s docstring lists their keyword
arguments. ``pdrlearn track --pipeline NAME`` looks them up there; a new pipeline registers itself with
``@register_pipeline(name)`` (see :mod:`pdrlearn.track.base`) and is listed in
:mod:`pdrlearn.track.pipelines`.

Warnings (no model, gaps, fallbacks) are ``logging`` records of the ``pdrlearn`` logger, not Python
``warnings``, and are also returned in ``result.info["warnings"]``; they print on stderr through a handler you
configure (``logging.basicConfig()``), not through Python's last-resort printer (decision B350). Silence them with
``logging.getLogger("pdrlearn").setLevel(logging.ERROR)``; capture them with a handler on that logger (or
pytest's ``caplog``). ``warnings.filterwarnings`` / ``catch_warnings`` do not see them.

Figures (decision E89): ``result.plot(session)`` draws one track; :func:`plot_paths` (saved) and
:func:`path_figure` (a figure) draw several, with the session's ground truth.
"""

from pdrlearn.track.base import PIPELINES, TrackResult, get_pipeline, register_pipeline
from pdrlearn.track.plots import path_figure, plot_paths

__all__ = ["PIPELINES", "TrackResult", "get_pipeline", "path_figure", "plot_paths", "register_pipeline"]
