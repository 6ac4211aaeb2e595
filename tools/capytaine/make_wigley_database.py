"""Build seahelm's shipped capytaine database of a ship hull: the Wigley I model at zero speed.

Needs capytaine (not a seahelm dependency, and never imported by seahelm or its tests); run it
in a separate environment, as ``make_box_database.py``::

    python3.11 -m venv /tmp/capyenv
    /tmp/capyenv/bin/pip install capytaine h5netcdf h5py
    /tmp/capyenv/bin/python tools/capytaine/make_wigley_database.py \
        --out src/seahelm/data/rao/wigley-i-3m-capytaine.nc
    /tmp/capyenv/bin/python tools/capytaine/make_wigley_database.py --convergence

Versions used for the shipped file: capytaine 3.0.0, numpy 2.4.6, xarray 2026.9.0, h5netcdf
1.8.2, h5py 3.16.0, Python 3.11.7 (the file's attribute ``capytaine_version`` records capytaine's).

The hull is the Wigley I form of the Delft series (Journée 1992, "Experiments and calculations
on four Wigley hullforms", Delft University of Technology, Ship Hydromechanics Laboratory,
report 909): L = 3 m, B = 0.3 m, T = 0.1875 m, half-breadth

    y = (B/2) [(1 − ζ²)(1 − ξ²)(1 + 0.2 ξ²) + ζ² (1 − ζ⁸)(1 − ξ²)⁴],  ξ = 2x/L, ζ = z/T,

whose block coefficient is 0.5607 (quadrature here; Journée's 0.561), waterplane coefficient
0.6933, KB 0.1069 m, BM 0.0349 m, BM_L 3.098 m (all by quadrature of the formula). The mass is
ρ∇. The mass distribution is **chosen, not Journée's** (his report was not available to us):
KG = 0.10 m (GM = 0.0418 m), radii of gyration k_xx = 0.4 B = 0.12 m,
k_yy = k_zz = 0.25 L = 0.75 m; heave and pitch at zero speed do not depend on KG or k_xx, the
roll does. The hydrostatic stiffness is the formula's (ρ g A_wp, ρ g ∇ GM, ρ g (I_L − ∇ BG))
about the centre of gravity; capytaine's from the panels is printed for comparison.

Wet surface: ``--nx`` panels along the length and ``--nz`` over the draught on each side
(default 90 × 12, the shipped file's: 2,160 hull panels, the largest 3.3 cm long and 1.6 cm
high; the shortest wave, 0.96 m, has 29 panels per wave length), uniform in ξ and ζ, both
reflection symmetries, and a lid on the inner free surface (``--nx`` × 4 panels per side)
against the irregular frequencies. The panels' volume is 0.5 % below the formula's (flat
panels on a curved hull), their roll stiffness 1.8 % (printed). Frequencies ω = 1.5 … 8.0 rad/s in steps of 0.25 (27: λ/L from 9.1 to 0.32;
ω√(L/g) from 0.83 to 4.4), wave directions β = 0 … 180° every 15° (capytaine's: 0 towards
the bow, 90° towards port), deep water, ρ = 1025 kg/m³, g = 9.80665 m/s².

The file is capytaine's dataset saved with ``capytaine.export_dataset``
(``separate_complex_values``), plus capytaine's own motion RAO (``capytaine.post_pro.rao``)
as the variable ``RAO``.

``--convergence`` solves a few frequencies and directions on 30 × 4, 60 × 8 and 90 × 12 panels
per side and prints the change of |RAO| (heave, roll, pitch) and of the roll excitation
moment of the coarser meshes from the 90 × 12 one (seahelm/data/rao/README.md has the table).
Run time: the shipped file about 2 minutes, the convergence study about 1 minute, on two
shared cores.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np
import xarray as xr
from scipy import integrate

import capytaine as cpt
from capytaine.post_pro.rao import rao as capytaine_rao

L, B, T = 3.0, 0.3, 0.1875
KG, KXX, KYY, KZZ = 0.10, 0.4 * 0.3, 0.25 * 3.0, 0.25 * 3.0
RHO, G = 1025.0, 9.80665
OMEGA = np.round(np.arange(1.5, 8.0 + 1e-9, 0.25), 10)
BETA = np.radians(np.arange(0.0, 180.0 + 1e-9, 15.0))
DOFS = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]


def eta(xi, zeta):
    """Half-breadth / (B/2) of Wigley I at ξ = 2x/L, ζ = z/T (ζ in [−1, 0])."""
    return ((1 - zeta ** 2) * (1 - xi ** 2) * (1 + 0.2 * xi ** 2)
            + zeta ** 2 * (1 - zeta ** 8) * (1 - xi ** 2) ** 4)


def hydrostatics() -> dict[str, float]:
    """Volume, KB, waterplane area and moments of the formula (numerical quadrature)."""
    q = lambda f: integrate.dblquad(f, 0.0, 1.0, 0.0, 1.0, epsabs=1e-13, epsrel=1e-12)[0]
    cb = q(lambda z, x: eta(x, -z))
    vol = cb * L * B * T
    zb = -q(lambda z, x: z * eta(x, -z)) * L * B * T * T / vol
    w = lambda f: integrate.quad(f, 0.0, 1.0, epsabs=1e-13, epsrel=1e-12)[0]
    awp = w(lambda x: eta(x, 0.0)) * L * B
    it = B ** 3 * L / 12.0 * w(lambda x: eta(x, 0.0) ** 3)
    il = B * L ** 3 / 4.0 * w(lambda x: x * x * eta(x, 0.0))
    return {"cb": cb, "volume": vol, "kb": T + zb, "awp": awp, "it": it, "il": il,
            "bm": it / vol, "bml": il / vol, "gm": T + zb + it / vol - KG}


def stiffness(h: dict[str, float]) -> np.ndarray:
    """Hydrostatic stiffness about the centre of gravity (heave, roll, pitch)."""
    c = np.zeros((6, 6))
    c[2, 2] = RHO * G * h["awp"]
    c[3, 3] = RHO * G * h["volume"] * h["gm"]
    c[4, 4] = RHO * G * h["volume"] * (h["kb"] + h["bml"] - KG)
    return c


def quarter(nx: int, nz: int) -> cpt.Mesh:
    """The hull for x <= 0, y <= 0 (nx/2 × nz quads), normals into the water."""
    x = np.linspace(-L / 2, 0.0, nx // 2 + 1)
    z = np.linspace(-T, 0.0, nz + 1)
    vertices = np.array([(xi, -B / 2 * eta(2 * xi / L, zj / T), zj) for xi in x for zj in z])
    n = z.size
    faces = np.array([(i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1)
                      for i in range(x.size - 1) for j in range(z.size - 1)])
    return cpt.Mesh(vertices, faces, name="quarter_hull")


def quarter_lid(nx: int, ny: int) -> cpt.Mesh:
    """The inner free surface z = 0 for x <= 0, y <= 0, between the waterline and y = 0."""
    x = np.linspace(-L / 2, 0.0, nx // 2 + 1)
    s = np.linspace(1.0, 0.0, ny + 1)
    vertices = np.array([(xi, -B / 2 * eta(2 * xi / L, 0.0) * sj, 0.0) for xi in x for sj in s])
    n = s.size
    faces = np.array([(i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j)
                      for i in range(x.size - 1) for j in range(s.size - 1)])
    return cpt.Mesh(vertices, faces, name="quarter_lid")


def symmetric(mesh: cpt.Mesh, name: str) -> cpt.ReflectionSymmetricMesh:
    half = cpt.ReflectionSymmetricMesh(mesh, plane="yOz", name=f"half_{name}")
    return cpt.ReflectionSymmetricMesh(half, plane="xOz", name=name)


def wigley_body(nx: int, nz: int) -> cpt.FloatingBody:
    """Wigley I with nx × nz panels per side, its lid and its mass matrix."""
    h = hydrostatics()
    hull = symmetric(quarter(nx, nz), "wigley_hull")
    lid = symmetric(quarter_lid(nx, 4), "lid")
    zg = KG - T
    mass = RHO * h["volume"]
    body = cpt.FloatingBody(mesh=hull, lid_mesh=lid,
                            dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, zg)),
                            center_of_mass=(0.0, 0.0, zg), mass=mass, name="wigley_i")
    inertia = body.compute_rigid_body_inertia(rho=RHO)  # for the coordinates; values replaced
    m = np.diag([mass, mass, mass, mass * KXX ** 2, mass * KYY ** 2, mass * KZZ ** 2])
    body.inertia_matrix = inertia.copy(data=m)
    body.hydrostatic_stiffness = inertia.copy(data=stiffness(h))
    return body, h


def check_hydrostatics(body: cpt.FloatingBody, h: dict[str, float]) -> None:
    """The panels' volume and stiffness against the formula's."""
    print(f"  volume from the panels {body.mesh.volume:.6e} m3, formula {h['volume']:.6e} "
          f"(C_b {h['cb']:.4f}, KB {h['kb']:.4f} m, BM {h['bm']:.4f} m, GM {h['gm']:.4f} m)",
          file=sys.stderr)
    c = body.compute_hydrostatic_stiffness(rho=RHO, g=G)
    exact = stiffness(h)
    for i, dof in ((2, "Heave"), (3, "Roll"), (4, "Pitch")):
        got = float(c.sel(influenced_dof=dof, radiating_dof=dof))
        print(f"  C[{dof}] from the panels {got:.6e}, formula {exact[i, i]:.6e} (used), "
              f"rel. diff {got / exact[i, i] - 1:+.1e}", file=sys.stderr)


def solve(nx: int, nz: int, omega: np.ndarray, beta: np.ndarray) -> xr.Dataset:
    """capytaine's dataset for Wigley I on nx × nz panels per side."""
    body, h = wigley_body(nx, nz)
    print(f"mesh: {nx} x {nz} panels per side, {body.mesh.nb_faces} hull panels, "
          f"{body.lid_mesh.nb_faces} lid panels", file=sys.stderr)
    check_hydrostatics(body, h)
    test_matrix = xr.Dataset(coords={"omega": omega, "wave_direction": beta,
                                     "radiating_dof": DOFS, "water_depth": [np.inf],
                                     "rho": [RHO], "g": [G]})
    t0 = time.perf_counter()
    ds = cpt.BEMSolver().fill_dataset(test_matrix, body, progress_bar=False)
    print(f"  solved in {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    ds["RAO"] = capytaine_rao(ds)
    ds.attrs["seahelm_hull"] = (
        f"Wigley I (Journee 1992): L {L:g} m, B {B:g} m, T {T:g} m, C_b {h['cb']:.4f}, "
        f"KG {KG:g} m (chosen), GM {h['gm']:.4g} m, k_xx {KXX:.4g} m, k_yy {KYY:.4g} m, "
        f"k_zz {KZZ:.4g} m; {nx} x {nz} panels per side, lid on the inner free surface")
    ds.attrs["seahelm_script"] = "tools/capytaine/make_wigley_database.py"
    return ds


def convergence() -> None:
    """|RAO| and the roll excitation on three meshes at a few frequencies and directions."""
    omega = np.array([2.0, 3.0, 4.0, 5.0, 6.0, 7.5])
    beta = np.radians([0.0, 45.0, 90.0, 135.0, 180.0])
    meshes = ((30, 4), (60, 8), (90, 12))
    sols = [solve(nx, nz, omega, beta) for nx, nz in meshes]
    quantities = []
    for ds in sols:
        amp = abs(ds["RAO"].sel(radiating_dof=["Heave", "Roll", "Pitch"]))
        exc = abs(ds["excitation_force"].sel(influenced_dof="Roll"))
        quantities.append((amp, exc))
    print("change from the 90 x 12 mesh, largest over the directions, relative to the largest "
          "value over the directions at that frequency:")
    print("omega  quantity     30x4      60x8   (largest, 90x12)")
    for w in omega:
        for label, pick in (("heave", lambda q: q[0].sel(radiating_dof="Heave")),
                            ("roll", lambda q: q[0].sel(radiating_dof="Roll")),
                            ("pitch", lambda q: q[0].sel(radiating_dof="Pitch")),
                            ("roll exc.", lambda q: q[1])):
            ref = pick(quantities[-1]).sel(omega=w)
            scale = float(ref.max())
            cells = [f"{float(abs(pick(q).sel(omega=w) - ref).max()) / scale:8.2%}"
                     for q in quantities[:-1]]
            print(f"{w:5.2f}  {label:10s} " + "  ".join(cells) + f"   ({scale:.4g})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", help="NetCDF file to write")
    parser.add_argument("--nx", type=int, default=90, help="panels along the length per side")
    parser.add_argument("--nz", type=int, default=12, help="panels over the draught")
    parser.add_argument("--convergence", action="store_true", help="mesh convergence study")
    args = parser.parse_args()
    if args.nx % 2:
        parser.error("--nx must be even (fore-aft symmetry)")
    if args.convergence:
        convergence()
    if args.out:
        ds = solve(args.nx, args.nz, OMEGA, BETA)
        cpt.export_dataset(args.out, ds)
        print(f"wrote {args.out}", file=sys.stderr)
    if not (args.out or args.convergence):
        parser.error("give --out FILE and/or --convergence")


if __name__ == "__main__":
    main()
