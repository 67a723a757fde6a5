"""The wrinkling curve A(d) of fiberfold's model, solved with FEniCSx (DOLFINx) on fiberfold's mesh.

A general-purpose finite-element code of the same discretisation, to time fiberfold against and
to check it by: the layer and the fibre-reinforced substrate of docs/model.md (sections 3 and 8),
Q2 displacements on 9-node quadrilaterals, 3 x 3 Gauss points, the boundary conditions of 8.3,
and plain Newton (PETSc SNES with a direct MUMPS solve) at fixed steps in d, halved on failure
(reference.py).

The mesh, with its imperfection, is read from the first VTU snapshot of a `fiberfold simulate`
run (its points are the reference coordinates, imperfection included), so that both programs
solve on the same nodes. The material is given here (Table 1 by default, --beta for the fibres).
Writes d, A, Newton iterations and the seconds of each step as CSV.
"""

import numpy as np

import reference


def main():
    parser = reference.arguments(__doc__.splitlines()[0], "simulate_0000.vtu of a fiberfold run", 0.25)
    args = parser.parse_args()
    c, s = np.cos(args.beta), np.sin(args.beta)
    # Boundary conditions (8.3): u_x = 0 at X = 0, u_x = -L d at X = L, u_y = 0 at the bottom.
    conditions = [
        (0, lambda x, box, tol: np.abs(x[0]) < tol, lambda d, box: 0.0),
        (0, lambda x, box, tol: np.abs(x[0] - box["length_x"]) < tol, lambda d, box: -box["length_x"] * d),
        (1, lambda x, box, tol: np.abs(x[1] + box["depth"]) < tol, lambda d, box: 0.0),
    ]
    reference.solve(args, "quadrilateral", 9, [(c, s), (c, -s)], conditions)


if __name__ == "__main__":
    main()
