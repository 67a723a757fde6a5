//! Helpers shared by the integration tests (each test crate uses some of them).
#![allow(dead_code)]

pub mod files;
pub mod resume;

use fiberfold::fem::element::{PlaneElement, ReferenceElement, ELEMENT_DOFS};
use fiberfold::fem::{Dirichlet, System};
use fiberfold::material::Bilayer;
use fiberfold::mesh::{Mesh, X, Y};
use fiberfold::Parameters;
use std::path::PathBuf;
use std::process::{Command, Output};

/// Layer and substrate the same neo-Hookean solid (`mu = 1`, `K = 3`, no fibres).
pub fn homogeneous_material() -> Bilayer {
    Bilayer::new(&Parameters {
        mu_l: 1.0,
        K_l: 3.0,
        mu_s: 1.0,
        K_s: 3.0,
        phi_m: 1.0,
        phi_f: 0.0,
        ..Parameters::default()
    })
}

/// A path under the temporary directory, unique to this test process, that nothing occupies
/// yet; what a test writes there is removed when the test is done with it, and kept where the
/// test fails (to be looked at).
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = PathBuf;

    fn deref(&self) -> &PathBuf {
        &self.0
    }
}

impl AsRef<std::path::Path> for Scratch {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("kept for a look: {}", self.0.display());
        } else if self.0.is_dir() {
            let _ = std::fs::remove_dir_all(&self.0);
        } else {
            let _ = std::fs::remove_file(&self.0);
        }
    }
}

/// A [`Scratch`] path named after `name`.
pub fn scratch(name: &str) -> Scratch {
    let path = std::env::temp_dir().join(format!("fiberfold-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&path);
    let _ = std::fs::remove_file(&path);
    Scratch(path)
}

/// `fiberfold bifurcation --element mixed` with `args`: its JSON summary.
pub fn mixed_bifurcation(name: &str, args: &[&str]) -> serde_json::Value {
    let out = scratch(name);
    let mut all = vec!["bifurcation", "--element", "mixed", "--out", out.to_str().unwrap()];
    all.extend(args);
    let output = fiberfold(&all);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_str(&std::fs::read_to_string(out.join("bifurcation.json")).unwrap()).unwrap()
}

/// Runs the `fiberfold` binary with `args`.
pub fn fiberfold<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// A small deterministic generator (xorshift), so every random test can be replayed.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `0..n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// `simulate` on the coarse mesh to d = 0.1 (4.5 waves, about a second) into `out`.
pub fn quick_simulate(out: &std::path::Path) -> Vec<String> {
    ["simulate", "--waves", "4.5", "--d-max", "0.1", "--out"]
        .iter()
        .map(|s| s.to_string())
        .chain(std::iter::once(out.display().to_string()))
        .collect()
}

/// A 2 x 1 map on small meshes (a few seconds a point): an isotropic soft and stiff layer.
pub fn tiny_map(out: &std::path::Path, extra: &[&str]) -> Vec<String> {
    tiny_map_of(2, out, extra)
}

/// [`tiny_map`] with `points` layers from mu_l = 1.5 to 10 (log-spaced).
pub fn tiny_map_of(points: usize, out: &std::path::Path, extra: &[&str]) -> Vec<String> {
    let points = points.to_string();
    let mut args: Vec<String> = [
        "map",
        "--set",
        "phi_m=1",
        "--set",
        "phi_f=0",
        "--x",
        "mu_l",
        "--x-from",
        "1.5",
        "--x-to",
        "10",
        "--x-points",
        points.as_str(),
        "--x-log",
        "--y",
        "beta",
        "--y-from",
        "0",
        "--y-to",
        "0",
        "--y-points",
        "1",
        "--waves",
        "2",
        "--elements-per-wave",
        "12",
        "--substrate-elements",
        "10",
        "--post-buckling-range",
        "0.04",
        "--fold",
        "1",
        "--crease-nx",
        "24",
        "--crease-layer-elements",
        "2",
        "--crease-substrate-elements",
        "10",
        "--no-crease-convergence",
        "--out",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.push(out.display().to_string());
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

/// The points of `map.json` without their wall times.
pub fn map_points(dir: &std::path::Path) -> Vec<serde_json::Value> {
    let text = std::fs::read_to_string(dir.join("map.json")).expect("map.json");
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut points = json["points"].as_array().unwrap().clone();
    for p in &mut points {
        p.as_object_mut().unwrap().remove("seconds");
    }
    points
}

/// A smooth distortion of every node, curving the element edges.
pub fn distortion(amplitude: f64) -> impl Fn([f64; 2]) -> [f64; 2] {
    move |[x, y]| {
        [
            amplitude * (1.7 * x + 0.9 * y).sin(),
            amplitude * (1.3 * x - 2.1 * y).cos(),
        ]
    }
}

/// Prescribes `value(X)` on every boundary node.
pub fn boundary_values(mesh: &Mesh, value: impl Fn([f64; 2]) -> [f64; 2]) -> Dirichlet {
    let nodes = [mesh.left(), mesh.right(), mesh.bottom(), mesh.top()].concat();
    let pairs = nodes.iter().flat_map(|&n| {
        let v = value(mesh.coordinates()[n]);
        [(mesh.dofs().dof(n, X), v[0]), (mesh.dofs().dof(n, Y), v[1])]
    });
    Dirichlet::new(pairs.collect()).unwrap()
}

/// Largest nodal error `max |u_i - exact_i(X)|` of the displacement `u` on `mesh`.
pub fn worst_nodal_error(mesh: &Mesh, u: &[f64], exact: impl Fn([f64; 2]) -> [f64; 2]) -> f64 {
    (0..mesh.num_nodes())
        .map(|n| {
            let v = exact(mesh.coordinates()[n]);
            (u[mesh.dofs().dof(n, X)] - v[0])
                .abs()
                .max((u[mesh.dofs().dof(n, Y)] - v[1]).abs())
        })
        .fold(0.0, f64::max)
}

/// Norms of the error of a finite-element displacement against an exact one.
pub struct ErrorNorms {
    /// `||u_h - u||_L2`.
    pub l2: f64,
    /// `|u_h - u|_H1 = ||Grad u_h - Grad u||_L2`.
    pub h1: f64,
    /// `||u||_L2`.
    pub exact_l2: f64,
}

impl ErrorNorms {
    pub fn relative_l2(&self) -> f64 {
        self.l2 / self.exact_l2
    }
}

/// [`ErrorNorms`] of the full displacement `u` against `exact` (and its gradient
/// `[du1/dX, du1/dY, du2/dX, du2/dY]`), with a 4x4 Gauss rule per element.
pub fn error_norms(
    system: &System,
    u: &[f64],
    exact: &dyn Fn([f64; 2]) -> [f64; 2],
    exact_gradient: &dyn Fn([f64; 2]) -> [f64; 4],
) -> ErrorNorms {
    let (r, s) = (0.339_981_043_584_856_3, 0.861_136_311_594_052_6);
    let (wr, ws) = (0.652_145_154_862_546_1, 0.347_854_845_137_453_9);
    let rule = [(-s, ws), (-r, wr), (r, wr), (s, ws)];
    let coordinates = system.mesh().coordinates();
    let mut norms = ErrorNorms {
        l2: 0.0,
        h1: 0.0,
        exact_l2: 0.0,
    };
    for (e, nodes) in system.mesh().elements().iter().enumerate() {
        let ue = system.element_displacements(e, u);
        for &(xi, wx) in &rule {
            for &(eta, wy) in &rule {
                let (n, dn) = (
                    PlaneElement::shape_functions([xi, eta]),
                    PlaneElement::shape_derivatives([xi, eta]),
                );
                // j[I][r] = dX_I / dxi_r.
                let (mut point, mut uh, mut j) = ([0.0; 2], [0.0; 2], [[0.0; 2]; 2]);
                for a in 0..9 {
                    for c in 0..2 {
                        point[c] += n[a] * coordinates[nodes[a]][c];
                        uh[c] += n[a] * ue[ELEMENT_DOFS.dof(a, c)];
                        j[c][0] += coordinates[nodes[a]][c] * dn[a][0];
                        j[c][1] += coordinates[nodes[a]][c] * dn[a][1];
                    }
                }
                let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                let mut grad = [0.0; 4];
                for a in 0..9 {
                    let g = [
                        (dn[a][0] * j[1][1] - dn[a][1] * j[1][0]) / det,
                        (-dn[a][0] * j[0][1] + dn[a][1] * j[0][0]) / det,
                    ];
                    for c in 0..2 {
                        grad[ELEMENT_DOFS.dof(c, 0)] += ue[ELEMENT_DOFS.dof(a, c)] * g[0];
                        grad[ELEMENT_DOFS.dof(c, 1)] += ue[ELEMENT_DOFS.dof(a, c)] * g[1];
                    }
                }
                let weight = wx * wy * det;
                let (v, dv) = (exact(point), exact_gradient(point));
                norms.l2 += weight * ((uh[0] - v[0]).powi(2) + (uh[1] - v[1]).powi(2));
                norms.h1 += weight * grad.iter().zip(&dv).map(|(a, b)| (a - b).powi(2)).sum::<f64>();
                norms.exact_l2 += weight * (v[0] * v[0] + v[1] * v[1]);
            }
        }
    }
    ErrorNorms {
        l2: norms.l2.sqrt(),
        h1: norms.h1.sqrt(),
        exact_l2: norms.exact_l2.sqrt(),
    }
}

/// A command that must exit 2 with a one-line error mentioning each of `must_mention`; its stderr.
pub fn rejected(args: &[&str], must_mention: &[&str]) -> String {
    let out = fiberfold(args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?} should exit 2, stderr: {stderr}");
    assert_eq!(
        stderr.trim().lines().count(),
        1,
        "{args:?}: one line expected: {stderr}"
    );
    for word in must_mention {
        assert!(stderr.contains(word), "{args:?}: `{word}` missing from: {stderr}");
    }
    stderr
}

/// An isotropic bilayer of stiffness ratio `mu_l / mu_s = ratio`, nearly incompressible
/// (K = 100 mu in both layers), no fibres.
pub fn isotropic(ratio: f64) -> Parameters {
    Parameters {
        mu_l: ratio,
        K_l: 100.0 * ratio,
        mu_s: 1.0,
        K_s: 100.0,
        phi_m: 1.0,
        phi_f: 0.0,
        mu_f: 0.0,
        ..Parameters::default()
    }
}

/// The undamped elastic residual of a recorded state `u` at `record.d`, assembled afresh on a new
/// system of `materials`, over the free unknowns off the nodes the contact pushes (where the
/// elastic residual balances the contact force), and Newton's tolerance `policy` gives it:
/// `(residual, tolerance)`.
pub fn undamped_residual(
    materials: &Bilayer,
    (record, system, u): (&fiberfold::protocol::StepRecord, &System, &[f64]),
    policy: &fiberfold::fem::NewtonPolicy,
) -> (f64, f64) {
    let pushed: Vec<usize> = record.augmented.as_ref().map_or(Vec::new(), |a| {
        a.pressure
            .iter()
            .filter(|(_, p)| *p != 0.0)
            .flat_map(|&(n, _)| system.mesh().dofs().node_dofs(n))
            .collect()
    });
    let mut fresh = System::new(system.mesh().clone(), materials).unwrap();
    let bc = fiberfold::protocol::model_conditions(system.mesh(), record.d).unwrap();
    let assembled = fresh.assemble(u, &bc, None, false).unwrap();
    let free = fresh.free_dofs(&bc).unwrap();
    let residual = free
        .iter()
        .zip(&assembled.residual)
        .filter(|(dof, _)| !pushed.contains(dof))
        .map(|(_, r)| r * r)
        .sum::<f64>()
        .sqrt();
    (
        residual,
        policy.residual_tolerance * assembled.force_norm() + policy.absolute_tolerance,
    )
}
