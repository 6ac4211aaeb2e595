"""Reading RAOs: a plain table (CSV), seahelm's RAO NetCDF, and capytaine's NetCDF output.

:func:`read_rao` takes any of the three (by suffix and content) and returns an
:class:`~seahelm.environment.rao.RAO` in seahelm's conventions (:mod:`.rao`: heading 0
following, π head, π/2 waves travelling to starboard; heave up, roll starboard down, pitch bow
up; phase = lead over the wave elevation at the origin, response Re(a H e^{iω_e t})).

The RAO table (CSV)
    One row per (dof, frequency, heading), a header line naming the columns (any order;
    lines starting with ``#`` are comments)::

        dof,frequency,heading_deg,amplitude,phase_deg
        heave,0.2,180,0.98,0.5
        roll,0.2,90,0.012,-84

    ``dof`` one of surge, sway, heave, roll, pitch, yaw; ``frequency`` the wave frequency ω
    [rad/s] (or ``period`` [s]); ``heading_deg`` ε [deg] (or ``heading`` [rad]);
    ``amplitude`` [m/m, rad/m] (or ``amplitude_deg`` [deg/m] for rotations); ``phase_deg``
    [deg] (or ``phase`` [rad]); an amplitude >= 0 (the sign is in the phase), a heading in
    [-180, 360] deg. An optional ``speed`` column [m/s] must hold one value. Every
    dof must have every (frequency, heading) of the grid.

seahelm's RAO NetCDF
    :meth:`RAO.to_xarray` written with ``to_netcdf``: ``amplitude`` and ``phase`` over
    (dof, frequency, heading), attribute ``format = "seahelm-rao-1"``.

capytaine's NetCDF (read as a file format; capytaine itself is not imported)
    A dataset of ``capytaine.assemble_dataset`` saved after
    ``capytaine.io.xarray.separate_complex_values`` (complex variables split along a
    dimension ``complex`` with coordinates ``re``, ``im``): ``added_mass`` and
    ``radiation_damping`` over (omega, radiating_dof, influenced_dof),
    ``diffraction_force`` and ``Froude_Krylov_force`` over (omega, wave_direction,
    influenced_dof), ``inertia_matrix`` and ``hydrostatic_stiffness`` over (influenced_dof,
    radiating_dof) — the body's, saved when it has them (``hydrostatics=True``). The motion
    RAO is the solution of [−ω²(M + A(ω)) − iωB(ω) + C] X = F_FK + F_D (capytaine's
    convention x(t) = Re(X e^{−iωt}), axes x forward, y port, z up, wave direction β = 0
    travelling towards +x), converted to seahelm's: X → conj(X), ε = −β (mod 2π), and sway,
    pitch and yaw change sign (y port → starboard; pitch positive bow down → up; yaw about
    z up → down). Wave directions β in [0, π] (the usual choice: waves towards port) give
    ε in {0} ∪ [π, 2π); such a file is mirrored to ε in [0, π] (ε → 2π − ε, sway, roll and yaw
    change sign), which holds for a hull symmetric about its centre plane, as :class:`RAO`
    assumes of every table over [0, π]. The RAOs hold at zero speed (capytaine's potential flow
    without forward speed) unless the file has a ``forward_speed``. Checked on a real
    capytaine 3.0 file, the box barge that seahelm ships (:func:`box_barge_database`):
    capytaine puts the ``complex`` dimension first; the reader selects it by name.

Bad input raises :class:`~seahelm.errors.ParameterError` naming the file and the column or
variable (missing dof, non-monotonic or repeated frequencies, missing grid points, NaN).
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError
from .rao import DOFS, RAO

__all__ = ["read_rao", "read_rao_table", "read_capytaine", "write_rao_table",
           "rao_from_capytaine_dataset", "box_barge_database", "wigley_database"]

#: The capytaine database shipped with seahelm (package data, ``seahelm/data/rao/``).
BOX_BARGE_DATABASE = "box-barge-100x20x5-capytaine.nc"
#: The shipped capytaine database of a ship hull (Wigley I, model scale).
WIGLEY_DATABASE = "wigley-i-3m-capytaine.nc"

_CAPY_DOFS = {"Surge": ("surge", 1.0), "Sway": ("sway", -1.0), "Heave": ("heave", 1.0),
              "Roll": ("roll", 1.0), "Pitch": ("pitch", -1.0), "Yaw": ("yaw", -1.0)}


def box_barge_database() -> Path:
    """The shipped capytaine NetCDF of a box barge (L 100 m, B 20 m, T 5 m) at zero speed.

    capytaine 3.0.0 (potential flow, 2,048 hull panels <= 1.25 m, a lid against irregular
    frequencies), 36 wave frequencies 0.2-1.6 rad/s, wave directions 0-180° every 15°, a
    homogeneous box of depth 10 m (GM 4.167 m, k_xx 6.455 m, k_yy 29.01 m); made by
    ``tools/capytaine/make_box_database.py`` (its docstring and ``seahelm/data/rao/README.md``
    give the command, the versions and the mesh convergence). It is the hull the closed form of
    Jensen, Mansour & Olsen (2004) models exactly (C_b = 1): ``docs/guide/waves-motions.rst``
    compares the two.

    Returns
    -------
    pathlib.Path
        The file, for :func:`read_rao`.
    """
    from importlib import resources

    return Path(str(resources.files("seahelm").joinpath("data", "rao", BOX_BARGE_DATABASE)))


def wigley_database() -> Path:
    """The shipped capytaine NetCDF of the Wigley I hull (L 3 m, B 0.3 m, T 0.1875 m), zero speed.

    The analytic ship-like hull of Journée (1992, Delft report 909; C_b 0.561), capytaine
    3.0.0 (potential flow, 2,160 hull panels: 90 along the length and 12 over the draught per
    side, a lid against irregular frequencies), 27 wave frequencies 1.5-8.0 rad/s (λ/L 9.1 to
    0.32), wave directions 0-180° every 15°; mass ρ∇, KG 0.10 m (GM 0.0418 m), k_xx 0.12 m,
    k_yy 0.75 m (chosen, not Journée's). Made by ``tools/capytaine/make_wigley_database.py``
    (its docstring and ``seahelm/data/rao/README.md`` give the command, the versions and the
    mesh convergence); ``docs/guide/waves-motions.rst`` compares the closed form with it.

    Returns
    -------
    pathlib.Path
        The file, for :func:`read_rao`.
    """
    from importlib import resources

    return Path(str(resources.files("seahelm").joinpath("data", "rao", WIGLEY_DATABASE)))


def _fail(path: Any, reason: str, field: str | None = None) -> ParameterError:
    return ParameterError(f"{reason} (file {os.fspath(path)})", field=field)


def read_rao(path: str | os.PathLike[str]) -> RAO:
    """An RAO from a table (``.csv``), seahelm's NetCDF or capytaine's NetCDF (``.nc``).

    Parameters
    ----------
    path : str or path-like
        The file.

    Returns
    -------
    RAO

    Raises
    ------
    ParameterError
        If the file cannot be read or is invalid (naming the file and the key).
    """
    p = Path(path)
    if p.is_dir():
        raise _fail(p, "is a directory, not an RAO file", field="path")
    if not p.is_file():
        raise _fail(p, "no such file", field="path")
    if p.suffix.lower() == ".csv":
        return read_rao_table(p)
    import xarray as xr

    try:
        ds = xr.load_dataset(p)
    except Exception as exc:  # noqa: BLE001 - any reader error is a bad file
        raise _fail(p, f"not a NetCDF file ({exc})", field="path") from None
    if ds.attrs.get("format") == "seahelm-rao-1":
        return _from_seahelm_dataset(ds, p)
    return rao_from_capytaine_dataset(ds, source=os.fspath(p))


def _from_seahelm_dataset(ds: Any, path: Any) -> RAO:
    for name in ("amplitude", "phase"):
        if name not in ds:
            raise _fail(path, f"has no variable '{name}'", field=name)
    amp = ds["amplitude"].transpose("dof", "frequency", "heading").values
    ph = ds["phase"].transpose("dof", "frequency", "heading").values
    try:
        return RAO(ds["frequency"].values, ds["heading"].values,
                   tuple(str(d) for d in ds["dof"].values), amp * np.exp(1j * ph),
                   float(ds.attrs.get("speed", 0.0)), str(ds.attrs.get("provenance", "")))
    except ParameterError as exc:
        raise _fail(path, str(exc), field=exc.field) from None


def read_rao_table(path: str | os.PathLike[str]) -> RAO:
    """An RAO from the documented CSV table (module docstring).

    Parameters
    ----------
    path : str or path-like
        The CSV file.

    Returns
    -------
    RAO

    Raises
    ------
    ParameterError
        Naming the file and the column: a missing column or dof, a value that is not a
        finite number (a speed not >= 0), a grid point missing, a frequency repeated for one
        dof and heading, a file that is not text.
    """
    p = Path(path)
    try:
        with open(p, newline="", encoding="utf-8") as fh:
            rows = [r for r in csv.reader(line for line in fh
                                          if not line.lstrip().startswith("#"))
                    if r and any(c.strip() for c in r)]
    except (UnicodeDecodeError, csv.Error) as exc:  # a binary file named .csv
        raise _fail(p, f"is not a text CSV table ({exc})", field="path") from None
    if not rows:
        raise _fail(p, "is empty", field="path")
    head = [c.strip() for c in rows[0]]

    def column(*names: str) -> tuple[int, str]:
        for n in names:
            if n in head:
                return head.index(n), n
        raise _fail(p, f"has no column {' or '.join(names)}; columns: {', '.join(head)}",
                    field=names[0])

    i_dof, _ = column("dof")
    i_f, f_name = column("frequency", "period")
    i_h, h_name = column("heading_deg", "heading")
    i_a, a_name = column("amplitude", "amplitude_deg")
    i_p, p_name = column("phase_deg", "phase")
    i_s = head.index("speed") if "speed" in head else None
    data: dict[tuple[str, float, float], complex] = {}
    speeds = set()
    for n, row in enumerate(rows[1:], start=2):
        if len(row) != len(head):  # (an extra value shifts nothing, but is a broken line)
            raise _fail(p, f"line {n} has {len(row)} values, the header {len(head)}")
        dof = row[i_dof].strip()
        if dof not in DOFS:
            raise _fail(p, f"line {n}: dof '{dof}' is not one of {', '.join(DOFS)}", "dof")
        vals = []
        for idx, name in ((i_f, f_name), (i_h, h_name), (i_a, a_name), (i_p, p_name)):
            try:
                v = float(row[idx])
            except ValueError:
                v = math.nan
            if not math.isfinite(v):
                raise _fail(p, f"line {n}: '{row[idx].strip()}' is not a finite number", name)
            vals.append(v)
        f, h, a, ph = vals
        if f <= 0:
            raise _fail(p, f"line {n}: must be > 0, got {f!r}", f_name)
        if a < 0:
            raise _fail(p, f"line {n}: an amplitude must be >= 0 (the sign is the phase), got "
                        f"{a!r}", a_name)
        if not -180.0 <= (h if h_name == "heading_deg" else math.degrees(h)) <= 360.0:
            unit = "deg" if h_name == "heading_deg" else "rad"
            raise _fail(p, f"line {n}: a heading must be in [-180, 360] deg, got {h!r} {unit}",
                        h_name)
        if f_name == "period":
            f = 2.0 * math.pi / f
        if h_name == "heading_deg":
            h = math.radians(h)
        if a_name == "amplitude_deg":
            a = math.radians(a)
        if p_name == "phase_deg":
            ph = math.radians(ph)
        if i_s is not None:
            try:
                u = float(row[i_s])
            except ValueError:
                u = math.nan
            if not (math.isfinite(u) and u >= 0.0):
                raise _fail(p, f"line {n}: speed '{row[i_s].strip()}' is not a finite number "
                            ">= 0 [m/s]", "speed")
            speeds.add(u)
        key = (dof, round(f, 12), round(h, 12))
        if key in data:
            raise _fail(p, f"line {n}: {dof} at frequency {f:.6g} rad/s and heading "
                        f"{math.degrees(h):.6g} deg is given twice", f_name)
        data[key] = a * complex(math.cos(ph), math.sin(ph))
    if len(speeds) > 1:
        raise _fail(p, f"holds several speeds {sorted(speeds)}; one table is one speed", "speed")
    if not data:
        raise _fail(p, "has a header but no rows of values (one row per dof, frequency and "
                    "heading)", f_name)
    dofs = tuple(d for d in DOFS if any(k[0] == d for k in data))
    freqs = np.array(sorted({k[1] for k in data}))
    heads = np.array(sorted({k[2] for k in data}))
    values = np.empty((len(dofs), freqs.size, heads.size), dtype=complex)
    for i, d in enumerate(dofs):
        for j, f in enumerate(freqs):
            for m, h in enumerate(heads):
                try:
                    values[i, j, m] = data[(d, f, h)]
                except KeyError:
                    raise _fail(p, f"{d} has no value at frequency {f:.6g} rad/s, heading "
                                f"{math.degrees(h):.6g} deg (every dof needs the full grid)",
                                "dof") from None
    return RAO(freqs, heads, dofs, values, speeds.pop() if speeds else 0.0,
               f"RAO table {p.name}")


def write_rao_table(rao: RAO, path: str | os.PathLike[str], *, force: bool = False) -> Path:
    """Write an RAO as the documented CSV table (degrees for headings and phases).

    Parameters
    ----------
    rao : RAO
        The RAOs.
    path : str or path-like
        The CSV file (written atomically; an existing file that is not a seahelm table is
        replaced only with ``force``: :func:`seahelm.output_files.check_output`).
    force : bool, optional
        Replace an existing file that is not seahelm's (default False).

    Returns
    -------
    pathlib.Path
    """
    from ..output_files import write_output

    def write(tmp: str) -> None:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            fh.write(f"# seahelm RAO table: {rao.provenance}\n# speed {rao.speed:g} m/s; "
                     "heading 0 following, 180 head; heave up, roll starboard down, pitch bow "
                     "up\n")
            w = csv.writer(fh)
            w.writerow(["dof", "frequency", "heading_deg", "amplitude", "phase_deg", "speed"])
            for i, d in enumerate(rao.dofs):
                for j, f in enumerate(rao.frequency):
                    for m, h in enumerate(rao.heading):
                        v = rao.values[i, j, m]
                        w.writerow([d, repr(float(f)), repr(math.degrees(h)),
                                    repr(float(abs(v))), repr(math.degrees(float(np.angle(v)))),
                                    repr(rao.speed)])

    return write_output(path, write, "csv", force=force)


def _complex(ds: Any, name: str, source: str) -> Any:
    if name not in ds:
        raise ParameterError(f"has no variable '{name}' (file {source}; capytaine writes the "
                             "body's inertia_matrix and hydrostatic_stiffness when it has them)",
                             field=name)
    da = ds[name]
    if "complex" in da.dims:
        da = da.sel(complex="re") + 1j * da.sel(complex="im")
    return da


def read_capytaine(path: str | os.PathLike[str]) -> RAO:
    """Motion RAOs from a capytaine NetCDF file (module docstring).

    Parameters
    ----------
    path : str or path-like
        The NetCDF file.

    Returns
    -------
    RAO
    """
    import xarray as xr

    return rao_from_capytaine_dataset(xr.load_dataset(path), source=os.fspath(path))


def rao_from_capytaine_dataset(ds: Any, *, source: str = "<dataset>") -> RAO:
    """Motion RAOs from a capytaine dataset (complex or split into ``re``/``im``).

    Parameters
    ----------
    ds : xarray.Dataset
        capytaine's dataset (module docstring).
    source : str, optional
        Its name in messages.

    Returns
    -------
    RAO
        In seahelm's conventions, the dofs capytaine computed among :data:`DOFS`.

    Raises
    ------
    ParameterError
        If a variable is missing, the frequencies are not increasing, or values are NaN.
    """
    if "omega" not in ds.coords:
        raise ParameterError(f"has no coordinate 'omega' (file {source})", field="omega")
    A = _complex(ds, "added_mass", source).real
    B = _complex(ds, "radiation_damping", source).real
    F = _complex(ds, "diffraction_force", source) + _complex(ds, "Froude_Krylov_force", source)
    M = _complex(ds, "inertia_matrix", source).real
    C = _complex(ds, "hydrostatic_stiffness", source).real
    dofs = [str(d) for d in A["radiating_dof"].values]
    A = A.transpose("omega", "influenced_dof", "radiating_dof").sel(
        influenced_dof=dofs, radiating_dof=dofs).values
    B = B.transpose("omega", "influenced_dof", "radiating_dof").sel(
        influenced_dof=dofs, radiating_dof=dofs).values
    M = M.transpose("influenced_dof", "radiating_dof").sel(influenced_dof=dofs,
                                                          radiating_dof=dofs).values
    C = C.transpose("influenced_dof", "radiating_dof").sel(influenced_dof=dofs,
                                                          radiating_dof=dofs).values
    F = F.transpose("omega", "wave_direction", "influenced_dof").sel(influenced_dof=dofs)
    w = np.asarray(ds["omega"].values, dtype=float)
    beta = np.asarray(F["wave_direction"].values, dtype=float)
    F = F.values
    for name, arr in (("added_mass", A), ("radiation_damping", B), ("excitation", F)):
        if not np.all(np.isfinite(arr)):
            raise ParameterError(f"holds NaN (file {source})", field=name)
    if w.size > 1 and not np.all(np.diff(w) > 0):
        raise ParameterError(f"must be strictly increasing (file {source})", field="omega")
    Z = (-(w ** 2)[:, None, None] * (M[None] + A) - 1j * w[:, None, None] * B + C[None])
    X = np.linalg.solve(Z[:, None], F[..., None])[..., 0]  # (omega, direction, dof)
    X = np.conj(X)  # e^{-iωt} -> e^{+iωt}
    known = [(i, *_CAPY_DOFS[d]) for i, d in enumerate(dofs) if d in _CAPY_DOFS]
    if not known:
        raise ParameterError(f"has none of the rigid-body dofs {', '.join(_CAPY_DOFS)} (file "
                             f"{source})", field="radiating_dof")
    eps = np.mod(-beta, 2.0 * math.pi)
    signs = {n: s for _, n, s in known}
    version = str(ds.attrs.get("capytaine_version", "")).strip()
    text = f"capytaine {version} file {source}" if version else f"capytaine file {source}"
    tol = 1e-9
    if (np.all((eps > math.pi - tol) | (eps < tol)) and not np.all(eps < math.pi + tol)):
        # directions in [0, π] (towards port): the mirror image, ε -> 2π - ε, of a hull
        # symmetric about its centre plane, on which sway, roll and yaw change sign
        eps = np.mod(2.0 * math.pi - eps, 2.0 * math.pi)
        eps[eps > 2.0 * math.pi - tol] = 0.0
        signs = {n: (-s if n in ("sway", "roll", "yaw") else s) for n, s in signs.items()}
        text += " (wave directions 0..180 deg towards port mirrored to starboard)"
    order = np.argsort(eps)
    values = np.stack([signs[n] * X[:, order, i] for i, n, _ in known])
    speed = float(ds["forward_speed"].values) if "forward_speed" in ds else 0.0
    return RAO(w, eps[order], tuple(n for _, n, _ in known), values, speed, text)
