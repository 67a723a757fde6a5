"""The parts the DOLFINx references share: fiberfold's mesh read from a VTU file, the model's
strain energies (docs/model.md, eqs. 1-3), Q2 displacements with 3 x 3 (x 3) Gauss points, plain
Newton (PETSc SNES with a direct MUMPS solve) at fixed steps in d, halved on failure, and the
wrinkle amplitude A = (max y - min y) / 2 of the top surface written per step as CSV. Run as a
script, it compares two such curves side by side (`compare`), or the first change of the
tangent's inertia of two runs (`inertia`).

`--element mixed` is fiberfold's mixed element (docs/guide/src/model/incompressible.md,
src/fem/element/mixed.rs): Q2 displacements and, per element, a pressure linear in the reference
coordinates, p = p0 + p1 (X - Xc)/h + p2 (Y - Yc)/h (+ p3 (Z - Zc)/h), discontinuous across
elements (Q2/P1disc, unmapped), with the Hu-Washizu energy int W_rest(F) + p ln J - p^2/(2 kappa)
dV, kappa = K_l in the layer and phi_m K_s in the substrate. Here the pressure stays an unknown
(a saddle point) where fiberfold condenses it per element; both have the same solutions.

`--inertia` counts, at every converged state, the negative eigenvalues of the tangent on the free
unknowns: Sylvester's law on a MUMPS LDL^T factorisation of the assembled Jacobian (Dirichlet rows
and columns replaced by the identity, which adds positive pivots only). For the mixed element that
Jacobian is the saddle point S = [[K_uu, B^T], [B, -M/kappa]], and by Haynsworth's inertia
additivity In(S) = In(-M/kappa) + In(K_uu - B^T (-M/kappa)^-1 B): the count comparable with
fiberfold's (its tangent is the condensed one) is that of S minus the pressure unknowns, provided
-M/kappa is negative definite. At the first state both are checked (the pressure block's inertia
and the Schur complement's, formed explicitly), and at the first state with a positive count the
mode (the Schur complement's most negative eigenvector, by SLEPc) is classified by the dominant
cosine cos(m pi X / L) of its top-surface u_y, as fiberfold's `mode_half_waves`; both go to
OUT.inertia.json.
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
    parser.add_argument("--element", choices=("displacement", "mixed"), default="displacement",
                        help="displacement: Q2; mixed: Q2/P1disc, fiberfold's default element")
    parser.add_argument("--inertia", action="store_true",
                        help="count the tangent's negative eigenvalues at every state (column `negative`)")
    parser.add_argument("--out", required=True,
                        help="CSV of d, A, newton_iterations, step_seconds (and negative, negative_saddle, zero_pivots)")
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
    box))`, `box` the mesh's `length_x`, `length_z` and `depth`. Writes `args.out` (and, with
    `args.inertia`, `args.out + ".inertia.json"`)."""
    import dolfinx_solver  # noqa: F401  (loads the MPI and PETSc libraries the wheel carries)
    from mpi4py import MPI
    import basix.ufl
    import ufl
    from dolfinx import default_scalar_type, fem, mesh as dmesh
    from dolfinx.fem.petsc import NonlinearProblem, assemble_matrix, assemble_vector
    from dolfinx.io.utils import cell_perm_vtk

    element = getattr(args, "element", "displacement")
    count_inertia = getattr(args, "inertia", False)
    dimension = 2 if cell == "quadrilateral" else 3
    points, cells = read_vtu(args.mesh_vtu, nodes, dimension)
    cells = cells[:, cell_perm_vtk(getattr(dmesh.CellType, cell), nodes)]
    coordinate = basix.ufl.element("Lagrange", cell, 2, shape=(dimension,))
    domain = dmesh.create_mesh(MPI.COMM_SELF, cells, coordinate, points)
    box = {"length_x": points[:, 0].max(), "depth": -points[:, 1].min(),
           "length_z": points[:, 2].max() if dimension == 3 else 0.0}
    dx = ufl.Measure("dx", domain=domain, metadata={"quadrature_degree": 5})  # 3 Gauss points a direction

    displacement_element = basix.ufl.element("Lagrange", cell, 2, shape=(dimension,))
    if element == "mixed":
        # One pressure polynomial of D + 1 coefficients per element: a DG0 vector field.
        pressure_element = basix.ufl.element("DG", cell, 0, shape=(dimension + 1,))
        W = fem.functionspace(domain, basix.ufl.mixed_element([displacement_element, pressure_element]))
        w = fem.Function(W)
        u, coefficients = ufl.split(w)
        U = W.sub(0)
        V, u_dofs = U.collapse()
        # collapse() maps each collapsed (unrolled) dof to the mixed space's: [array].
        u_dofs = np.asarray(u_dofs).reshape(-1)
        p_dofs = np.sort(np.asarray(W.sub(1).collapse()[1]).reshape(-1))
    else:
        W = fem.functionspace(domain, displacement_element)
        w = fem.Function(W)
        u, U, V = w, W, W
        u_dofs = np.arange(W.dofmap.index_map.size_local * dimension)
        p_dofs = np.zeros(0, dtype=np.int32)
    dw = ufl.TestFunction(W)

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

    fibres = args.phi_f * sum(fibre(a) for a in families)
    if element == "mixed":
        # W = W_rest + kappa/2 (ln J)^2 (Tissue::volumetric_split): kappa = K_l, phi_m K_s.
        rest = (in_layer * neo_hookean(args.mu_l, 0.0)
                + (1.0 - in_layer) * (args.phi_m * neo_hookean(args.mu_s, 0.0) + fibres))
        kappa = in_layer * args.K_l + (1.0 - in_layer) * args.phi_m * args.K_s
        # The pressure basis of MixedElement::new: 1 and (X_i - centroid_i) / h, h = V^(1/D),
        # the centroid and V by the same Gauss points.
        test = ufl.TestFunction(Q)
        X = ufl.SpatialCoordinate(domain)
        volumes = assemble_vector(fem.form(test * dx)).array.copy()
        centroid = []
        for i in range(dimension):
            c = fem.Function(Q)
            c.x.array[:] = assemble_vector(fem.form(X[i] * test * dx)).array / volumes
            centroid.append(c)
        size = fem.Function(Q)
        size.x.array[:] = volumes ** (1.0 / dimension)
        p = coefficients[0] + sum(coefficients[i + 1] * (X[i] - centroid[i]) / size for i in range(dimension))
        energy = rest + p * ufl.ln(J) - p**2 / (2.0 * kappa)
    else:
        substrate = args.phi_m * neo_hookean(args.mu_s, args.K_s) + fibres
        energy = in_layer * neo_hookean(args.mu_l, args.K_l) + (1.0 - in_layer) * substrate
    residual = ufl.derivative(energy * dx, w, dw)

    tol = 1e-9 * max(box["length_x"], box["length_z"])
    bcs, loads = [], []
    for component, where, value in conditions:
        sub, _ = U.sub(component).collapse()
        dofs = fem.locate_dofs_geometrical((U.sub(component), sub), lambda x: where(x, box, tol))[0]
        constant = fem.Constant(domain, default_scalar_type(0.0))
        bcs.append(fem.dirichletbc(constant, dofs, U.sub(component)))
        loads.append((constant, value))

    # The top surface: in each column of nodes (the imperfection moves nodes along Y only), the
    # highest one.
    coordinates = V.tabulate_dof_coordinates()[:, :3]
    if len(u_dofs) != dimension * len(coordinates):
        sys.exit("the displacement dofs do not map one to one onto the nodes")
    columns = {}
    for node, x in enumerate(coordinates):
        key = (round(x[0], 9), round(x[2], 9))
        if key not in columns or x[1] > coordinates[columns[key], 1]:
            columns[key] = node
    top = np.array(sorted(columns.values()))
    top_y = coordinates[top, 1]

    problem = NonlinearProblem(
        residual, w, bcs=bcs, petsc_options_prefix="reference_",
        petsc_options={"snes_type": "newtonls", "snes_linesearch_type": "basic", "snes_atol": 1e-10,
                       "snes_rtol": 1e-12, "snes_stol": 0.0, "snes_max_it": 25, "ksp_type": "preonly",
                       "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"},
    )
    snes = problem.solver
    if count_inertia:
        tangent = fem.form(ufl.derivative(residual, w, ufl.TrialFunction(W)))
        report = {"element": element, "unknowns": int(W.dofmap.index_map.size_local * W.dofmap.index_map_bs),
                  "pressure_unknowns": int(len(p_dofs)), "dirichlet_unknowns":
                  int(sum(len(bc.dof_indices()[0]) for bc in bcs)), "checks": [], "first_positive": None}

    d, step, start = 0.0, args.d_first, time.perf_counter()
    with open(args.out, "w") as out:
        out.write("d,A,newton_iterations,step_seconds" + (",negative,negative_saddle,zero_pivots" if count_inertia else "") + "\n")
        while d < args.d_max - 1e-12:
            target = min(d + step, args.d_max)
            saved = w.x.array.copy()
            for constant, value in loads:
                constant.value = value(target, box)
            began = time.perf_counter()
            problem.solve()
            if snes.getConvergedReason() <= 0:
                w.x.array[:] = saved
                step *= 0.5
                if step < args.min_step:
                    print(f"stopped at d = {d:.6f}: Newton failed at the smallest step", file=sys.stderr)
                    break
                continue
            d = target
            displacement = w.x.array[u_dofs]
            y = top_y + displacement[dimension * top + 1]
            amplitude = 0.5 * (y.max() - y.min())
            seconds = time.perf_counter() - began
            row = f"{d:.6f},{amplitude:.15e},{snes.getIterationNumber()},{seconds:.4f}"
            line = f"d = {d:.6f}  A = {amplitude:.6f}  {snes.getIterationNumber()} it"
            if count_inertia:
                matrix = assemble_matrix(tangent, bcs=bcs, diag=1.0)
                matrix.assemble()
                saddle, zero, _ = inertia(matrix)
                negative = saddle - len(p_dofs)
                row += f",{negative},{saddle},{zero}"
                line += f"  {negative} negative" + (f" ({saddle} of the saddle point)" if len(p_dofs) else "")
                line += f", {zero} zero" if zero else ""
                if not report["checks"]:
                    report["checks"].append(dict(d=round(d, 6), **check_saddle_point(matrix, u_dofs, p_dofs, saddle)))
                    print(f"inertia check at d = {d:.6f}: {report['checks'][-1]}", file=sys.stderr)
                if negative > 0 and report["first_positive"] is None:
                    found = dict(d=round(d, 6), negative=int(negative), saddle=int(saddle))
                    found.update(check_saddle_point(matrix, u_dofs, p_dofs, saddle))
                    found.update(mode(matrix, u_dofs, p_dofs, coordinates, top, dimension, box["length_x"]))
                    report["first_positive"] = found
                    print(f"first positive count at d = {d:.6f}: {found}", file=sys.stderr)
                matrix.destroy()
            out.write(row + "\n")
            out.flush()
            if not args.quiet:
                print(line)
            step = args.step
    if count_inertia:
        import json
        report["reached"] = round(d, 6)
        json.dump(report, open(args.out + ".inertia.json", "w"), indent=2)
    print(f"time: {time.perf_counter() - start:.2f} s to d = {d:.6f}", file=sys.stderr)


def inertia(matrix):
    """(negative, zero, positive) eigenvalues of the symmetric `matrix`: the pivots of its
    LDL^T factorisation by MUMPS (SYM = 2, 1x1 and 2x2 pivots; INFOG(12) the negative ones,
    INFOG(28) the null ones)."""
    from petsc4py import PETSc

    matrix.setOption(PETSc.Mat.Option.SYMMETRIC, True)
    matrix.setOption(PETSc.Mat.Option.SPD, False)
    ksp = PETSc.KSP().create(PETSc.COMM_SELF)
    ksp.setOperators(matrix)
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("cholesky")
    pc.setFactorSolverType("mumps")
    pc.setFactorSetUpSolverType()
    factor = pc.getFactorMatrix()
    factor.setMumpsIcntl(24, 1)  # null pivot detection, which MatGetInertia requires (their count: zero)
    pc.setUp()
    negative, zero, positive = factor.getInertia()
    if factor.getMumpsInfog(12) != negative:
        sys.exit(f"MUMPS INFOG(12) = {factor.getMumpsInfog(12)} but MatGetInertia says {negative}")
    ksp.destroy()
    return int(negative), int(zero), int(positive)


def schur_complement(matrix, u_dofs, p_dofs):
    """K_uu - B^T C^-1 B of the saddle point [[K_uu, B^T], [B, C]] (C block diagonal, the
    element pressures), in the order of the sorted displacement unknowns; and C."""
    from petsc4py import PETSc

    u_is = PETSc.IS().createGeneral(np.sort(u_dofs).astype(np.int32), comm=PETSc.COMM_SELF)
    p_is = PETSc.IS().createGeneral(p_dofs.astype(np.int32), comm=PETSc.COMM_SELF)
    K = matrix.createSubMatrix(u_is, u_is)
    Bt = matrix.createSubMatrix(u_is, p_is)
    B = matrix.createSubMatrix(p_is, u_is)
    C = matrix.createSubMatrix(p_is, p_is)
    # C^-1 block by block: the rows of one element's pressures share their columns.
    indptr, indices, values = C.getValuesCSR()
    n = len(indptr) - 1
    inverse = {}
    for row in range(n):
        block = tuple(indices[indptr[row]:indptr[row + 1]])
        if block not in inverse:
            dense = np.array([[C.getValue(i, j) for j in block] for i in block])
            inverse[block] = np.linalg.inv(dense)
    C_inverse = PETSc.Mat().createAIJ([n, n], nnz=max(len(b) for b in inverse), comm=PETSc.COMM_SELF)
    for block, values in inverse.items():
        C_inverse.setValues(list(block), list(block), values.ravel())
    C_inverse.assemble()
    S = K.copy()
    S.axpy(-1.0, Bt.matMult(C_inverse).matMult(B), structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
    return S, C


def check_saddle_point(matrix, u_dofs, p_dofs, saddle):
    """The two premises of `negative = In_-(S) - pressures`: the pressure block C = -M/kappa is
    negative definite, and the Schur complement (the condensed tangent) has In_-(S) - pressures
    negative eigenvalues (Haynsworth)."""
    if len(p_dofs) == 0:
        return {}
    S, C = schur_complement(matrix, u_dofs, p_dofs)
    pressure = inertia(C)
    condensed = inertia(S)
    return {"saddle_negative": int(saddle), "pressure_unknowns": int(len(p_dofs)),
            "pressure_block_negative": pressure[0], "pressure_block_nonnegative": pressure[1] + pressure[2],
            "schur_negative": condensed[0], "schur_zero": condensed[1],
            "haynsworth_holds": bool(pressure[0] == len(p_dofs) and condensed[0] == saddle - len(p_dofs))}


def mode(matrix, u_dofs, p_dofs, coordinates, top, dimension, length):
    """The eigenvector of the most negative eigenvalue of the (condensed) tangent on the free
    unknowns, by SLEPc's shift and invert about 0, and the number m of half waves of the dominant
    cosine cos(m pi X / L) of its top-surface u_y."""
    from petsc4py import PETSc
    from slepc4py import SLEPc

    if len(p_dofs):
        S, _ = schur_complement(matrix, u_dofs, p_dofs)
    else:
        S = matrix
    eps = SLEPc.EPS().create(PETSc.COMM_SELF)
    eps.setOperators(S)
    eps.setProblemType(SLEPc.EPS.ProblemType.HEP)
    eps.setDimensions(4)
    eps.setTarget(0.0)
    eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
    st = eps.getST()
    st.setType("sinvert")
    st.getKSP().setType("preonly")
    st.getKSP().getPC().setType("cholesky")
    st.getKSP().getPC().setFactorSolverType("mumps")
    eps.setTolerances(1e-10, 500)
    eps.solve()
    vector = S.createVecRight()
    pairs = []
    for i in range(eps.getConverged()):
        value = eps.getEigenpair(i, vector).real
        pairs.append((value, vector.getArray().copy()))
    if not pairs:
        return {"mode_half_waves": None}
    value, vector = min(pairs, key=lambda pair: pair[0])
    # The vector is in the order of the sorted displacement unknowns; u_dofs[i] is the unknown of
    # the collapsed displacement dof i.
    position = np.searchsorted(np.sort(u_dofs), u_dofs)
    uy = vector[position][dimension * top + 1]
    X = coordinates[top, 0]
    order = np.argsort(X)
    X, uy = X[order], uy[order]
    m_max = len(X) // 2
    basis = np.cos(np.outer(X, np.arange(m_max + 1)) * np.pi / length)
    amplitudes = np.abs(np.linalg.lstsq(basis, uy, rcond=None)[0])
    return {"eigenvalue": float(value), "mode_half_waves": int(np.argmax(amplitudes)),
            "smallest_eigenvalues": sorted(float(v) for v, _ in pairs)}


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


def first_changes(secondary_json, ours_csv, theirs_csv, our_log=None):
    """fiberfold's first change of the inertia (its `secondary.json`) against the reference's
    (the column `negative` of its CSV, and its OUT.inertia.json when there), their difference in
    d, the states where the two counts differ (fiberfold's read off its log, `d = ... N negative`,
    when given), and the largest relative difference of A(d) over the d both reached."""
    import json

    changes = json.load(open(secondary_json))["changes"]
    if changes:
        c = changes[0]
        print("fiberfold: first inertia change between d = %.6f (%d negative) and d = %.6f (%d negative), "
              "mode %s half waves (eigenvalue %.6e)" % (c["d_before"], c["negative_before"], c["d_after"],
                                                       c["negative_after"], c["mode_half_waves"], c["eigenvalue"]))
    else:
        c = None
        print("fiberfold: no change of the inertia")
    rows = [(round(float(r["d"]), 6), int(r["negative"])) for r in csv.DictReader(open(theirs_csv))]
    if not rows:
        print("FEniCSx: no converged state")
        return
    first = next((i for i, (_, n) in enumerate(rows) if n > 0), None)
    try:
        report = json.load(open(theirs_csv + ".inertia.json"))
    except OSError:
        report = {}
    zero = [round(float(r["d"]), 6) for r in csv.DictReader(open(theirs_csv)) if int(r.get("zero_pivots") or 0)]
    if zero:
        print("FEniCSx: MUMPS found null pivots at d = " + ", ".join("%g" % d for d in zero[:10]))
    if rows[0][1] != 0:
        print("FEniCSx: count %d already at the first state d = %.6f" % (rows[0][1], rows[0][0]))
    if first is None:
        print("FEniCSx:   count 0 at every state up to d = %.6f" % rows[-1][0])
    else:
        found = report.get("first_positive") or {}
        print("FEniCSx:   last count 0 at d = %.6f, first count > 0 at d = %.6f (count %d), mode %s half waves "
              "(eigenvalue %s)" % (rows[first - 1][0] if first else float("nan"), rows[first][0], rows[first][1],
                                   found.get("mode_half_waves", "?"),
                                   "%.6e" % found["eigenvalue"] if "eigenvalue" in found else "?"))
        if c is not None:
            print("difference (FEniCSx - fiberfold) of the first d with a negative eigenvalue: %+.6f"
                  % (round(rows[first][0] - c["d_after"], 9) + 0.0))
    for check in report.get("checks", []) + ([report["first_positive"]] if report.get("first_positive") else []):
        if "pressure_unknowns" in check and "saddle_negative" in check:
            print("FEniCSx saddle point at d = %.6f: %d negative = %d pressure unknowns (pressure block: %d negative)"
                  " + %d of the Schur complement: %s" % (
                      check["d"], check["saddle_negative"], check["pressure_unknowns"],
                      check["pressure_block_negative"], check["schur_negative"],
                      "Haynsworth holds" if check["haynsworth_holds"] else "DOES NOT HOLD"))
    if our_log:
        ours = {round(float(m.group(1)), 6): int(m.group(2))
                for m in re.finditer(r"^d = ([0-9.]+) .* ([0-9]+) negative", open(our_log).read(), re.M)}
        theirs = dict(rows)
        both = sorted(d for d in ours if d in theirs)
        differ = [d for d in both if ours[d] != theirs[d]]
        print("counts: equal at %d of the %d common d%s" % (
            len(both) - len(differ), len(both),
            "" if not differ else "; they differ at d = " + ", ".join("%g (%d vs %d)" % (d, ours[d], theirs[d])
                                                              for d in differ[:10])))
    curves = [{round(float(r["d"]), 6): float(r["A"]) for r in csv.DictReader(open(f))} for f in (ours_csv, theirs_csv)]
    common = sorted(d for d in curves[0] if d in curves[1])
    if common:
        worst = max(common, key=lambda d: abs(curves[0][d] - curves[1][d]) / abs(curves[0][d]))
        print("A(d): largest relative difference %.1e (at d = %g) over %d common d from %g to %g" % (
            abs(curves[0][worst] - curves[1][worst]) / abs(curves[0][worst]), worst, len(common), common[0],
            common[-1]))
    else:
        print("A(d): no common d (see the logs)")


if __name__ == "__main__" and sys.argv[1:2] == ["compare"]:
    compare(*sys.argv[2:6])
elif __name__ == "__main__" and sys.argv[1:2] == ["inertia"]:
    first_changes(*sys.argv[2:6])
