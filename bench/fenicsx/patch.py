"""The wrinkle amplitude A(d) of a patch of fiberfold's model in three dimensions, solved with
FEniCSx (DOLFINx) on fiberfold's mesh.

A general-purpose finite-element code of the same discretisation, to time fiberfold against and
to check it by: the layer and the fibre-reinforced substrate of docs/model.md (sections 3 and 8)
with the fibre families along (cos beta cos psi, +-sin beta, cos beta sin psi), Q2 displacements
on 27-node hexahedra, 3 x 3 x 3 Gauss points, and plain Newton (PETSc SNES with a direct MUMPS
solve) at fixed steps in d, halved on failure. The patch's sides are symmetry planes: u_X = 0 on
X = 0 and -d Lx on X = Lx, u_Z = 0 on Z = 0 and -R d Lz on Z = Lz, u_Y = 0 on the bottom.

The mesh, with its imperfection, is read from `state.vtu` of a `fiberfold pattern --sides
symmetry --follow-to D` run (its points are the reference coordinates, imperfection included),
so that both programs solve on the same nodes. The material is given here (Table 1 by default).
Writes d, A, Newton iterations and the seconds of each step as CSV.
"""

import argparse
import base64
import re
import sys
import time

import numpy as np


def read_vtu(path):
    """Points and 27-node cells (VTK's node order) of an uncompressed binary VTU file."""
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

    points = array("Points", np.float64).reshape(-1, 3)
    connectivity = array("connectivity", np.int64)
    offsets = array("offsets", np.int64)
    if not np.all(np.diff(np.concatenate([[0], offsets])) == 27):
        sys.exit(f"{path}: the cells are not 27-node hexahedra")
    return points, connectivity.reshape(-1, 27)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh-vtu", required=True, help="state.vtu of a fiberfold pattern run, symmetry sides")
    parser.add_argument("--d-max", type=float, default=0.12)
    parser.add_argument("--d-first", type=float, default=0.005, help="first d (fiberfold's --d-start)")
    parser.add_argument("--step", type=float, default=0.005)
    parser.add_argument("--min-step", type=float, default=1e-5)
    parser.add_argument("--biaxial", type=float, default=1.0, help="R = d_3 / d")
    parser.add_argument("--beta", type=float, default=0.0)
    parser.add_argument("--psi", type=float, default=0.0)
    for name, value in [("mu_l", 10.0), ("K_l", 30.0), ("mu_s", 1.0), ("K_s", 3.0), ("phi_m", 0.9),
                        ("phi_f", 0.1), ("mu_f", 10.0), ("lambda_f", 1.0)]:
        parser.add_argument("--" + name, type=float, default=value)
    parser.add_argument("--out", required=True, help="CSV of d, A, newton_iterations, step_seconds")
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args()

    import dolfinx_solver  # noqa: F401  (loads the MPI and PETSc libraries the wheel carries)
    from mpi4py import MPI
    import basix.ufl
    import ufl
    from dolfinx import default_scalar_type, fem, mesh as dmesh
    from dolfinx.fem.petsc import NonlinearProblem
    from dolfinx.io.utils import cell_perm_vtk

    points, cells = read_vtu(args.mesh_vtu)
    cells = cells[:, cell_perm_vtk(dmesh.CellType.hexahedron, 27)]
    coordinate = basix.ufl.element("Lagrange", "hexahedron", 2, shape=(3,))
    domain = dmesh.create_mesh(MPI.COMM_SELF, cells, coordinate, points)
    length_x, length_z, depth = points[:, 0].max(), points[:, 2].max(), -points[:, 1].min()

    V = fem.functionspace(domain, ("Lagrange", 2, (3,)))
    u, v = fem.Function(V), ufl.TestFunction(V)

    # The layer (Y > 0) and the substrate, told apart at each cell's centre.
    Q = fem.functionspace(domain, ("DG", 0))
    in_layer = fem.Function(Q)
    centres = domain.geometry.x[domain.geometry.dofmaps[0]].mean(axis=1)
    for cell, centre in enumerate(centres):
        in_layer.x.array[Q.dofmap.cell_dofs(cell)] = 1.0 if centre[1] > 0.0 else 0.0

    # Strain energies (docs/model.md, eqs. 1-3).
    F = ufl.Identity(3) + ufl.grad(u)
    J = ufl.det(F)
    I1 = ufl.tr(F.T * F)

    def neo_hookean(mu, K):
        return mu / 2 * (J ** (-2.0 / 3.0) * I1 - 3.0) + K / 2 * ufl.ln(J) ** 2

    def fibre(direction):
        stretched = F * ufl.as_vector(direction)
        return args.mu_f / 4 * (ufl.dot(stretched, stretched) - args.lambda_f**2) ** 2

    cb, sb = np.cos(args.beta), np.sin(args.beta)
    cp, sp = np.cos(args.psi), np.sin(args.psi)
    families = [(cb * cp, sb, cb * sp), (cb * cp, -sb, cb * sp)]
    substrate = args.phi_m * neo_hookean(args.mu_s, args.K_s) + args.phi_f * sum(fibre(a) for a in families)
    energy = in_layer * neo_hookean(args.mu_l, args.K_l) + (1.0 - in_layer) * substrate
    dx = ufl.Measure("dx", domain=domain, metadata={"quadrature_degree": 5})  # 3 x 3 x 3 Gauss points
    residual = ufl.derivative(energy * dx, u, v)

    tol = 1e-9 * max(length_x, length_z)

    def dofs(component, where):
        sub, _ = V.sub(component).collapse()
        return fem.locate_dofs_geometrical((V.sub(component), sub), where)[0]

    end_x = fem.Constant(domain, default_scalar_type(0.0))
    end_z = fem.Constant(domain, default_scalar_type(0.0))
    zero = fem.Constant(domain, default_scalar_type(0.0))
    bcs = [
        fem.dirichletbc(zero, dofs(0, lambda x: np.abs(x[0]) < tol), V.sub(0)),
        fem.dirichletbc(end_x, dofs(0, lambda x: np.abs(x[0] - length_x) < tol), V.sub(0)),
        fem.dirichletbc(zero, dofs(2, lambda x: np.abs(x[2]) < tol), V.sub(2)),
        fem.dirichletbc(end_z, dofs(2, lambda x: np.abs(x[2] - length_z) < tol), V.sub(2)),
        fem.dirichletbc(zero, dofs(1, lambda x: np.abs(x[1] + depth) < tol), V.sub(1)),
    ]

    # The top surface: in each column of nodes (the imperfection moves nodes along Y only), the
    # highest one.
    nodes = V.tabulate_dof_coordinates()
    columns = {}
    for node, (x, y, z) in enumerate(nodes):
        key = (round(x, 9), round(z, 9))
        if key not in columns or y > nodes[columns[key], 1]:
            columns[key] = node
    top = np.array(sorted(columns.values()))
    top_y = nodes[top, 1]

    problem = NonlinearProblem(
        residual, u, bcs=bcs, petsc_options_prefix="patch_",
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
            end_x.value = -length_x * target
            end_z.value = -length_z * args.biaxial * target
            began = time.perf_counter()
            problem.solve()
            converged = snes.getConvergedReason() > 0
            if not converged:
                u.x.array[:] = saved
                step *= 0.5
                if step < args.min_step:
                    print(f"stopped at d = {d:.6f}: Newton failed at the smallest step", file=sys.stderr)
                    break
                continue
            d = target
            y = top_y + u.x.array[3 * top + 1]
            amplitude = 0.5 * (y.max() - y.min())
            out.write(f"{d:.6f},{amplitude:.15e},{snes.getIterationNumber()},{time.perf_counter() - began:.4f}\n")
            out.flush()
            if not args.quiet:
                print(f"d = {d:.6f}  A = {amplitude:.6f}  {snes.getIterationNumber()} it")
            step = args.step
    print(f"time: {time.perf_counter() - start:.2f} s to d = {d:.6f}", file=sys.stderr)


if __name__ == "__main__":
    main()
