"""RAOs: the closed-form heave/pitch of Jensen, Mansour & Olsen (2004) against their amplitude
formulas typed separately, the long-wave limits (the ship follows the surface: signs and
phases), a regular wave's response |H| a cos(ω_e t + ϕ + arg H), the CSV table and the NetCDF
round trips, capytaine's NetCDF layout (a synthetic file with known matrices), bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.constants import GRAVITY
from seahelm.environment.rao import RAO, closed_form_rao, imo_roll_period
from seahelm.environment.rao_io import read_rao, read_rao_table, write_rao_table
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.ships import get_ship
from seahelm.vessels.particulars import Particulars

P = Particulars(length=175.0, beam=25.4, draft=8.5, block_coefficient=0.5617)
G = GRAVITY


def jensen_amplitudes(w, beta, U, L, B0, T, cb, smith="k"):
    """Φ_w = ηF, Φ_θ = ηG of Jensen et al. (2004), scalar amplitude form, B = C_b B0; the Smith
    factor κ = exp(−kT) (``smith="k"``) or exp(−k_e T) (``"k_e"``, MSS's transcription)."""
    B = cb * B0
    k = w * w / G
    Fn = U / math.sqrt(G * L)
    alpha = 1 - Fn * math.sqrt(k * L) * math.cos(beta)
    A = 2 * math.sin(0.5 * k * B * alpha ** 2) * math.exp(-k * T * alpha ** 2)
    f = math.sqrt((1 - k * T) ** 2 + (A ** 2 / (k * B * alpha ** 3)) ** 2)
    ke = abs(k * math.cos(beta))
    kappa = math.exp(-(ke if smith == "k_e" else k) * T)
    F = kappa * f * 2 / (ke * L) * math.sin(ke * L / 2)
    Gp = kappa * f * 24 / (ke ** 2 * L ** 3) * (math.sin(ke * L / 2)
                                                - ke * L / 2 * math.cos(ke * L / 2))
    eta = 1 / math.sqrt((1 - 2 * k * T * alpha ** 2) ** 2 + (A ** 2 / (k * B * alpha ** 2)) ** 2)
    return eta * abs(F), eta * abs(Gp)


@pytest.mark.parametrize("smith", ["k", "k_e"])
@pytest.mark.parametrize("U", [0.0, 5.0, 8.0])
@pytest.mark.parametrize("beta_deg", [60.0, 120.0, 150.0, 180.0])
def test_heave_and_pitch_amplitudes_are_jensens(U, beta_deg, smith):
    w = np.linspace(0.2, 1.5, 27)
    rao = closed_form_rao(P, U, frequency=w, heading=[math.radians(beta_deg)], smith=smith)
    for i, wi in enumerate(w):
        heave, pitch = jensen_amplitudes(wi, math.radians(beta_deg), U, 175.0, 25.4, 8.5, 0.5617,
                                         smith)
        assert rao.amplitude("heave")[i, 0] == pytest.approx(heave, rel=1e-12)
        assert rao.amplitude("pitch")[i, 0] == pytest.approx(pitch, rel=1e-12)


@pytest.mark.parametrize("eps_deg", [0.0, 30.0, 90.0, 150.0, 180.0, 240.0])
def test_long_waves_the_ship_follows_the_surface(eps_deg):
    """ω → 0: heave = ζ(0), pitch = ∂ζ/∂x (bow up), roll = −∂ζ/∂y (starboard down)."""
    eps = math.radians(eps_deg)
    w, a, U = 0.02, 1.3, 6.0
    rao = closed_form_rao(P, U, frequency=[0.01, w, 0.03],
                          heading=np.radians(np.arange(0, 360, 30)),
                          roll_period=5.0)
    k = w * w / G
    we = w - w * w * U * math.cos(eps) / G
    t = np.linspace(0.0, 2 * math.pi / abs(we), 50)
    # ζ(x, y, t) = a cos(ω_e t − k x cos ε − k y sin ε) in the ship's frame (x fwd, y stbd)
    zeta = a * np.cos(we * t)
    slope_x = a * k * math.cos(eps) * np.sin(we * t)
    slope_y = a * k * math.sin(eps) * np.sin(we * t)
    heave = rao.regular_wave_response("heave", a, w, eps, t)
    pitch = rao.regular_wave_response("pitch", a, w, eps, t)
    roll = rao.regular_wave_response("roll", a, w, eps, t)
    np.testing.assert_allclose(heave, zeta, atol=2e-3 * a)
    np.testing.assert_allclose(pitch, slope_x, atol=2e-3 * a * k)
    np.testing.assert_allclose(roll, -slope_y, atol=5e-3 * a * k)  # lag 2 zeta w_e/w_phi


def test_a_regular_wave_gives_the_rao_times_the_amplitude_with_its_phase():
    rao = closed_form_rao(P, 7.0, metacentric_height=0.3)
    a, w, eps, phase = 2.0, rao.frequency[40], rao.heading[27], 0.7
    we = w - w * w * 7.0 * math.cos(eps) / G
    t = np.linspace(0.0, 120.0, 1001)
    for dof in rao.dofs:
        H = rao.values[rao.dofs.index(dof), 40, 27]
        expected = a * abs(H) * np.cos(we * t + phase + np.angle(H))
        got = rao.regular_wave_response(dof, a, w, eps, t, phase=phase)
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-9 * a * abs(H) + 1e-15)


def test_interpolation_mirrors_port_and_starboard_and_warns_outside():
    rao = closed_form_rao(P, 5.0, roll_period=25.0)
    e = math.radians(60.0)
    for dof, sign in (("heave", 1), ("pitch", 1), ("roll", -1)):
        assert rao(dof, 0.6, 2 * math.pi - e) == pytest.approx(sign * rao(dof, 0.6, e))
    with pytest.warns(ValidityRangeWarning, match="outside the RAO table"):
        rao("heave", 3.0, e)
    with pytest.raises(ParameterError, match="not in this RAO"):
        rao.amplitude("yaw")


def test_closed_form_inputs_and_the_roll_period():
    # IMO A.749(18): T = 2 C B / sqrt(GM), C = 0.373 + 0.023 B/T - 0.043 L/100
    c = 0.373 + 0.023 * 25.4 / 8.5 - 0.043 * 1.75
    assert imo_roll_period(175.0, 25.4, 8.5, 1.0) == pytest.approx(2 * c * 25.4)
    assert closed_form_rao(P, 5.0).dofs == ("heave", "pitch")
    assert closed_form_rao(get_ship("son-nomoto-container"), 5.0,
                           metacentric_height=0.3).dofs == ("heave", "roll", "pitch")
    with pytest.raises(ParameterError, match="no particulars"):
        closed_form_rao(get_ship("mariner-nomoto1").replace(particulars=None), 5.0)
    with pytest.raises(ParameterError, match="roll_damping"):
        closed_form_rao(P, 5.0, roll_period=20.0, roll_damping=0.0)
    with pytest.raises(ParameterError, match="speed"):
        closed_form_rao(P, -1.0)
    with pytest.warns(ValidityRangeWarning, match="Jensen"):
        closed_form_rao(P, 25.0)


def test_table_and_netcdf_round_trips(tmp_path):
    rao = closed_form_rao(P, 6.0, metacentric_height=0.5, frequency=np.linspace(0.2, 1.2, 6),
                          heading=np.radians([0, 90, 180]))
    back = read_rao(write_rao_table(rao, tmp_path / "r.csv"))
    assert back.dofs == rao.dofs and back.speed == 6.0
    np.testing.assert_allclose(back.values, rao.values, rtol=1e-12, atol=1e-15)
    rao.to_xarray().to_netcdf(tmp_path / "r.nc")
    back = read_rao(tmp_path / "r.nc")
    np.testing.assert_allclose(back.values, rao.values, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("text, match", [
    ("dof,frequency,heading_deg,amplitude\nheave,0.2,0,1\n", "no column phase_deg or phase"),
    ("dof,frequency,heading_deg,amplitude,phase_deg\nbob,0.2,0,1,0\n", "dof 'bob'"),
    ("dof,frequency,heading_deg,amplitude,phase_deg\nheave,0.2,0,nan,0\n", "not a finite"),
    ("dof,frequency,heading_deg,amplitude,phase_deg\nheave,0.2,0,1,0\nheave,0.2,0,1,0\n",
     "given twice"),
    ("dof,frequency,heading_deg,amplitude,phase_deg\nheave,0.2,0,1,0\nheave,0.4,0,1,0\n"
     "roll,0.2,0,1,0\n", "roll has no value at frequency 0.4"),
    ("dof,frequency,heading_deg,amplitude,phase_deg\nheave,-0.2,0,1,0\n", "must be > 0"),
    # (a speed that is no number was a bare ValueError naming neither file nor column; NaN
    # speeds were 'several speeds [nan, nan]')
    ("dof,frequency,heading_deg,amplitude,phase_deg,speed\nheave,0.2,0,1,0,fast\n",
     "`speed` line 2: speed 'fast' is not a finite number >= 0"),
    ("dof,frequency,heading_deg,amplitude,phase_deg,speed\nheave,0.2,0,1,0,nan\n"
     "heave,0.4,0,1,0,nan\n", "`speed` line 2: speed 'nan'"),
    ("dof,frequency,heading_deg,amplitude,phase_deg,speed\nheave,0.2,0,1,0,-1\n",
     "speed '-1' is not"),
])
def test_bad_tables_name_the_file_and_the_column(tmp_path, text, match):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ParameterError, match=match) as info:
        read_rao_table(path)
    assert "bad.csv" in str(info.value)


def test_a_binary_file_or_a_directory_is_a_parameter_error_naming_it(tmp_path):
    """(A binary file named .csv was a bare UnicodeDecodeError, naming neither the file nor
    the key; a directory was 'no such file'.)"""
    path = tmp_path / "binary.csv"
    path.write_bytes(bytes(range(256)) * 4)
    with pytest.raises(ParameterError, match=r"`path` is not a text CSV table .*binary\.csv"):
        read_rao(path)
    with pytest.raises(ParameterError, match=r"`path` is a directory, not an RAO file"):
        read_rao(tmp_path)


def test_rao_validates_its_grid():
    with pytest.raises(ParameterError, match="strictly increasing"):
        RAO(np.array([0.5, 0.4]), np.array([0.0]), ("heave",), np.ones((1, 2, 1)))
    with pytest.raises(ParameterError, match="finite"):
        RAO(np.array([0.4, 0.5]), np.array([0.0]), ("heave",), np.full((1, 2, 1), np.nan))


def _capytaine_file(path, beta=(0.0, math.pi / 2, math.pi)):
    """A capytaine-layout dataset (separate_complex_values) of a diagonal heave-roll-pitch body."""
    import xarray as xr

    dofs = ["Heave", "Roll", "Pitch"]
    w = np.array([0.3, 0.5, 0.8])
    beta = np.array(beta)
    M = np.diag([2e7, 3e9, 4e10])
    C = np.diag([4e7, 1.5e8, 5e10])
    A = np.stack([np.diag([1.5e7, 5e8, 3e10]) * (1 + 0.1 * x) for x in w])
    B = np.stack([np.diag([2e6, 1e7, 4e9]) * (1 + x) for x in w])
    F = (np.arange(27).reshape(3, 3, 3) + 1.0) * 1e6 * np.exp(1j * np.linspace(0, 2, 27)
                                                            ).reshape(3, 3, 3)
    cplx = {"complex": ["re", "im"]}

    def split(z):
        return np.stack([z.real, z.imag], axis=-1)

    ds = xr.Dataset({
        "added_mass": (("omega", "radiating_dof", "influenced_dof"), A.transpose(0, 2, 1)),
        "radiation_damping": (("omega", "radiating_dof", "influenced_dof"), B.transpose(0, 2, 1)),
        "diffraction_force": (("omega", "wave_direction", "influenced_dof", "complex"),
                              split(0.25 * F)),
        "Froude_Krylov_force": (("omega", "wave_direction", "influenced_dof", "complex"),
                                split(0.75 * F)),
        "inertia_matrix": (("influenced_dof", "radiating_dof"), M),
        "hydrostatic_stiffness": (("influenced_dof", "radiating_dof"), C),
    }, coords={"omega": w, "wave_direction": beta, "radiating_dof": dofs,
               "influenced_dof": dofs, **cplx})
    ds.to_netcdf(path)
    return w, beta, M, C, A, B, F


@pytest.mark.parametrize("beta, eps, mirrored", [
    # waves towards port (capytaine's usual 0..180 deg): mirrored to eps = beta, roll flips
    ((0.0, math.pi / 2, math.pi), (0.0, math.pi / 2, math.pi), True),
    # waves towards starboard: eps = -beta (mod 2 pi) already in [0, pi]
    ((0.0, -math.pi / 2, -math.pi), (0.0, math.pi / 2, math.pi), False),
    # a full circle: eps = -beta mod 2 pi, no mirror
    ((0.0, math.pi / 2, -math.pi / 2), (0.0, 1.5 * math.pi, math.pi / 2), False)])
def test_capytaine_netcdf(tmp_path, beta, eps, mirrored):
    w, beta, M, C, A, B, F = _capytaine_file(tmp_path / "capy.nc", beta)
    rao = read_rao(tmp_path / "capy.nc")
    assert rao.dofs == ("heave", "roll", "pitch") and rao.speed == 0.0
    assert ("mirrored" in rao.provenance) == mirrored
    np.testing.assert_allclose(rao.heading, sorted(eps), atol=1e-12)
    for i, (name, sign) in enumerate((("heave", 1), ("roll", 1), ("pitch", -1))):
        if mirrored and name == "roll":
            sign = -1
        for j in range(3):
            Z = -w[j] ** 2 * (M[i, i] + A[j, i, i]) - 1j * w[j] * B[j, i, i] + C[i, i]
            for b, e in enumerate(eps):
                expected = sign * np.conj(F[j, b, i] / Z)
                got = rao.values[i, j, int(np.argmin(np.abs(rao.heading - e)))]
                assert got == pytest.approx(expected, rel=1e-12)


def test_capytaine_file_without_the_inertia_matrix(tmp_path):
    import xarray as xr

    _capytaine_file(tmp_path / "capy.nc")
    ds = xr.load_dataset(tmp_path / "capy.nc").drop_vars("inertia_matrix")
    ds.to_netcdf(tmp_path / "bad.nc")
    with pytest.raises(ParameterError, match="inertia_matrix") as info:
        read_rao(tmp_path / "bad.nc")
    assert info.value.field == "inertia_matrix"


def test_the_particulars_gm_gives_the_roll_rao():
    """A ship whose particulars know GM (the container ship's 0.3 m) gets the roll RAO without
    an argument, equal to the one with GM given; an explicit GM or roll period wins; GM is a
    length (scaled with the ship) and must be > 0."""
    import dataclasses

    ship = get_ship("son-nomoto-container")
    assert ship.particulars.metacentric_height == 0.3
    own = closed_form_rao(ship, 7.0)
    given = closed_form_rao(dataclasses.replace(ship.particulars, metacentric_height=None), 7.0,
                            metacentric_height=0.3)
    assert own.dofs == given.dofs == ("heave", "roll", "pitch")
    np.testing.assert_array_equal(own.values, given.values)
    other = closed_form_rao(ship, 7.0, metacentric_height=1.2)
    period = imo_roll_period(175.0, 25.4, 8.5, 1.2)
    assert f"T_phi {period:.4g} s" in other.provenance
    assert closed_form_rao(get_ship("kvlcc2-full"), 7.0).dofs == ("heave", "pitch")
    assert ship.particulars.scaled(0.5).metacentric_height == pytest.approx(0.15)
    with pytest.raises(ParameterError, match="metacentric_height"):
        dataclasses.replace(ship.particulars, metacentric_height=-0.1)
