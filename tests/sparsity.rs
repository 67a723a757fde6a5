//! The sparsity of the tangent and the inertia counted in the background, against independent
//! facts: groups of an added energy enter the tangent as their Hessians, the stored entries (and
//! so the factorisation's analysis) change only when a group needs new ones, and a positive
//! definite matrix minus `m` springs far stiffer than it has exactly `m` negative eigenvalues.

use fiberfold::fem::added::{AddedEnergy, Block};
use fiberfold::fem::inertia::BackgroundInertia;
use fiberfold::fem::linear_solver::multiply;
use fiberfold::fem::{SparseLdlt, System};
use fiberfold::material::Bilayer;
use fiberfold::mesh::{Mesh, MeshSpec, X, Y};
use fiberfold::protocol::model_conditions;
use fiberfold::Parameters;

/// A quadratic energy `1/2 c |u_g - 0.1|^2` on each group's unknowns, announcing `likely`
/// groups to come.
struct Springs {
    groups: Vec<Vec<usize>>,
    likely: Vec<Vec<usize>>,
    stiffness: f64,
}

impl AddedEnergy for Springs {
    fn groups(&self) -> &[Vec<usize>] {
        &self.groups
    }

    fn likely_groups(&self) -> Vec<Vec<usize>> {
        self.likely.clone()
    }

    fn block(&self, g: usize, u: &[f64], with_tangent: bool) -> Block {
        let dofs = &self.groups[g];
        let n = dofs.len();
        let gradient: Vec<f64> = dofs.iter().map(|&d| self.stiffness * (u[d] - 0.1)).collect();
        Block {
            energy: gradient.iter().map(|g| g * g).sum::<f64>() / (2.0 * self.stiffness),
            hessian: match with_tangent {
                true => (0..n * n)
                    .map(|i| if i % (n + 1) == 0 { self.stiffness } else { 0.0 })
                    .collect(),
                false => Vec::new(),
            },
            gradient,
        }
    }
}

/// The stored entries (and so the factorisation's analysis) survive a change of the groups
/// that fit in them, a group coupling distant unknowns adds entries once (with those of the
/// groups announced as likely), and in every case the tangent is the elastic one plus the
/// groups' Hessians.
#[test]
fn groups_that_fit_keep_the_stored_entries_and_the_tangent_adds_them() {
    let mesh = Mesh::new(MeshSpec::new(4, 1, 2, 1.0, 4.0, 2.0)).unwrap();
    let mut system = System::new(mesh.clone(), &Bilayer::new(&Parameters::default())).unwrap();
    let bc = model_conditions(&mesh, 0.05).unwrap();
    let u: Vec<f64> = (0..mesh.num_dofs()).map(|i| 0.01 * (i as f64 * 0.37).sin()).collect();
    let elastic = system.assemble(&u, &bc, None, true).unwrap();
    let free = system.free_dofs(&bc).unwrap().to_vec();
    let v: Vec<f64> = (0..free.len()).map(|i| (i as f64 * 0.91).cos()).collect();
    let elastic_times_v = multiply(elastic.tangent.as_ref().unwrap().as_ref(), &v);
    let top = mesh.top();
    let (left, right) = (top[1], top[top.len() - 2]);
    let dofs = mesh.dofs();
    let one_node = vec![dofs.node_dofs(left).collect()];
    let distant = vec![dofs.node_dofs(left).chain(dofs.node_dofs(right)).collect()];
    let (middle, bottom) = (top[top.len() / 2], mesh.bottom()[1]);
    let announced = vec![vec![dofs.dof(middle, Y), dofs.dof(bottom, X)]];
    let mut check = |groups: &Vec<Vec<usize>>| {
        let springs = Springs {
            groups: groups.clone(),
            likely: announced.clone(),
            stiffness: 7.0,
        };
        let assembled = system.assemble_with(&u, &bc, None, true, &springs).unwrap();
        let mut expected = elastic_times_v.clone();
        for &dof in groups.iter().flatten() {
            let f = free.binary_search(&dof).unwrap();
            expected[f] += 7.0 * v[f];
        }
        let got = multiply(assembled.tangent.as_ref().unwrap().as_ref(), &v);
        let worst = got.iter().zip(&expected).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(worst < 1e-10, "tangent with {groups:?}: {worst:e}");
        (assembled.pattern, assembled.structure)
    };
    let (pattern, structure) = check(&one_node);
    assert_ne!(pattern, elastic.pattern, "new groups, new layout");
    assert_eq!(structure, elastic.structure, "a node's own unknowns are stored");
    let (_, coupled) = check(&distant);
    assert_ne!(coupled, elastic.structure, "distant nodes need new entries");
    assert_eq!(check(&Vec::new()).1, coupled, "entries once added stay");
    assert_eq!(check(&one_node).1, coupled);
    assert_eq!(check(&distant).1, coupled);
    assert_eq!(
        check(&announced).1,
        coupled,
        "the likely group was stored with the growth"
    );
}

/// Counts made on the second thread come back in order and are exact: a positive definite `K`
/// minus a spring far stiffer than `K` on each of `m` unknowns has exactly `m` negative
/// eigenvalues (interlacing, with the Schur complement on the other unknowns positive
/// definite); a solver whose factor was freed factorises again to the same count.
#[test]
fn inertia_counted_in_the_background_is_exact_and_in_order() {
    let mesh = Mesh::new(MeshSpec::new(4, 1, 2, 1.0, 4.0, 2.0)).unwrap();
    let mut system = System::new(mesh.clone(), &Bilayer::new(&Parameters::default())).unwrap();
    let bc = model_conditions(&mesh, 0.0).unwrap();
    let u = vec![0.0; mesh.num_dofs()];
    let free = system.free_dofs(&bc).unwrap().to_vec();
    let elastic = system.assemble(&u, &bc, None, true).unwrap();
    let mut solver = SparseLdlt::new(elastic.tangent.as_ref().unwrap().symbolic());
    let mut counter = BackgroundInertia::default();
    let counts = [0, 3, 1, 5, 2];
    for (i, &m) in counts.iter().enumerate() {
        let springs = Springs {
            groups: free.iter().step_by(7).take(m).map(|&dof| vec![dof]).collect(),
            likely: Vec::new(),
            stiffness: -1e9,
        };
        let assembled = system.assemble_with(&u, &bc, None, true, &springs).unwrap();
        // Every other count analyses the pattern itself, the others share `solver`'s analysis.
        counter.start(assembled, |_| (i % 2 == 1).then(|| solver.sibling()));
    }
    let got: Vec<Option<usize>> = (0..counts.len()).map(|_| counter.next_count()).collect();
    assert_eq!(got, counts.map(Some).to_vec());
    assert_eq!(counter.next_count(), None);

    let k = elastic.tangent.as_ref().unwrap().as_ref();
    solver.factorize(k);
    let mut x = elastic.residual.clone();
    solver.solve_in_place(&mut x).unwrap();
    solver.free_factor();
    assert_eq!(solver.negative_pivots(), None, "no factorisation after freeing it");
    solver.factorize(k);
    let mut again = elastic.residual.clone();
    solver.solve_in_place(&mut again).unwrap();
    assert_eq!((solver.negative_pivots(), x), (Some(0), again));
}
