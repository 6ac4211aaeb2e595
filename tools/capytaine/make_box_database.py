"""Build seahelm's shipped capytaine database: a rectangular box barge at zero speed.

Needs capytaine (not a seahelm dependency, and never imported by seahelm or its tests); run it
in a separate environment::

    python3.11 -m venv /tmp/capyenv
    /tmp/capyenv/bin/pip install capytaine h5netcdf h5py
    /tmp/capyenv/bin/python tools/capytaine/make_box_database.py \
        --out src/seahelm/data/rao/box-barge-100x20x5-capytaine.nc
    /tmp/capyenv/bin/python tools/capytaine/make_box_database.py --convergence

Versions used for the shipped file: capytaine 3.0.0, numpy 2.4.6, xarray 2026.9.0, h5netcdf
1.8.2, h5py 3.16.0, Python 3.11.7 (the file's attribute ``capytaine_version`` records capytaine's).

The hull is the one the closed form of Jensen, Mansour & Olsen (2004) models exactly: a box of
length L = 100 m, breadth B = 20 m and draught T = 5 m (C_b = 1, so B_e = B), made of one
homogeneous solid of depth D = 10 m whose density makes it float at T (mass ρ L B T). Its centre
of gravity is then at the waterline (KG = D/2 = T), the rotation centre used for the rotations;
GM = KB + BM − KG = T/2 + B²/(12 T) − T = 4.167 m; the radii of gyration are those of the solid
box: k_xx = √((B² + D²)/12) = 6.455 m, k_yy = √((L² + D²)/12) = 29.01 m,
k_zz = √((L² + B²)/12) = 29.44 m. The hydrostatic stiffness is the box's exact one (ρ g L B,
ρ g ∇ GM, ρ g ∇ GM_L): capytaine's from the panels (printed) is 0.6 % low in roll on the 1.25 m
mesh, 2.5 % on a 2.5 m one (the midpoint rule's ∫y² dA over the bottom panels' width).

Wet surface: panels of at most ``--panel`` metres (default 1.25 m, the mesh of the shipped
file: 80 × 16 panels on the bottom, 4 over the draught, 2,048 hull panels), with a lid of
1,280 panels on the inner free surface to remove the irregular frequencies (the first for
this box is near 1.5 rad/s), and the two reflection symmetries. Frequencies ω = 0.2 … 1.6
rad/s in steps of 0.04 (36; the shortest wave, 24 m, has ~19 panels per wave length), wave
directions β = 0 … 180° every 15°
(capytaine's: β = 0 travels towards +x, the bow; β = 90° towards +y, port), deep water,
ρ = 1025 kg/m³, g = 9.80665 m/s² (seahelm's constants).

The file is capytaine's dataset (``assemble_dataset`` through ``fill_dataset``) saved with
``capytaine.export_dataset`` (``separate_complex_values``), plus capytaine's own motion RAO
(``capytaine.post_pro.rao``) as the variable ``RAO``, which seahelm's tests compare with the
RAO that seahelm's reader solves from the same matrices.

``--convergence`` solves a few frequencies and directions on meshes of 2.5, 1.67 and 1.25 m
and prints the change of |RAO| (heave, roll, pitch) of the coarser meshes from the 1.25 m one
(seahelm/data/rao/README.md has the table). Run time of the shipped file: about 5 minutes on
two shared cores.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np
import xarray as xr

import capytaine as cpt
from capytaine.post_pro.rao import rao as capytaine_rao

L, B, T, D = 100.0, 20.0, 5.0, 10.0
RHO, G = 1025.0, 9.80665
OMEGA = np.round(np.arange(0.2, 1.6 + 1e-9, 0.04), 10)
BETA = np.radians(np.arange(0.0, 180.0 + 1e-9, 15.0))
DOFS = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]


def box_body(panel: float) -> cpt.FloatingBody:
    """The box barge with panels of at most ``panel`` metres, its lid and its mass matrix."""
    res = (2 * int(np.ceil(L / panel / 2)), 2 * int(np.ceil(B / panel / 2)),
           int(np.ceil(T / panel)))
    hull = cpt.mesh_parallelepiped(size=(L, B, T), center=(0.0, 0.0, -T / 2), resolution=res,
                                   missing_sides={"top"}, reflection_symmetry=True,
                                   name="box_barge")
    lid = waterplane_lid(res[0], res[1])
    mass = RHO * L * B * T
    body = cpt.FloatingBody(mesh=hull, lid_mesh=lid,
                            dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
                            center_of_mass=(0.0, 0.0, 0.0), mass=mass, name="box_barge")
    inertia = body.compute_rigid_body_inertia(rho=RHO)  # for the coordinates; values replaced
    m = np.zeros((6, 6))
    m[0, 0] = m[1, 1] = m[2, 2] = mass
    m[3, 3] = mass * (B ** 2 + D ** 2) / 12.0
    m[4, 4] = mass * (L ** 2 + D ** 2) / 12.0
    m[5, 5] = mass * (L ** 2 + B ** 2) / 12.0
    body.inertia_matrix = inertia.copy(data=m)
    body.hydrostatic_stiffness = inertia.copy(data=box_stiffness())
    return body, res


def waterplane_lid(nx: int, ny: int) -> cpt.ReflectionSymmetricMesh:
    """The inner free surface z = 0 (L × B), panelled as the bottom, with the same symmetries.

    (``Mesh.generate_lid`` of capytaine 3.0 drops the candidate lid points that lie on the
    projected edges of the bottom panels: with a lid grid aligned with the hull's it returns
    no panel at all.)
    """
    x = np.linspace(-L / 2, 0.0, nx // 2 + 1)
    y = np.linspace(-B / 2, 0.0, ny // 2 + 1)
    vertices = np.array([(xi, yj, 0.0) for xi in x for yj in y])
    n = y.size
    faces = np.array([(i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j)
                      for i in range(x.size - 1) for j in range(y.size - 1)])
    quarter = cpt.Mesh(vertices, faces, name="quarter_lid")
    half = cpt.ReflectionSymmetricMesh(quarter, plane="yOz", name="half_lid")
    return cpt.ReflectionSymmetricMesh(half, plane="xOz", name="lid")


def box_stiffness() -> np.ndarray:
    """The box's hydrostatic stiffness about the centre of gravity (at the waterline)."""
    vol = L * B * T
    c = np.zeros((6, 6))
    c[2, 2] = RHO * G * L * B
    c[3, 3] = RHO * G * vol * (T / 2 + B ** 2 / (12 * T) - T)
    c[4, 4] = RHO * G * vol * (T / 2 + L ** 2 / (12 * T) - T)
    return c


def check_hydrostatics(body: cpt.FloatingBody) -> None:
    """capytaine's hydrostatic stiffness from the panels against the box's exact one."""
    c = body.compute_hydrostatic_stiffness(rho=RHO, g=G)
    exact = box_stiffness()
    for i, dof in ((2, "Heave"), (3, "Roll"), (4, "Pitch")):
        got = float(c.sel(influenced_dof=dof, radiating_dof=dof))
        print(f"  C[{dof}] from the panels {got:.6e}, exact {exact[i, i]:.6e} (used), "
              f"rel. diff {got / exact[i, i] - 1:+.1e}", file=sys.stderr)


def solve(panel: float, omega: np.ndarray, beta: np.ndarray) -> xr.Dataset:
    """capytaine's dataset for the box on the mesh of ``panel`` metres."""
    body, res = box_body(panel)
    print(f"mesh: panels <= {panel} m, resolution {res}, {body.mesh.nb_faces} hull panels, "
          f"{body.lid_mesh.nb_faces} lid panels", file=sys.stderr)
    check_hydrostatics(body)
    test_matrix = xr.Dataset(coords={"omega": omega, "wave_direction": beta,
                                     "radiating_dof": DOFS, "water_depth": [np.inf],
                                     "rho": [RHO], "g": [G]})
    solver = cpt.BEMSolver()
    t0 = time.perf_counter()
    ds = solver.fill_dataset(test_matrix, body, progress_bar=False)
    print(f"  solved in {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    ds["RAO"] = capytaine_rao(ds)
    ds.attrs["seahelm_hull"] = (
        f"rectangular box L {L:g} m, B {B:g} m, T {T:g} m, homogeneous solid of depth {D:g} m "
        f"(centre of gravity at the waterline, GM {T / 2 + B ** 2 / (12 * T) - T:.4g} m, "
        f"k_xx {np.sqrt((B ** 2 + D ** 2) / 12):.4g} m, k_yy {np.sqrt((L ** 2 + D ** 2) / 12):.4g}"
        f" m), panels <= {panel:g} m {res}, lid on the inner free surface")
    ds.attrs["seahelm_script"] = "tools/capytaine/make_box_database.py"
    return ds


def motion_amplitudes(ds: xr.Dataset) -> xr.DataArray:
    return abs(ds["RAO"].sel(radiating_dof=["Heave", "Roll", "Pitch"]))


def convergence() -> None:
    """|RAO| of heave, roll and pitch on three meshes at a few frequencies and directions."""
    omega = np.array([0.4, 0.7, 0.8, 0.9, 1.0, 1.2, 1.5])
    beta = np.radians([0.0, 45.0, 90.0, 135.0, 180.0])
    panels = (2.5, 2.5 / 1.5, 1.25)
    amps = [motion_amplitudes(solve(p, omega, beta)) for p in panels]
    print("change of |RAO| from the 1.25 m mesh, largest over the directions, relative to the "
          "largest |RAO| over the directions at that frequency:")
    print("omega  dof     " + "  ".join(f"{p:6.3g} m" for p in panels[:-1]))
    for w in omega:
        for dof in ("Heave", "Roll", "Pitch"):
            ref = amps[-1].sel(omega=w, radiating_dof=dof)
            scale = float(ref.max())
            cells = [f"{float(abs(a.sel(omega=w, radiating_dof=dof) - ref).max()) / scale:8.2%}"
                     for a in amps[:-1]]
            print(f"{w:5.2f}  {dof:6s} " + "  ".join(cells) + f"   (largest |RAO| {scale:.4g})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", help="NetCDF file to write")
    parser.add_argument("--panel", type=float, default=1.25, help="largest panel [m]")
    parser.add_argument("--convergence", action="store_true", help="mesh convergence study")
    args = parser.parse_args()
    if args.convergence:
        convergence()
    if args.out:
        ds = solve(args.panel, OMEGA, BETA)
        cpt.export_dataset(args.out, ds)
        print(f"wrote {args.out}", file=sys.stderr)
    if not (args.out or args.convergence):
        parser.error("give --out FILE and/or --convergence")


if __name__ == "__main__":
    main()
