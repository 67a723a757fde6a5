"""The parts the DOLFINx references share: fiberfold's mesh read from a VTU file, the model's
strain energies (docs/model.md, eqs. 1-3), Q2 displacements with 3 x 3 (x 3) Gauss points, plain
Newton (PETSc SNES with a direct MUMPS solve) at fixed steps in d, halved on failure, and the
wrinkle amplitude A = (max y - min y) / 2 of the top surface written per step as CSV. Run as a
script, it compares two such curves side by side (`compare`).
"""

import argparse
import base64
import csv
import re
import sys
import time

import numpy as np

# Table 1.
MATERIAL = [("mu_l", 10.0), ("K_l", 30.0), ("mu_s", 1.0), ("K_s", 3.0), ("phi_m", 0.9), ("phi_f", 0.1),
            ("mu_f", 10.0), ("lambda_f", 1.0)]


def arguments(description, mesh_help, d_max):
    """The options every reference takes: the mesh, the steps, the fibres and the material."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--mesh-vtu", required=True, help=mesh_help)
    parser.add_argument("--d-max", type=float, default=d_max)
    parser.add_argument("--d-first", type=float, default=0.005, help="first d (fiberfold's first state)")
    parser.add_argument("--step", type=float, default=0.005)
    parser.add_argument("--min-step", type=float, default=1e-5)
    parser.add_argument("--beta", type=float, default=0.0)
    for name, value in MATERIAL:
        parser.add_argument("--" + name, type=float, default=value)
    parser.add_argument("--out", required=True, help="CSV of d, A, newton_iterations, step_seconds")
    parser.add_argument("--quiet", action="store_true")
    return parser


def read_vtu(path, nodes, dimension):
    """Points (their first `dimension` coordinates) and `nodes`-node cells (VTK's node order) of
    an uncompressed binary VTU file."""
    text = open(path).read()
    if 'compressor="' in text.split(">", 2)[1]:
        sys.exit(f"{path}: compressed VTU is not read here")

    def array(name, dtype):
        match = re.search(r'<DataArray[^>]*Name="%s"[^>]*>\s*([^<]*)</DataArray>' % name, text)
        if match is None:
            sys.exit(f"{path}: no DataArray {name}")
        raw = base64.b64decode(match.group(1).strip())
        size = int(np.frombuffer(raw[:8], dtype=np.uint64)[0])
        return np.frombuffer(raw[8 : 8 + size], dtype=dtype)

    points = array("Points", np.float64).reshape(-1, 3)[:, :dimension]
    connectivity = array("connectivity", np.int64)
    offsets = array("offsets", np.int64)
    if not np.all(np.diff(np.concatenate([[0], offsets])) == nodes):
        sys.exit(f"{path}: the cells do not have {nodes} nodes")
    return points, connectivity.reshape(-1, nodes)


def solve(args, cell, nodes, families, conditions):
    """Follows the path of the model on the mesh of `args.mesh_vtu` (`nodes`-node `cell`s) with
    the fibre `families` and the Dirichlet `conditions`: `(component, where(x, box), value(d,
    box))`, `box` the mesh's `length_x`, `length_z` and `depth`. Writes `args.out`."""
    import dolfinx_solver  # noqa: F401  (loads the MPI and PETSc libraries the wheel carries)
    from mpi4py import MPI
    import basix.ufl
    import ufl
    from dolfinx import default_scalar_type, fem, mesh as dmesh
    from dolfinx.fem.petsc import NonlinearProblem
    from dolfinx.io.utils import cell_perm_vtk

    dimension = 2 if cell == "quadrilateral" else 3
    points, cells = read_vtu(args.mesh_vtu, nodes, dimension)
    cells = cells[:, cell_perm_vtk(getattr(dmesh.CellType, cell), nodes)]
    coordinate = basix.ufl.element("Lagrange", cell, 2, shape=(dimension,))
    domain = dmesh.create_mesh(MPI.COMM_SELF, cells, coordinate, points)
    box = {"length_x": points[:, 0].max(), "depth": -points[:, 1].min(),
           "length_z": points[:, 2].max() if dimension == 3 else 0.0}

    V = fem.functionspace(domain, ("Lagrange", 2, (dimension,)))
    u, v = fem.Function(V), ufl.TestFunction(V)

    # The layer (Y > 0) and the substrate, told apart at each cell's centre.
    Q = fem.functionspace(domain, ("DG", 0))
    in_layer = fem.Function(Q)
    centres = domain.geometry.x[domain.geometry.dofmaps[0]].mean(axis=1)
    for index, centre in enumerate(centres):
        in_layer.x.array[Q.dofmap.cell_dofs(index)] = 1.0 if centre[1] > 0.0 else 0.0

    # Strain energies (docs/model.md, eqs. 1-3), with the 3D invariants (F33 = 1 in the plane).
    F = ufl.Identity(dimension) + ufl.grad(u)
    J = ufl.det(F)
    I1 = ufl.tr(F.T * F) + (1.0 if dimension == 2 else 0.0)

    def neo_hookean(mu, K):
        return mu / 2 * (J ** (-2.0 / 3.0) * I1 - 3.0) + K / 2 * ufl.ln(J) ** 2

    def fibre(direction):
        stretched = F * ufl.as_vector(direction)
        return args.mu_f / 4 * (ufl.dot(stretched, stretched) - args.lambda_f**2) ** 2

    substrate = args.phi_m * neo_hookean(args.mu_s, args.K_s) + args.phi_f * sum(fibre(a) for a in families)
    energy = in_layer * neo_hookean(args.mu_l, args.K_l) + (1.0 - in_layer) * substrate
    dx = ufl.Measure("dx", domain=domain, metadata={"quadrature_degree": 5})  # 3 Gauss points a direction
    residual = ufl.derivative(energy * dx, u, v)

    tol = 1e-9 * max(box["length_x"], box["length_z"])
    bcs, loads = [], []
    for component, where, value in conditions:
        sub, _ = V.sub(component).collapse()
        dofs = fem.locate_dofs_geometrical((V.sub(component), sub), lambda x: where(x, box, tol))[0]
        constant = fem.Constant(domain, default_scalar_type(0.0))
        bcs.append(fem.dirichletbc(constant, dofs, V.sub(component)))
        loads.append((constant, value))

    # The top surface: in each column of nodes (the imperfection moves nodes along Y only), the
    # highest one.
    coordinates = V.tabulate_dof_coordinates()[:, :3]
    columns = {}
    for node, x in enumerate(coordinates):
        key = (round(x[0], 9), round(x[2], 9))
        if key not in columns or x[1] > coordinates[columns[key], 1]:
            columns[key] = node
    top = np.array(sorted(columns.values()))
    top_y = coordinates[top, 1]

    problem = NonlinearProblem(
        residual, u, bcs=bcs, petsc_options_prefix="reference_",
        petsc_options={"snes_type": "newtonls", "snes_linesearch_type": "basic", "snes_atol": 1e-10,
                       "snes_rtol": 1e-12, "snes_stol": 0.0, "snes_max_it": 25, "ksp_type": "preonly",
                       "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"},
    )
    snes = problem.solver

    d, step, start = 0.0, args.d_first, time.perf_counter()
    with open(args.out, "w") as out:
        out.write("d,A,newton_iterations,step_seconds\n")
        while d < args.d_max - 1e-12:
            target = min(d + step, args.d_max)
            saved = u.x.array.copy()
            for constant, value in loads:
                constant.value = value(target, box)
            began = time.perf_counter()
            problem.solve()
            if snes.getConvergedReason() <= 0:
                u.x.array[:] = saved
                step *= 0.5
                if step < args.min_step:
                    print(f"stopped at d = {d:.6f}: Newton failed at the smallest step", file=sys.stderr)
                    break
                continue
            d = target
            y = top_y + u.x.array[dimension * top + 1]
            amplitude = 0.5 * (y.max() - y.min())
            out.write(f"{d:.6f},{amplitude:.15e},{snes.getIterationNumber()},{time.perf_counter() - began:.4f}\n")
            out.flush()
            if not args.quiet:
                print(f"d = {d:.6f}  A = {amplitude:.6f}  {snes.getIterationNumber()} it")
            step = args.step
    print(f"time: {time.perf_counter() - start:.2f} s to d = {d:.6f}", file=sys.stderr)


def compare(ours, theirs, our_seconds, their_seconds):
    """The ratio of the wall times and the largest relative difference of A(d) over the d both
    curves (CSV with columns d and A) reached."""
    curves = [{round(float(r["d"]), 6): float(r["A"]) for r in csv.DictReader(open(f))} for f in (ours, theirs)]
    common = sorted(d for d in curves[0] if d in curves[1])
    print("ratio (FEniCSx / fiberfold): %.2fx" % (float(their_seconds) / float(our_seconds)))
    if common:
        worst = max(abs(curves[0][d] - curves[1][d]) / abs(curves[0][d]) for d in common)
        print("A(d): largest relative difference %.1e over %d common d up to %g" % (worst, len(common), common[-1]))
    else:
        print("A(d): no common d (see the logs)")


if __name__ == "__main__" and sys.argv[1:2] == ["compare"]:
    compare(*sys.argv[2:6])
