//! The flags of `fiberfold map` as the library's options ([`MapOptions`]): the two axes and how
//! each point is computed, read by the command line as they are.

use super::{Axis, MapSettings, MapStudy};
use crate::error::Result;
use crate::fem::ElementKind;
use crate::parameters::Parameters;
use crate::studies::crease::{CreaseMesh, Criterion};
use clap::Args;

/// The axes of a map and how each point is computed (the command line's flags).
#[derive(Clone, Debug, PartialEq, Args)]
pub struct MapOptions {
    /// Parameter along the horizontal axis (any numeric key of --set).
    #[arg(long, default_value = "mu_l")]
    pub x: String,
    /// First value of --x (units of the parameter: moduli by mu_s, angles in radians).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub x_from: f64,
    /// Last value of --x.
    #[arg(long, default_value_t = 30.0, allow_negative_numbers = true)]
    pub x_to: f64,
    /// Values of --x.
    #[arg(long, default_value_t = 12)]
    pub x_points: usize,
    /// Space the --x values geometrically (a log axis).
    #[arg(long)]
    pub x_log: bool,

    /// Parameter along the vertical axis.
    #[arg(long, default_value = "beta")]
    pub y: String,
    /// First value of --y.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub y_from: f64,
    /// Last value of --y (the default is pi/2).
    #[arg(long, default_value_t = std::f64::consts::FRAC_PI_2, allow_negative_numbers = true)]
    pub y_to: f64,
    /// Values of --y.
    #[arg(long, default_value_t = 7)]
    pub y_points: usize,
    /// Space the --y values geometrically (a log axis).
    #[arg(long)]
    pub y_log: bool,

    /// Also the direction of the first wrinkles under biaxial compression d_3 = R d (R in
    /// [0, 1]; 1 equibiaxial): each point's onset over wavenumbers and directions of the
    /// surface, written as d_wrinkle_biaxial and theta0 (radians, wave vector from X towards
    /// Z) and drawn as the crests' direction in each cell. The crease search and the nonlinear
    /// run stay in plane strain. Absent: not computed.
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    pub biaxial: Option<f64>,

    /// Let the bulk modulus stay at its base value when mu_l or mu_s is mapped (by default it
    /// scales with it, keeping the base K/mu: Table 1's Poisson ratio).
    #[arg(long)]
    pub free_bulk: bool,

    /// Crease search on the base mesh alone: no mesh sequence, no uncertainty (faster; `first`
    /// is then never too_close_to_call).
    #[arg(long)]
    pub no_crease_convergence: bool,

    /// Finite element of the crease search and the nonlinear runs (mixed, the default: the more
    /// accurate, and the only one for incompressible = true; displacement locks above
    /// K/mu ~ 100).
    #[arg(long, value_enum, default_value_t = MapSettings::default().crease_mesh.element)]
    pub element: ElementKind,

    /// Nonlinear run: wavelengths 2 pi/k0 across the half domain (2 x waves an integer).
    #[arg(long, default_value_t = 4.0, allow_negative_numbers = true)]
    pub waves: f64,
    /// Nonlinear run: Q2 elements per wavelength along X.
    #[arg(long, default_value_t = 20)]
    pub elements_per_wave: usize,
    /// Nonlinear run: elements through the layer.
    #[arg(long, default_value_t = 2)]
    pub layer_elements: usize,
    /// Nonlinear run: graded elements through the substrate (domain depth 50 H).
    #[arg(long, default_value_t = 25)]
    pub substrate_elements: usize,
    /// Nonlinear run: amplitude of the seed along the mode of the first secondary bifurcation,
    /// which breaks the symmetry between troughs (units of H; A_init of the wrinkle is 0.05).
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub seed: f64,
    /// Nonlinear run: compression beyond d_wrinkle to follow the wrinkle (the run ends at
    /// d_wrinkle + this, at most 0.7).
    #[arg(long, default_value_t = 0.2, allow_negative_numbers = true)]
    pub post_buckling_range: f64,
    /// Nonlinear run: follow a fold or a doubled period past the state where it closes on itself
    /// (in contact, one trough more than 20 % deeper than all others, or deep troughs alternating
    /// with shallower ones by more than 20 %) to d_wrinkle + --post-buckling-range. By default the
    /// run ends there: a closed trough only deepens, so the answer is `fold` or `period_doubling`
    /// either way.
    #[arg(long)]
    pub follow_closed_folds: bool,

    /// Crease search: fold lengths a (units of H), comma separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![0.5, 1.0, 2.0], allow_negative_numbers = true)]
    pub fold: Vec<f64>,
    /// Crease search: elements along X of its 12 H base mesh (refined 8 times at the crease;
    /// the onset is converged on the base mesh times 1, 2, 3).
    #[arg(long, default_value_t = MapSettings::default().crease_mesh.nx)]
    pub crease_nx: usize,
    /// Crease search: elements through the layer of the base mesh (each twice as thick as the
    /// one above it).
    #[arg(long, default_value_t = MapSettings::default().crease_mesh.layer)]
    pub crease_layer_elements: usize,
    /// Crease search: graded elements through the substrate of the base mesh.
    #[arg(long, default_value_t = MapSettings::default().crease_mesh.substrate)]
    pub crease_substrate_elements: usize,
    /// Crease search: the creased state compared with the flat state.
    #[arg(long, value_enum, default_value_t = MapSettings::default().crease_criterion)]
    pub crease_criterion: Criterion,
}

impl MapOptions {
    /// The map of these options around the parameters `base` (not yet validated:
    /// [`MapStudy::validate`]).
    pub fn study(&self, base: Parameters) -> Result<MapStudy> {
        let axis = |name: &str, from, to, points, log| Axis {
            name: name.to_string(),
            from,
            to,
            points,
            log,
        };
        let defaults = MapSettings::default();
        Ok(MapStudy {
            base,
            x: axis(&self.x, self.x_from, self.x_to, self.x_points, self.x_log),
            y: axis(&self.y, self.y_from, self.y_to, self.y_points, self.y_log),
            settings: MapSettings {
                waves: self.waves,
                elements_per_wave: self.elements_per_wave,
                layer_elements: self.layer_elements,
                substrate_elements: self.substrate_elements,
                seed: self.seed,
                post_buckling_range: self.post_buckling_range,
                follow_closed_folds: self.follow_closed_folds,
                crease_mesh: CreaseMesh {
                    nx: self.crease_nx,
                    layer: self.crease_layer_elements,
                    substrate: self.crease_substrate_elements,
                    element: self.element,
                    ..defaults.crease_mesh
                },
                fold_lengths: self.fold.clone(),
                keep_poisson: !self.free_bulk,
                crease_criterion: self.crease_criterion,
                crease_refinement: match self.no_crease_convergence {
                    true => None,
                    false => defaults.crease_refinement,
                },
                biaxial: self.biaxial,
                ..defaults
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Flags {
        #[command(flatten)]
        options: MapOptions,
    }

    fn parse(flags: &[&str]) -> MapOptions {
        Flags::try_parse_from(["map"].iter().chain(flags)).unwrap().options
    }

    #[test]
    fn the_flags_at_their_defaults_are_the_default_settings() {
        let study = parse(&[]).study(Parameters::default()).unwrap();
        assert_eq!(study.settings, MapSettings::default());
        assert_eq!((study.x.name.as_str(), study.x.points), ("mu_l", 12));
        assert_eq!(
            (study.y.name.as_str(), study.y.to),
            ("beta", std::f64::consts::FRAC_PI_2)
        );
        let chosen = parse(&[
            "--x-points",
            "3",
            "--no-crease-convergence",
            "--fold",
            "1,2",
            "--biaxial",
            "1",
        ])
        .study(Parameters::default())
        .unwrap();
        assert_eq!(chosen.x.points, 3);
        assert_eq!(chosen.settings.crease_refinement, None);
        assert_eq!(chosen.settings.fold_lengths, vec![1.0, 2.0]);
        assert_eq!(chosen.settings.biaxial, Some(1.0));
    }
}
