"""Plots of adjoin's results with matplotlib (``python3-matplotlib``; imported on first use).

Each function draws on the Axes it is given (or a new figure's) and returns the Axes, so
plots compose as in any matplotlib script:

    >>> import adjoin, adjoin.plot
    >>> ax = adjoin.plot.drift_profile(result, "A", label="friction 5 %")
    >>> ax.figure.savefig("drifts.png")
"""
from __future__ import annotations

from typing import Any, Sequence

import numpy as np


def _axes(ax):
    if ax is not None:
        return ax
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - the message is the point
        raise ImportError("adjoin.plot needs matplotlib (Debian: apt install python3-matplotlib)") from e
    return plt.figure().add_subplot()


def peak_drifts(result: Any, building: str = "A") -> np.ndarray:
    """The peak storey drifts |x_i - x_{i-1}| max [m] of a building run, storey 1 first
    (``result.summary["peaks"]["A.drift1"]["max_abs"]``, ...)."""
    peaks = result.summary["peaks"]
    drifts = []
    storey = 1
    while f"{building}.drift{storey}" in peaks:
        drifts.append(peaks[f"{building}.drift{storey}"]["max_abs"])
        storey += 1
    if not drifts:
        raise ValueError(f"the result has no drift peaks of building {building} (a building scene's run has)")
    return np.array(drifts)


def drift_profile(results: Any, building: str = "A", *, storey_height: float | None = None, ax=None,
                  label: str | None = None, **style) -> Any:
    """The peak storey drifts up a building: drift [m] (or drift ratio [-] when
    ``storey_height`` [m] is given) on x, storey on y. ``results`` is one Result or a list of
    them (e.g. one per record): their mean, with the range shaded."""
    ax = _axes(ax)
    runs = results if isinstance(results, (list, tuple)) else [results]
    drifts = np.array([peak_drifts(r, building) for r in runs])
    if storey_height:
        drifts = drifts / storey_height
    storeys = np.arange(1, drifts.shape[1] + 1)
    line, = ax.plot(drifts.mean(axis=0), storeys, marker="o", label=label, **style)
    if len(runs) > 1:
        ax.fill_betweenx(storeys, drifts.min(axis=0), drifts.max(axis=0), color=line.get_color(), alpha=0.15)
    ax.set_xlabel("peak storey drift ratio [-]" if storey_height else "peak storey drift [m]")
    ax.set_ylabel(f"storey of building {building}")
    ax.set_yticks(storeys)
    return ax


def timeseries(result: Any, channels: Sequence[str], *, ax=None, **style) -> Any:
    """Time series of a run (columns of ``result.timeseries``) against t [s, or the scene's
    time unit]."""
    ax = _axes(ax)
    t = result.timeseries["t"]
    for name in channels:
        ax.plot(t, result.timeseries[name], label=name, **style)
    ax.set_xlabel("t")
    ax.legend()
    return ax


def spectrum(values: dict, quantity: str = "psa", *, ax=None, label: str | None = None, **style) -> Any:
    """A spectrum of ``adjoin.spectrum`` (or ``rotd``: quantity ``"rotd50"``) against the
    period [s], one line per damping ratio."""
    ax = _axes(ax)
    for zeta in np.unique(values["damping"]):
        pick = values["damping"] == zeta
        text = f"{label}, " if label else ""
        ax.plot(values["period"][pick], values[quantity][pick], label=f"{text}{100 * zeta:g} %", **style)
    ax.set_xlabel("period [s]")
    unit = {"sd": "m", "sv": "m/s", "psv": "m/s"}.get(quantity, "g")
    ax.set_ylabel(f"{quantity} [{unit}]")
    ax.legend()
    return ax
