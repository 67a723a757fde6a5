"""The wrinkle amplitude A(d) of a patch of fiberfold's model in three dimensions, solved with
FEniCSx (DOLFINx) on fiberfold's mesh.

A general-purpose finite-element code of the same discretisation, to time fiberfold against and
to check it by: the layer and the fibre-reinforced substrate of docs/model.md (sections 3 and 8)
with the fibre families along (cos beta cos psi, +-sin beta, cos beta sin psi), Q2 displacements
on 27-node hexahedra, 3 x 3 x 3 Gauss points, and plain Newton (PETSc SNES with a direct MUMPS
solve) at fixed steps in d, halved on failure (reference.py). The patch's sides are symmetry
planes: u_X = 0 on X = 0 and -d Lx on X = Lx, u_Z = 0 on Z = 0 and -R d Lz on Z = Lz, u_Y = 0
on the bottom.

The mesh, with its imperfection, is read from `state.vtu` of a `fiberfold pattern --sides
symmetry --follow-to D` run (its points are the reference coordinates, imperfection included),
so that both programs solve on the same nodes. The material is given here (Table 1 by default).
Writes d, A, Newton iterations and the seconds of each step as CSV.
"""

import numpy as np

import reference


def main():
    parser = reference.arguments(__doc__.splitlines()[0],
                                 "state.vtu of a fiberfold pattern run with symmetry sides", 0.12)
    parser.add_argument("--biaxial", type=float, default=1.0, help="R = d_3 / d")
    parser.add_argument("--psi", type=float, default=0.0)
    args = parser.parse_args()
    cb, sb = np.cos(args.beta), np.sin(args.beta)
    cp, sp = np.cos(args.psi), np.sin(args.psi)
    families = [(cb * cp, sb, cb * sp), (cb * cp, -sb, cb * sp)]
    conditions = [
        (0, lambda x, box, tol: np.abs(x[0]) < tol, lambda d, box: 0.0),
        (0, lambda x, box, tol: np.abs(x[0] - box["length_x"]) < tol, lambda d, box: -box["length_x"] * d),
        (2, lambda x, box, tol: np.abs(x[2]) < tol, lambda d, box: 0.0),
        (2, lambda x, box, tol: np.abs(x[2] - box["length_z"]) < tol,
         lambda d, box: -box["length_z"] * args.biaxial * d),
        (1, lambda x, box, tol: np.abs(x[1] + box["depth"]) < tol, lambda d, box: 0.0),
    ]
    reference.solve(args, "hexahedron", 27, families, conditions)


if __name__ == "__main__":
    main()
