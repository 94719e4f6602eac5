"""adjoin: the earthquake response of adjacent structures joined by dampers, from Python.

``import adjoin`` gives the library, not the command line: scenes from files or dicts, runs
whose results come back in memory (numpy arrays), records, spectra and modes, and errors as
exceptions. The numbers are those of ``adjoin run`` on the same scene, bit for bit.

    >>> import adjoin
    >>> scene = adjoin.load_scene("records/scenes/paper-strong.toml", set={"solver.h": 0.001})
    >>> result = adjoin.run(scene)
    >>> result.summary["peaks"]["x1"]["max_abs"]        # as in summary.json
    >>> result.timeseries["x1"]                          # numpy array, as in timeseries.csv

Scenes (SPEC §3, §5): ``load_scene``, ``Scene.from_dict``, ``Scene.to_dict``, ``Scene.to_toml``.
Runs: ``run``, ``run_many`` (native threads, the GIL released), ``run_structure`` (a
structure built in code, on a record), ``Result``.
Ground motions and spectra: ``read_record``, ``Record``, ``spectrum``, ``rotd``,
``ductility_spectrum``, ``default_periods``.
Structures: ``modes``, ``joint`` (the minimum seismic joint), ``StructureBuilder``.
Design studies (SPEC §9): ``ida`` (stripes over a suite), ``fragility`` (lognormal fits).
Errors: ``InputError`` (a ValueError, with ``.field``), ``NumericalError`` (an
ArithmeticError, with ``.time``).
Plots (matplotlib, when installed): ``adjoin.plot``.
"""
from __future__ import annotations

import json
import os
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

from . import _adjoin
from ._adjoin import (  # noqa: F401  (re-exported)
    BuildingBuilder,
    ContactBuilder,
    InputError,
    NumericalError,
    Record,
    Structure,
    StructureBuilder,
)

__all__ = [
    "InputError", "NumericalError", "Scene", "load_scene", "run", "run_many", "run_structure", "Result",
    "Record", "read_record", "spectrum", "rotd", "ductility_spectrum", "default_periods",
    "modes", "joint", "ida", "fragility", "optimize", "Structure", "StructureBuilder", "BuildingBuilder", "ContactBuilder",
]


class Scene:
    """A scene the library's scene readers accepted: a two-block scene (SPEC §3) or a
    building scene (SPEC §5).

    Made by ``load_scene(path)``, ``Scene.from_dict(d)`` or ``Scene.from_toml(text)``; every
    check of a scene file applies (unknown keys, types, ranges), and a problem raises
    ``InputError`` whose ``.field`` is the dotted key (``"solver.h"``, ``"link.1.slip_force"``).
    Values are in the scene's units: SI (m, kg, N, s) or the paper's dimensionless units.

    Attributes:
        name (str): the scene's ``name``.
        building (bool): a building scene (``[building.A]`` ...) rather than a two-block one.
        warnings (list[str]): valid but probably unintended choices (``adjoin run`` prints
            them as ``warning: ...``).
        file (str): the file it was read from (``<folder>/<dict>`` for a dict).
    """

    __slots__ = ("_scene",)

    def __init__(self, _scene: Any):
        self._scene = _scene

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], *, folder: str | os.PathLike[str] | None = None,
                  name: str = "<dict>") -> Scene:
        """A scene from a dict with the structure of the TOML file: nested dicts for tables
        (``{"solver": {"h": 0.002}}``), lists of dicts for arrays of tables
        (``"link": [{"floors": [3, 3], ...}]``), numbers, strings, bools and lists as values
        (numpy scalars and arrays are accepted).

        The dict is written as TOML (toml++) and read by the scene reader itself, so it is
        checked exactly as a file: ``InputError`` with ``.field`` naming the key.

        Args:
            d: the scene.
            folder: where relative paths (``ground.file``) start; default the working folder.
            name: the scene's stand-in file name in messages.
        """
        return cls(_adjoin.Scene.from_dict(dict(d), folder=_path_or_none(folder), name=name))

    @classmethod
    def from_toml(cls, text: str, *, folder: str | os.PathLike[str] | None = None,
                  name: str = "<text>") -> Scene:
        """A scene from TOML text (what a scene file holds); ``folder`` as in ``from_dict``."""
        return cls(_adjoin.Scene.from_toml(text, folder=_path_or_none(folder), name=name))

    def to_dict(self) -> dict:
        """The scene as a dict (the structure of the TOML file), with the ``set``/``unset``
        edits of ``load_scene`` applied by the rules of ``--set``/``--unset`` (a key replaces
        its alternative, ``building.A.period`` for ``stiffness``; a new ``ground.source`` or
        contact ``model`` drops the keys it does not take) and relative record paths made
        absolute, so that ``Scene.from_dict(scene.to_dict())`` is the same scene."""
        return self._scene.to_dict()

    def to_toml(self) -> str:
        """The scene as TOML text (``to_dict()`` written by toml++), readable by ``adjoin run``."""
        return self._scene.to_toml()

    @property
    def name(self) -> str:
        return self._scene.name

    @property
    def building(self) -> bool:
        return self._scene.building

    @property
    def warnings(self) -> list:
        return list(self._scene.warnings)

    @property
    def file(self) -> str:
        return self._scene.file

    def __repr__(self) -> str:
        return repr(self._scene)


def _path_or_none(p):
    return None if p is None else os.fspath(p)


def load_scene(path: str | os.PathLike[str], set: Mapping[str, Any] | None = None,
               unset: Iterable[str] | None = None) -> Scene:
    """Reads and checks a scene file (TOML), as ``adjoin run PATH --set K=V --unset K`` does.

    Args:
        path: the scene file: a two-block scene (``[model]``, SPEC §3) or a building scene
            (``[building.A]``, SPEC §5). Relative paths inside it start at its folder.
        set: edits by dotted key, ``{"solver.h": 0.001, "link.1.slip_ratio": 0.1}``; values
            are Python values (numbers in the scene's units, strings, bools, lists), lists
            counted from 1 as the scene's ``[[link]]`` tables are.
        unset: dotted keys or sections removed first (``["ground.scale_pga"]``).

    Returns:
        Scene

    Raises:
        InputError: the file cannot be read or a key is wrong; ``.field`` names the key.
    """
    return Scene(_adjoin.load_scene(os.fspath(path), set=None if set is None else dict(set),
                                    unset=None if unset is None else [str(k) for k in unset]))


def _as_scene(scene: Scene | Mapping[str, Any] | str | os.PathLike[str]) -> Scene:
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, Mapping):
        return Scene.from_dict(scene)
    if isinstance(scene, (str, os.PathLike)):
        return load_scene(scene)
    raise TypeError(f"expected an adjoin.Scene, a dict or a scene file's path, got {type(scene).__name__}")


class Result:
    """What one run gives, in memory: the same values ``adjoin run`` writes into its folder.

    Attributes:
        summary (dict): summary.json, parsed (``json.loads`` of the same text): ``scene``,
            ``units``, ``solver`` (``h``, ``steps``, ``wall_seconds`` ...), ``peaks``
            (``{name: {"max_abs", "t"}}``), ``final``, ``pounding``, ``energy`` for a
            two-block scene; ``structure`` (periods, damping ratios, mode shapes), ``peaks``
            by channel (``"A.drift2"``), ``links``, ``contacts`` for a building scene. Values
            in the scene's units (SI: m, N, s, J; dimensionless otherwise).
        timeseries (dict[str, numpy.ndarray]): each column of timeseries.csv by name
            (two-block: ``t, x1, x2, v1, v2, f1, f2, q, ag, gap, phase``; building: ``t, ag``
            and a column per channel, ``A.x3`` [m], ``A.a3_abs`` [g], ``link1.force`` [N] ...);
            numbers as float64 arrays holding exactly the CSV's values, words (``phase``)
            as an array of str. Empty when the run wrote no time series (``timeseries=False``).
        impacts (list[dict]): the rows of impacts.csv (a contact law's impacts, in the order
            they started): ``t_start`` [s], ``duration``, ``force_max`` [N],
            ``penetration_max`` [m], ``impulse`` [N s], ``complete`` (bool) ...; building
            scenes also ``contact`` (1-based). Empty without a contact law.
        spectra (dict[str, numpy.ndarray | list]): spectra.csv's columns (``[output.spectra]``).
        energy_history (dict[str, numpy.ndarray]): energy.csv's columns (``output.energy_history``).
        channels (list[str]): the names of the time-series columns other than ``t``.
    """

    __slots__ = ("summary", "timeseries", "impacts", "spectra", "energy_history", "channels", "_brief")

    def __init__(self, raw: dict):
        self.summary = json.loads(raw["summary_json"])
        self.timeseries = _arrays(raw["timeseries"])
        self.impacts = _rows(raw["impacts"])
        self.spectra = dict(raw["spectra"])
        self.energy_history = dict(raw["energy"])
        self.channels = [name for name in self.timeseries if name != "t"]
        self._brief = raw["brief"]

    def brief(self) -> str:
        """The short report ``adjoin run`` prints: scene, solver, phases, peaks, pounding
        margin, energy, error estimate."""
        return self._brief

    def __repr__(self) -> str:
        return f"<adjoin.Result of '{self.summary.get('scene')}': {len(self.channels)} channels>"


def _arrays(columns: dict) -> dict:
    """Columns as numpy arrays: numbers as they come (float64, owning their buffer), words as
    arrays of str."""
    return {name: values if isinstance(values, np.ndarray) else np.array(values, dtype=str)
            for name, values in columns.items()}


def _rows(columns: dict) -> list:
    if not columns:
        return []
    names = list(columns)
    count = len(columns[names[0]])
    rows = []
    for i in range(count):
        row = {}
        for name in names:
            value = columns[name][i]
            if name == "complete":
                value = value == "true"
            elif name == "contact":
                value = int(value)
            else:
                value = float(value) if not isinstance(value, str) else value
            row[name] = value
        rows.append(row)
    return rows


def run(scene: Scene | Mapping[str, Any] | str | os.PathLike[str], *, timeseries: bool = True,
        every: int | None = None, allow_long: bool = False) -> Result:
    """Runs one scene as ``adjoin run`` does and returns its results in memory.

    The step, horizon, error estimate and outputs are the scene's (``[solver]``,
    ``[output]``); the numbers are those ``adjoin run`` writes, bit for bit (the same
    library calls make the same texts, read back exactly). The GIL is released while the
    run computes.

    Args:
        scene: an ``adjoin.Scene``, a dict (``Scene.from_dict``) or a scene file's path.
        timeseries: keep the time series the scene asks for (``output.timeseries``);
            False drops it (faster, less memory). It never adds one the scene does not ask.
        every: keep every n-th grid point in the time series (``output.every``); None keeps
            the scene's rule.
        allow_long: run even when the run is estimated (from its first steps) at more than
            2 hours; refused otherwise, as ``adjoin run`` refuses it without ``--allow-long``.

    Returns:
        Result: ``.summary`` (summary.json as a dict), ``.timeseries`` (numpy arrays by
        column), ``.impacts``, ``.channels``, ``.brief()``.

    Raises:
        InputError: the scene is refused when run (the run would need more memory than the
            machine has, or more than 2 hours); ``.field`` names the key when one is at fault.
        NumericalError: the computation failed; ``.time`` says when.
    """
    s = _as_scene(scene)
    return Result(_adjoin.run(s._scene, timeseries=timeseries, every=_every(every), allow_long=allow_long))


def run_many(scenes: Sequence[Scene | Mapping[str, Any] | str | os.PathLike[str]], jobs: int = 0, *,
             timeseries: bool = True, every: int | None = None, allow_long: bool = False) -> list:
    """Runs many scenes in native threads (the GIL released) and returns their results in
    the order of ``scenes``: each result equals ``run(scene)``'s.

    Args:
        scenes: scenes, dicts or paths (all read first, so a bad scene fails before any run).
        jobs: threads; 0 uses one per core.
        timeseries, every, allow_long: as in ``run``.

    Raises:
        InputError, NumericalError: of the first scene (in input order) that failed; the
            message starts with ``scenes[i]:``, and ``.field`` / ``.time`` are that run's.
    """
    loaded = [_as_scene(s) for s in scenes]
    if jobs < 0:
        raise InputError(f"jobs = {jobs}: expected 0 (one per core) or a positive number of threads")
    raw = _adjoin.run_many([s._scene for s in loaded], jobs=jobs, timeseries=timeseries, every=_every(every),
                            allow_long=allow_long)
    return [Result(r) for r in raw]


def run_structure(structure: Structure, record: str | os.PathLike[str], *, scale_pga: float | None = None,
                  scale: float = 1.0, h: float | None = None, t_end: float | None = None, tolerance: float | None = None,
                  name: str = "building", timeseries: bool = True, every: int | None = None,
                  allow_long: bool = False) -> Result:
    """Runs a structure built in code (``StructureBuilder.build()``) on a record, as a building
    scene with ``[ground] source = "record"`` runs: the same numbers as that scene's run.

    Args:
        structure: an ``adjoin.Structure``.
        record: a record file's path (the format from the file, as a scene's ``ground.file``).
        scale_pga: scale the record to this peak ground acceleration [g] (``ground.scale_pga``).
        scale: a plain factor on the record's acceleration, after ``scale_pga`` (``ground.scale``;
            a suite's scale factor).
        h, t_end: the step and the horizon [s] (``solver.h``, ``solver.t_end``); None chooses
            them by a scene's rules (the step for ``tolerance``, the horizon from the record's
            duration and the longest period).
        tolerance: the relative error of the peaks the step is chosen for (not with ``h``).
        name: the run's name (summary.json ``scene``).
        timeseries, every, allow_long: as in ``run``.

    Raises:
        InputError: a bad value; ``.field`` names the keyword (``"h"``, ``"scale_pga"``, ``"scale"``).
        NumericalError: the computation failed; ``.time`` says when.
    """
    return Result(_adjoin.run_structure(structure, os.fspath(record), scale_pga=scale_pga, scale=scale, h=h, t_end=t_end,
                                        tolerance=tolerance, name=name, timeseries=timeseries, every=_every(every),
                                        allow_long=allow_long))


def _every(every):
    if every is None:
        return 0
    if int(every) < 1:
        raise InputError(f"every = {every}: expected a whole number >= 1 (or None: the scene's rule)")
    return int(every)


def read_record(path: str | os.PathLike[str], *, format: str = "auto", units: str | None = None,
                dt: float | None = None, time_column: str = "", accel_column: str = "",
                delimiter: str = "", channel: int = 0) -> Record:
    """Reads an accelerogram file, as ``adjoin record`` and a scene's ``[ground]`` do.

    Formats: PEER AT2, one-column, two-column, delimited (CSV with a header), USGS SMC,
    COSMOS V1/V2, K-NET/KiK-net, ESM/ITACA, CSMIP/DMG V2; ``format="auto"`` finds it from
    the file's header (docs/reference/records.md).

    Args:
        path: the file.
        format: ``auto``, ``at2``, ``one-column``, ``two-column``, ``delimited`` (``csv``),
            ``smc``, ``cosmos``, ``knet``, ``esm``, ``dmg``.
        units: the file's acceleration unit when it does not say: ``g``, ``m/s2``,
            ``cm/s2`` (``gal``), ``mm/s2``.
        dt: the step [s] of a one-column file (or a delimited one without a time column).
        time_column, accel_column: delimited files: a column's name or 1-based index.
        delimiter: delimited and two-column files: one character; "" guesses.
        channel: multi-channel COSMOS or DMG files: which channel (1-based).

    Returns:
        Record: ``.dt`` [s], ``.accel`` [g] (numpy), ``.units``, ``.header``, ``.source``.

    Raises:
        InputError: the file cannot be read or is malformed (the message names its line).
    """
    return _adjoin.read_record(os.fspath(path), format=format, units=units, dt=dt, time_column=time_column,
                               accel_column=accel_column, delimiter=delimiter, channel=channel)


def spectrum(accel: Record | np.ndarray, dt: float | None = None, periods: Sequence[float] | None = None,
             damping: float | Sequence[float] = 0.05, *, units: str = "g", peaks: str = "exact",
             free_vibration: bool = False, threads: int = 0) -> dict:
    """Elastic response spectra (post/spectrum.hpp), the numbers of ``adjoin spectrum``.

    The oscillator u'' + 2 zeta omega u' + omega^2 u = -a_g(t) is advanced exactly for a_g
    linear between samples, and its peaks are located between samples exactly.

    Args:
        accel: an ``adjoin.Record`` (its own samples and step: the CLI's numbers bit for bit)
            or a one-dimensional array of accelerations in ``units``.
        dt: the step [s] (arrays only).
        periods: oscillator periods [s] (>= 0; 0 is the rigid oscillator, the PGA); None:
            100 log-spaced from 0.01 s to 10 s (``default_periods()``).
        damping: a damping ratio (0.05 is 5 %) or a list of them.
        units: the unit of an array's samples: ``g``, ``m/s2``, ``cm/s2``, ``mm/s2``.
        peaks: ``"exact"`` (located between sub-steps) or ``"samples"``.
        free_vibration: also scan one damped period of free vibration after the record.
        threads: worker threads; 0 one per core (the numbers do not depend on it).

    Returns:
        dict of numpy arrays, one element per (damping, period), damping-major as the CSV of
        ``adjoin spectrum``: ``period`` [s], ``damping``, ``sd`` [m], ``sv`` [m/s] (true
        relative velocity), ``sa`` [g] (true absolute acceleration), ``psv`` [m/s],
        ``psa`` [g].
    """
    return _adjoin.spectrum(accel, dt, periods=_list_or_none(periods), damping=_floats(damping), units=units,
                            peaks=peaks, free_vibration=free_vibration, threads=threads)


def rotd(h1: Record | np.ndarray, h2: Record | np.ndarray, dt: float | None = None,
         periods: Sequence[float] | None = None, damping: float | Sequence[float] = 0.05, *,
         percentiles: Sequence[float] = (50, 100), angle_step: float = 1.0, units: str = "g",
         peaks: str = "exact", threads: int = 0) -> dict:
    """Orientation-independent spectra of two horizontal components (post/rotd.hpp):
    RotD00, RotD50, RotD100 (Boore 2010) and GMRotI50 (Boore et al. 2006), the numbers of
    ``adjoin spectrum H1 H2 --rotd``.

    Args:
        h1, h2: Records, or arrays in ``units`` sampled at ``dt`` [s], of the same length.
        periods, damping, units, peaks, threads: as in ``spectrum``.
        percentiles: RotD percentiles wanted; those other than 0, 50 and 100 (always given)
            add columns ``rotdNN``.
        angle_step: the rotation step [degrees]; 90 / angle_step a whole number.

    Returns:
        dict of numpy arrays per (damping, period): ``period`` [s], ``damping``, ``rotd00``,
        ``rotd50``, ``rotd100``, ``gmroti50`` (PSA in g), ``angle00``, ``angle100``
        [degrees from h1's direction], ``psa_h1``, ``psa_h2`` [g], and ``gmroti50_angle``
        (one per damping) [degrees].
    """
    return _adjoin.rotd(h1, h2, dt, periods=_list_or_none(periods), damping=_floats(damping),
                        percentiles=[float(p) for p in percentiles], angle_step=angle_step, units=units, peaks=peaks,
                        threads=threads)


def ductility_spectrum(accel: Record | np.ndarray, dt: float | None = None,
                       periods: Sequence[float] | None = None,
                       ductility: float | Sequence[float] = (1, 2, 4, 6), damping: float | Sequence[float] = 0.05,
                       *, hysteresis: str = "epp", hardening: float = 0.0, units: str = "g", tolerance: float = 1e-4,
                       threads: int = 0) -> dict:
    """Constant-ductility (inelastic) spectra (post/inelastic.hpp), the numbers of
    ``adjoin spectrum RECORD --ductility ...``: for each period the largest yield strength
    with which the oscillator reaches the target ductility.

    Args:
        accel, dt, units, threads: as in ``spectrum``.
        periods: periods [s], each in [1e-4, 1e4]; None: the default periods without 0.
        ductility: target ductilities mu = max|u| / u_y, each in [1, 100].
        damping: damping ratio(s) on the initial stiffness.
        hysteresis: ``"epp"`` (elastic-perfectly-plastic) or ``"bilinear"``.
        hardening: the post-yield stiffness ratio (bilinear), in [0, 1).
        tolerance: relative tolerance on the ductility reached.

    Returns:
        dict of numpy arrays per (damping, period, ductility): ``period`` [s], ``damping``,
        ``ductility`` (the target), ``cy`` = f_y / (m g), ``uy`` [m], ``R`` = f_e / f_y,
        ``ductility_reached``, ``peak_displacement`` [m].
    """
    return _adjoin.ductility_spectrum(accel, dt, periods=_list_or_none(periods), ductility=_floats(ductility),
                                      damping=_floats(damping), hysteresis=hysteresis, hardening=hardening,
                                      units=units, tolerance=tolerance, threads=threads)


def default_periods() -> np.ndarray:
    """The default spectrum periods [s]: 100 log-spaced from 0.01 s to 10 s."""
    return np.asarray(_adjoin.default_periods())


def modes(scene: Scene | Structure | Mapping[str, Any] | str | os.PathLike[str]) -> dict:
    """Each building's undamped modes (structure/modal.hpp), as ``adjoin modes`` prints them.

    Args:
        scene: a building scene (Scene, dict or path) or a ``Structure`` built in code.

    Returns:
        dict: ``{"A": {...}, "B": {...}, "coupled": {...}}``; per building ``periods`` [s],
        ``omega`` [rad/s], ``shapes`` (floors x modes, mass-normalised, floor 1 first),
        ``damping`` (total ratio), ``inherent_damping``, ``device_damping``, ``zener_stiffening``,
        ``participation`` (of the shape scaled to 1 at the roof), ``effective_mass`` [kg],
        ``p_delta``; an isolated building also ``isolated_period`` [s] (a friction pendulum's
        2 pi sqrt(R/g), NaN for a flat slider) and ``isolated_period_flexible`` [s] (the base
        and the storeys at their initial stiffness on the pendulum's W/R);
        ``coupled``: ``periods_free`` and ``periods_locked`` [s] of both buildings with the
        links' friction dampers free or locked.

    Raises:
        InputError: a two-block scene (its modes are the two blocks' own).
    """
    if isinstance(scene, Structure):
        return _adjoin.modes(scene)
    return _adjoin.modes(_as_scene(scene)._scene)


def joint(scene: Scene | Mapping[str, Any] | str | os.PathLike[str], *, contact: int = 1,
          tol: float | None = None, allow_long: bool = False) -> dict:
    """The minimum seismic joint: the smallest clear gap at rest with which the floors of a
    contact pair never touch (study/seismic_joint.hpp), as ``adjoin joint`` finds it.

    Two answers that agree to the tolerance: a bisection over runs on the gap, and the
    largest relative displacement s_max of one run without contact; beside them the codes'
    rules (SRSS, ASCE 7-16 12.12.3, and the absolute sum) from the floors' own peaks.

    Args:
        scene: a Scene, dict or path; a building scene's pair ``contact`` (1-based) or a
            two-block scene's ``model.gap0`` (contact 1).
        contact: the contact pair whose gap is the joint.
        tol: the bisection's tolerance in the scene's length unit (m for SI and building
            scenes); None: 1e-6 of s_max.
        allow_long: as in ``run``.

    Returns:
        dict: ``joint`` (the gap found that does not touch) [m], ``touching_below`` [m],
        ``tolerance`` [m], ``runs``, ``s_max`` [m], ``t_critical`` [s], ``difference``
        (joint - s_max) [m], ``agree``, ``peak_a``, ``peak_b`` (the floors' peak
        displacements) [m] and their times [s], ``srss``, ``abs_sum`` [m], ``floors``,
        ``gap_key``, ``length_unit``, ``time_unit``, ``notes``, ``wall_seconds``.
    """
    return _adjoin.joint(_as_scene(scene)._scene, contact=contact, tol=tol, allow_long=allow_long)


# ---- design studies (SPEC §9) ----

def _bad(field: str, message: str) -> InputError:
    """An InputError about keyword ``field``, its message starting with it."""
    error = InputError(f"{field}: {message}")
    error.field = field
    return error


def _whole(value, field: str, least: int, most: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < least \
            or (most is not None and value > most):
        upto = f" and at most {most}" if most is not None else ""
        raise _bad(field, f"{value!r}: expected a whole number >= {least}{upto}")
    return int(value)


def _ida_csv_columns(path) -> dict:
    """ida.csv (or any table with a header) as {column: list of str}."""
    import csv
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise _bad("table", f"{os.fspath(path)}: cannot be read ({e.strerror})") from None
    if not rows:
        raise _bad("table", f"{os.fspath(path)}: empty (expected ida.csv: record,im,scale,<edp>...)")
    header, body = rows[0], [r for r in rows[1:] if r]
    for line, r in enumerate(body, start=2):
        if len(r) != len(header):
            raise _bad("table", f"{os.fspath(path)}:{line}: {len(r)} cells, the header has {len(header)}")
    return {name: [r[k] for r in body] for k, name in enumerate(header)}


def _table_columns(table) -> dict:
    if isinstance(table, (str, os.PathLike)):
        return _ida_csv_columns(table)
    names = getattr(getattr(table, "dtype", None), "names", None)
    if names:  # a numpy structured array
        return {name: table[name] for name in names}
    if isinstance(table, Mapping):
        return dict(table)
    raise _bad("table", f"a {type(table).__name__}: expected an ida.csv path, a mapping of columns "
                        "(record, im, <edp>...) or a structured array")


def _cell_number(value) -> float:
    if value is None:
        return float("nan")
    if isinstance(value, (bool, np.bool_)):
        return 1.0 if value else 0.0
    if isinstance(value, str):
        text = value.strip()
        if text == "":
            return float("nan")
        if text in ("true", "false"):
            return 1.0 if text == "true" else 0.0
        return float(text)
    return float(value)


def fragility(table: str | os.PathLike[str] | Mapping[str, Any] | np.ndarray | Sequence[Any], event: str, *,
              bootstrap: int = 1000, seed: int = 1, at: float | None = None,
              labels: Sequence[str] | None = None) -> dict:
    """The lognormal fragility P(event | IM = x) = Phi(ln(x / theta) / beta) of the runs of an
    IDA, fitted as ``adjoin fragility`` fits it (post/fragility.hpp: maximum likelihood on the
    counts per IM level, bootstrap bounds over records, and for IDA traces the IM at first
    event). The numbers equal that command's fragility.json on the same table.

    Args:
        table: an ida.csv path, or its columns: a mapping (e.g. what ``ida`` returns) or a
            structured array with ``im`` (g), the columns the event reads, and ``record`` (the
            runs of one record are resampled together; without it each run is its own
            record). An ``error`` column marks failed runs (left out, counted). A list of
            tables is several designs, as ``adjoin fragility A/ida.csv B/ida.csv`` takes them.
        event: a condition on the columns, ``COLUMN > NUMBER`` (>, >=, <, <=) joined by
            ``and``/``or``, e.g. ``"contact1.impacts > 0"``. A run whose event reads an empty
            value (NaN) is left out and counted.
        bootstrap: resamples of the records for the 5 %/95 % bounds (0: none; at most 100000).
        seed: the bootstrap's seed (the same seed gives the same bounds on every machine).
        at: an IM (g) at which to give the fitted probability of the event.
        labels: with a list of tables, the designs' names, one per table (default: an ida.csv's
            folder name, as the command's ``--label``; "design N" for columns).

    Returns:
        With a list of tables, ``{"event": event, "designs": [...]}`` (the command's JSON for
        several tables), each design a dict as below with its ``label``. Otherwise a
        dict: ``fitted`` (False for data without a fit: no events, events everywhere, perfect
        separation; ``problem`` says which and theta, beta are None), ``theta`` (g),
        ``beta``, ``log_likelihood``, ``levels`` (g), ``n`` and ``events`` per level (numpy
        arrays), ``records``, ``runs``, ``skipped`` (``failed``, ``unknown``), ``bootstrap``
        (``samples``, ``seed``, ``degenerate``, ``percentiles``, ``theta`` and ``beta``
        (low, high)) or None, ``first_event`` (traces: ``theta``, ``beta``, ``records``,
        ``censored``...) or None, and with ``at`` its ``im`` and ``probability``.

    Raises:
        InputError: with ``.field`` the keyword at fault (``table``, ``event``, ``bootstrap``,
        ``seed``, ``at``, ``labels``).
    """
    if not isinstance(event, str) or not event.strip():
        raise _bad("event", f"{event!r}: expected a condition such as \"contact1.impacts > 0\"")
    bootstrap = _whole(bootstrap, "bootstrap", 0, 100000)
    seed = _whole(seed, "seed", 0, 2**64 - 1)
    if at is not None:
        try:
            at = float(at)
        except (TypeError, ValueError):
            raise _bad("at", f"{at!r}: expected an intensity > 0 (g)") from None
        if not (at > 0.0 and np.isfinite(at)):
            raise _bad("at", f"{at!r}: expected an intensity > 0 (g)")
    if _several_tables(table):
        tables = list(table)
        if not tables:
            raise _bad("table", "an empty list: expected one table per design")
        names = _design_labels(tables, labels)
        designs = []
        for name, one in zip(names, tables):
            design = {"label": name}
            if isinstance(one, (str, os.PathLike)):
                design["file"] = os.fspath(one)
            design.update(_fragility_of_table(one, event, bootstrap, seed, at))
            designs.append(design)
        return {"event": event, "designs": designs}
    if labels is not None:
        raise _bad("labels", "labels name several designs: give a list of tables")
    return _fragility_of_table(table, event, bootstrap, seed, at)


def _several_tables(table) -> bool:
    """A list or tuple of tables (not one table: a path, a mapping of columns, an array)."""
    return isinstance(table, (list, tuple))


def _design_labels(tables, labels) -> list:
    if labels is None:
        names = []
        for k, t in enumerate(tables):
            if isinstance(t, (str, os.PathLike)):
                path = os.fspath(t)
                folder = os.path.basename(os.path.dirname(path))
                names.append(folder if folder else os.path.basename(path))
            else:
                names.append(f"design {k + 1}")
        return names
    if isinstance(labels, str):
        labels = labels.split(",")
    names = [str(v) for v in labels]
    if len(names) != len(tables):
        raise _bad("labels", f"{len(names)} labels for {len(tables)} tables (give one per table, in order)")
    return names


def _fragility_of_table(table, event, bootstrap, seed, at) -> dict:
    columns = _table_columns(table)
    if "im" not in columns:
        raise _bad("table", f"no column im; its columns are {', '.join(map(str, columns))}")
    count = len(columns["im"])
    names, values = [], []
    for name, column in columns.items():
        if name in ("record", "error"):
            continue
        if len(column) != count:
            raise _bad("table", f"column {name} has {len(column)} values, im has {count}")
        try:
            values.append([_cell_number(v) for v in column])
        except (TypeError, ValueError):
            continue  # words (not a demand): the event cannot read it, and says which columns it can
        names.append(str(name))
    if "im" not in names:
        raise _bad("table", "im: expected numbers (the intensity of each run, g)")
    im = values[names.index("im")]
    for r, v in enumerate(im):
        if not (v > 0.0 and np.isfinite(v)):
            raise _bad("table", f"row {r + 1}: im {v!r}: expected an intensity > 0")
    records = [str(r) for r in columns["record"]] if "record" in columns else [str(r) for r in range(count)]
    if any(r == "" for r in records):
        raise _bad("table", "an empty record name")
    errors = [str(e) for e in columns["error"]] if "error" in columns else []
    return _adjoin.fragility(records, im, names, values, errors, event, bootstrap, seed, at)


def ida(scene: str | os.PathLike[str], suite: str | os.PathLike[str] | Sequence[str | os.PathLike[str]], *,
        im: str = "pga", levels: Sequence[float] | None = None, trace: bool = False,
        edp: Sequence[str] | None = None, capacity: str | None = None, units: str | None = None,
        jobs: int = 0, trace_start: float = 0.1, trace_factor: float = 1.5, trace_tol: float = 0.05,
        trace_runs: int = 20, out: str | os.PathLike[str] | None = None) -> dict:
    """Incremental dynamic analysis, as ``adjoin ida SCENE --suite ... --im IM --levels
    ...|--trace`` runs it (study/ida.hpp, io/ida_files.hpp): each record of the suite scaled
    (``ground.scale``) so that its IM, of the record as read, equals a level. Stripes (``levels``):
    one sweep over the (record, level) pairs; tracing (``trace=True``): hunt and fill per
    record up to its capacity event. Native threads, the GIL released. The rows equal that
    command's ida.csv, bit for bit; with ``out`` the same ida.csv and ida.png are written.

    Args:
        scene: the base scene's TOML file (its ground is replaced by each record).
        suite: record files, or folders of them (every file a reader recognises).
        im: ``"pga"`` or ``"sa:T"`` (the 5 %-damped PSA at T s), in g.
        levels: stripes: the IM levels (g), each > 0, each once (not with ``trace``).
        trace: hunt and fill per record (Vamvatsikos & Cornell) up to the capacity event (the
            run's collapse, a failed run, or ``capacity``), starting at ``trace_start`` (g),
            stepping by ``trace_factor``, bracketing to ``trace_tol`` (relative), at most
            ``trace_runs`` runs per record.
        edp: the demands, sweep-table column names (default: as ``adjoin ida``; see
            docs/reference/cli.md#adjoin-ida).
        capacity: an event expression (as ``fragility``'s ``event``: ``"COLUMN OP X"``
            comparisons joined by ``and``/``or``) that marks the capacity event
            (``capacity_event``; a failed run or the run's collapse marks it too).
        units: the units of records that do not state theirs (g, m/s2, cm/s2, mm/s2).
        jobs: threads (0: one per core).
        out: a folder (made if missing) for ``ida.csv`` and ``ida.png`` (the IDA curves of the
            first demand with their 16/50/84 % fractiles), the files of ``adjoin ida --out``
            (not its sweep.csv, sweep.json or journal); None: no file.

    Returns:
        dict of columns, one row per run (record by record; stripes: the levels in the order
        given, traces: each record's runs by IM):
        ``record`` (file names), ``im`` (g), ``scale``, one numpy array per demand (NaN
        where the run has no value), ``error`` (a failed run's message, else ""),
        ``capacity_event`` (bool). ``fragility(result, event)`` fits it directly.

    Raises:
        InputError: with ``.field`` the keyword at fault (``levels``, ``im``, ``edp``, ...).
    """
    if not isinstance(scene, (str, os.PathLike)):
        raise _bad("scene", f"a {type(scene).__name__}: expected the base scene's TOML file (a path)")
    if not isinstance(im, str):
        raise _bad("im", f"{im!r}: expected pga or sa:T")
    if trace and levels is not None:
        raise _bad("levels", "levels and trace: give one (stripes at given levels, or tracing per record)")
    if not trace and levels is None:
        raise _bad("levels", "expected the IM levels in g (stripes), e.g. levels=[0.1, 0.2, 0.4], or trace=True")
    level_list = []
    if not trace:
        try:
            level_list = [float(v) for v in np.atleast_1d(np.asarray(levels, dtype=float))]
        except (TypeError, ValueError):
            raise _bad("levels", f"{levels!r}: expected numbers > 0 (g)") from None
        if not level_list:
            raise _bad("levels", "empty: expected at least one IM level (g)")
        for v in level_list:
            if not (v > 0.0 and np.isfinite(v)):
                raise _bad("levels", f"{v!r}: expected IM levels in g, numbers > 0")
            if level_list.count(v) > 1:
                raise _bad("levels", f"the level {v!r} appears twice")
    options = {}
    for name, value in (("trace_start", trace_start), ("trace_factor", trace_factor), ("trace_tol", trace_tol)):
        try:
            options[name] = float(value)
        except (TypeError, ValueError):
            raise _bad(name, f"{value!r}: expected a number") from None
    trace_runs = _whole(trace_runs, "trace_runs", 0)
    suite_list = [os.fspath(suite)] if isinstance(suite, (str, os.PathLike)) else [os.fspath(s) for s in suite]
    if not suite_list:
        raise _bad("suite", "empty: expected record files or folders of them")
    if isinstance(edp, str):
        edp = [edp]
    edps = [] if edp is None else [str(e) for e in edp]
    jobs = _whole(jobs, "jobs", 0)
    if out is not None and (not isinstance(out, (str, os.PathLike)) or os.fspath(out) == ""):
        raise _bad("out", f"{out!r}: expected a folder (a path) for ida.csv and ida.png")
    result = _adjoin.ida(os.fspath(scene), suite_list, im, level_list, bool(trace), options["trace_start"],
                         options["trace_factor"], options["trace_tol"], trace_runs, edps, capacity or "", units or "",
                         jobs, os.fspath(out) if out is not None else "")
    return _arrays(result["columns"])



def optimize(study: str | os.PathLike[str], *, jobs: int = 0, out: str | os.PathLike[str] | None = None) -> dict:
    """Design optimisation, as ``adjoin optimize STUDY.toml --out DIR`` runs it
    (io/optimize_study.hpp, study/optimize.hpp): damper parameters (continuous, with bounds)
    searched with NLopt and placements enumerated, to minimise a demand's statistic over a suite
    of records under constraints; two objectives give a Pareto front. The study file:
    docs/reference/study-file.md. Native threads (each design's records), the GIL released.

    Args:
        study: the study file (TOML, ``[optimize]``).
        jobs: threads for each design's runs (0: one per core).
        out: a folder for ``evaluations.csv``, ``optimum.json`` and the cache
            ``evaluations.cache.csv`` (a rerun with the same study and folder takes every
            design already evaluated from it); None: no file is written and nothing is cached.

    Returns:
        dict: optimum.json's keys (``variables``, ``placement``, ``objective``,
        ``evaluations``, ``runs``, ``history``, ``searches``, ``pareto``, ...), and
        ``table``: evaluations.csv as columns (numbers as numpy arrays, ``feasible`` and
        ``pareto`` as bool arrays, ``stage`` and placements as lists of str).

    Raises:
        InputError: ``.field`` ``"study"`` (the message names the file's line and key),
            ``"out"``, or a scene key.
        NumericalError: a run failed (the message names the design and the record).
    """
    import csv
    import io
    if not isinstance(study, (str, os.PathLike)):
        raise _bad("study", f"a {type(study).__name__}: expected the study file (a path)")
    jobs = _whole(jobs, "jobs", 0)
    text, table = _adjoin.optimize(os.fspath(study), jobs, "" if out is None else os.fspath(out))
    result = json.loads(text)
    rows = list(csv.reader(io.StringIO(table)))
    header, body = rows[0], rows[1:]
    columns = {}
    for k, name in enumerate(header):
        cells = [r[k] for r in body]
        if cells and all(c in ("true", "false") for c in cells):
            columns[name] = np.array([c == "true" for c in cells], dtype=bool)
            continue
        try:
            columns[name] = np.array([float(c) if c else np.nan for c in cells], dtype=float)
        except ValueError:
            columns[name] = cells
    result["table"] = columns
    return result


def _list_or_none(values):
    return None if values is None else [float(v) for v in np.atleast_1d(np.asarray(values, dtype=float))]


def _floats(values):
    return [float(v) for v in np.atleast_1d(np.asarray(values, dtype=float))]
