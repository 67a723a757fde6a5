//! `fiberfold map`: which instability comes first, and what the wrinkle becomes, over a grid of
//! two parameters (`point` computes one point), computed point by point into a folder that
//! resumes and shards ([`super::grid`]), and assembled by [`collect`] into `map.csv`,
//! `map.json` and the phase diagram `map.png/svg`.

mod figure;
mod options;
mod point;

pub use options::MapOptions;
pub use point::{compute as compute_point, doubling, first_instability, post_buckling, First, MapPoint, PostBuckling};

use super::crease::{CreaseMesh, CreaseStudy, Criterion, Refinement, Scan};
use super::grid::{self, At, GridStudy};
pub use super::grid::{Axis, Computed, Shard};
use super::orientation::Modes;
use super::Tick;
use crate::error::{Error, Result};
use crate::output::table::{variant_name, Cell};
use crate::output::{write_json, CsvWriter};
use crate::parameters::Parameters;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// How each point is computed (the CLI's flags of the same names).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapSettings {
    /// Wavelengths of `2 pi / k0` across the nonlinear run's half domain (`2 waves` an integer).
    pub waves: f64,
    /// Q2 elements per wavelength along X in the nonlinear run.
    pub elements_per_wave: usize,
    pub layer_elements: usize,
    pub substrate_elements: usize,
    /// Depth of the nonlinear run's domain (units of H).
    pub depth: f64,
    /// `A_init` of the seeded wrinkle, and `A_2` of the seed along the first secondary mode.
    pub imperfection: f64,
    pub seed: f64,
    /// The nonlinear run goes to `d_wrinkle + post_buckling_range`, at most `d_limit`.
    pub post_buckling_range: f64,
    pub d_limit: f64,
    /// Energy the viscous stabilisation may dissipate, relative to the strain energy, so that
    /// the run crosses the snaps a wrinkle makes into a fold or a period doubling (a `simulate`
    /// run stops at 1 %, where the path stops being quasi-static).
    pub snap_budget: f64,
    /// Follow a fold or a doubled period past the state where it closes on itself (in contact,
    /// one trough more than 20 % deeper than all others, or deep troughs alternating with
    /// shallower ones by more than 20 %) to the run's end. Without, the run ends there: the
    /// classification of the last state is then `fold` or `period_doubling` whatever follows,
    /// since a closed trough only deepens. Maps written before this setting followed every run
    /// (`true`).
    #[serde(default = "followed_before")]
    pub follow_closed_folds: bool,

    /// The crease search ([`CreaseStudy`], without its mesh check); its mesh's element is the
    /// nonlinear run's too.
    pub crease_mesh: CreaseMesh,
    pub fold_lengths: Vec<f64>,
    pub crease_scan: Scan,
    /// The mesh sequence that converges each point's crease onset (None in files written before
    /// it existed: the base mesh alone).
    #[serde(default)]
    pub crease_refinement: Option<Refinement>,
    /// The crease search's criterion (held in files written before it existed).
    #[serde(default)]
    pub crease_criterion: Criterion,
    /// Scale the bulk modulus with a mapped shear modulus (`K_l` with `mu_l`, `K_s` with
    /// `mu_s`), keeping the base set's `K / mu`: the Poisson ratio stays Table 1's.
    pub keep_poisson: bool,
    /// `R = d_3 / d`: each point also finds the direction of the first wrinkles under biaxial
    /// compression `d_3 = R d` (the linear theory over the directions of the surface), drawn
    /// on the figure as the crests' direction. The crease search and the nonlinear run stay
    /// in plane strain.
    #[serde(default)]
    pub biaxial: Option<f64>,
}

impl Default for MapSettings {
    /// Four wavelengths at 20 elements each, the coarse mesh's layers (2 + 25, depth 50),
    /// `A_init = 0.05` with a 0.01 seed along the first secondary mode, runs to `d_wrinkle + 0.2`
    /// (at most 0.7); the
    /// crease search of `fiberfold crease` without its mesh check.
    fn default() -> Self {
        let crease = CreaseStudy::default();
        MapSettings {
            waves: 4.0,
            elements_per_wave: 20,
            layer_elements: 2,
            substrate_elements: 25,
            depth: 50.0,
            imperfection: 0.05,
            seed: 0.01,
            post_buckling_range: 0.2,
            d_limit: 0.7,
            snap_budget: 0.5,
            follow_closed_folds: false,

            crease_mesh: crease.mesh,
            fold_lengths: crease.fold_lengths,
            crease_scan: crease.scan,
            // Three meshes at most: a point's crease search within about twice its cost on one.
            crease_refinement: crease.refinement.map(|r| Refinement { max_meshes: 3, ..r }),
            crease_criterion: crease.criterion,
            keep_poisson: true,
            biaxial: None,
        }
    }
}

/// Maps written before [`MapSettings::follow_closed_folds`] existed followed every fold.
fn followed_before() -> bool {
    true
}

impl MapSettings {
    /// The crease search of every point (without the mesh check; each point's scan is then
    /// fitted to its `d_wrinkle`).
    pub fn crease_study(&self) -> CreaseStudy {
        CreaseStudy {
            mesh: self.crease_mesh,
            fold_lengths: self.fold_lengths.clone(),
            scan: self.crease_scan,
            criterion: self.crease_criterion,
            refinement: self.crease_refinement,
            lowest_only: true,
            stop_past_wrinkle: true,
        }
    }

    fn validate(&self) -> Result<()> {
        if !(self.waves.is_finite() && self.waves >= 1.0 && (2.0 * self.waves).fract() == 0.0 && self.waves <= 50.0) {
            return Err(Error::invalid("waves", self.waves, "[1, 50] with 2 waves an integer"));
        }
        if !(4..=200).contains(&self.elements_per_wave) {
            return Err(Error::invalid("elements-per-wave", self.elements_per_wave, "[4, 200]"));
        }
        if !(self.post_buckling_range.is_finite() && self.post_buckling_range > 0.0 && self.post_buckling_range < 1.0) {
            return Err(Error::invalid(
                "post-buckling-range",
                self.post_buckling_range,
                "(0, 1)",
            ));
        }
        if !(self.seed.is_finite() && (0.0..1.0).contains(&self.seed)) {
            return Err(Error::invalid("seed", self.seed, "[0, 1)"));
        }
        let counts = [
            ("layer-elements", self.layer_elements, 16),
            ("substrate-elements", self.substrate_elements, 400),
            ("crease-nx", self.crease_mesh.nx, 2000),
            ("crease-layer-elements", self.crease_mesh.layer, 64),
            ("crease-substrate-elements", self.crease_mesh.substrate, 1000),
        ];
        for (name, count, most) in counts {
            if !(1..=most).contains(&count) {
                return Err(Error::invalid(name, count, &format!("[1, {most}]")));
            }
        }
        if let Some(biaxial) = self.biaxial {
            Modes {
                biaxial: Some(biaxial),
                theta: None,
            }
            .validate()?;
        }
        self.crease_study().validate()
    }
}

/// The map: a base parameter set, two axes and the settings of every point (`map-spec.json`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapStudy {
    pub base: Parameters,
    pub x: Axis,
    pub y: Axis,
    pub settings: MapSettings,
}

impl MapStudy {
    pub fn validate(&self) -> Result<()> {
        grid::validate_axes(&self.base, &self.x, &self.y)?;
        self.settings.validate()?;
        self.settings.crease_mesh.element.check_for(self.base.incompressible)?;
        for axis in [&self.x, &self.y] {
            if self.base.incompressible && axis.name.starts_with("K_") {
                return Err(Error::invalid(
                    if std::ptr::eq(axis, &self.x) { "x" } else { "y" },
                    &axis.name,
                    "a parameter incompressible tissue uses (K_l and K_s do not enter when incompressible = true)",
                ));
            }
        }
        for (_, parameters) in self.grid()? {
            parameters.validate()?;
        }
        Ok(())
    }

    /// Every point `(index, ix, iy, x, y)` with its parameter set, `index = iy * nx + ix`.
    pub fn grid(&self) -> Result<Vec<(At, Parameters)>> {
        grid::points(&self.base, &self.x, &self.y, self.settings.keep_poisson)
    }
}

impl GridStudy for MapStudy {
    type Point = MapPoint;
    const COMMAND: &'static str = "map";

    fn points(&self) -> Result<Vec<(At, Parameters)>> {
        self.grid()
    }

    fn compute_point(&self, at: At, parameters: Parameters, _folder: &Path) -> Result<MapPoint> {
        point::compute(&self.settings, &self.settings.crease_study(), at, parameters)
    }
}

/// Computes the points of `shard` (all without one) not yet in `out`, in parallel, each
/// written as soon as it is done; `tick` once per point of the share, reused ones first.
pub fn compute(study: &MapStudy, out: &Path, shard: Option<Shard>, tick: Tick) -> Result<Computed> {
    study.validate()?;
    grid::compute(study, out, shard, tick)
}

/// `map.json`.
#[derive(Clone, Debug, Serialize)]
pub struct MapReport {
    pub command: &'static str,
    pub study: MapStudy,
    pub points: Vec<MapPoint>,
    /// Sum over points of their wall time (s): the work, whatever the parallelism.
    pub point_seconds: f64,
    pub note: &'static str,
}

const MAP_NOTE: &str = "d_wrinkle: minimum of the linear theory's d_c(k) (minimum: interior, long_wave or \
    short_wave). d_crease: energy criterion of `fiberfold crease`, minimised over the fold lengths and converged \
    in the mesh, with its uncertainty d_crease_error. first: the smaller of the two, or too_close_to_call where they \
    differ by less than d_crease_error. d_wrinkle_biaxial and theta0 (with --biaxial R): the onset over \
    wavenumbers and directions of the surface under d_3 = R d, and the direction of its wave vector from X towards \
    Z (radians; the crests run perpendicular to it; empty where no direction is preferred). d_ellipticity_loss_fe: \
    the first d at which a state of the nonlinear run has a Gauss point without strong ellipticity; beyond it the \
    answer depends on the mesh. d_ellipticity_loss_fold: the same in the crease search's states, at the tip of its \
    seeded fold (singular by construction: the fold's, not the tissue's). becomes (where the wrinkle has a wavelength and comes first): a nonlinear run of `waves` \
    wavelengths 2 pi / k0 to d_wrinkle + post_buckling_range; if the tangent's inertia changes along it \
    (d_secondary), the run is repeated seeded with that change's mode (secondary_half_waves across the domain), and \
    ends where a fold or a doubled period closes on itself (in contact, one trough more than 20 % deeper than all \
    others, or deep troughs alternating with shallower ones by more than 20 %; d_reached; --follow-closed-folds \
    follows it on); the last state is classified: 'fold' if one trough is more than 20 % deeper than all others, \
    'period_doubling' if deep and shallow troughs alternate (spread above 20 %) or the surface's k/2 component is \
    at least 20 % of its k component, 'unresolved' if the path stayed periodic but its last state is unstable, 'crease' if the troughs stay alike but close on themselves, 'wrinkle' otherwise.";

/// Assembles the finished points of `study` in `out` into `map.csv`, `map.json` and the phase
/// diagram; refuses a folder of another map or with missing points.
pub fn collect(study: &MapStudy, out: &Path) -> Result<(MapReport, Vec<PathBuf>)> {
    study.validate()?;
    let points = grid::finished_points(study, out)?;
    let report = MapReport {
        command: "map",
        study: study.clone(),
        point_seconds: points.iter().map(|p| p.seconds.iter().sum::<f64>()).sum(),
        points,
        note: MAP_NOTE,
    };
    let mut files = vec![write_csv(&report, out)?];
    files.extend(figure::phase_diagram(&report, out)?);
    let json = out.join("map.json");
    write_json(&json, &report)?;
    files.push(json);
    Ok((report, files))
}

fn write_csv(report: &MapReport, out: &Path) -> Result<PathBuf> {
    let path = out.join("map.csv");
    let (x, y) = (report.study.x.name.as_str(), report.study.y.name.as_str());
    let mut table = CsvWriter::create(
        &path,
        &[
            "index",
            x,
            y,
            "d_wrinkle",
            "k0",
            "minimum",
            "d_crease",
            "d_crease_error",
            "crease_fold_length",
            "first",
            "becomes",
            "d_secondary",
            "secondary_half_waves",
            "d_first_contact",
            "d_reached",
            "d_wrinkle_biaxial",
            "theta0",
            "d_ellipticity_loss_fe",
            "d_ellipticity_loss_fold",
            "seconds",
        ],
    )?;
    let number = |v: Option<f64>| v.map_or(Cell::Empty, Cell::Number);
    for p in &report.points {
        let minimum = p.minimum.map(|m| variant_name(&m)).unwrap_or_default();
        let (first, becomes) = (
            variant_name(&p.first),
            p.becomes.map(|b| variant_name(&b)).unwrap_or_default(),
        );
        table.append_cells(&[
            Cell::Number(p.index as f64),
            Cell::Number(p.x),
            Cell::Number(p.y),
            number(p.d_wrinkle),
            number(p.k0),
            Cell::Text(&minimum),
            number(p.d_crease),
            number(p.d_crease_error),
            number(p.crease_fold_length),
            Cell::Text(&first),
            Cell::Text(&becomes),
            number(p.d_secondary),
            number(p.secondary_half_waves.map(|m| m as f64)),
            number(p.d_first_contact),
            number(p.d_reached),
            number(p.d_wrinkle_biaxial),
            number(p.theta0),
            number(p.d_ellipticity_loss_fe),
            number(p.d_ellipticity_loss_fold),
            Cell::Number(p.seconds.iter().sum()),
        ])?;
    }
    Ok(path)
}

#[cfg(test)]
mod tests;
