//! Tests of the parameter set: the table, files, `--set`, validation.

use super::*;

#[test]
fn defaults_are_table_1_and_round_trip_through_toml() {
    let p = Parameters::default();
    p.validate().unwrap();
    assert_eq!(Parameters::from_toml_str(&p.to_toml()).unwrap(), p);
}

/// Every row of the table: its key is in the help and the parameter file with its default,
/// and a value outside its range is refused with that range named.
#[test]
fn the_table_drives_help_file_and_validation() {
    let (help, file) = (set_help(), Parameters::default().to_toml());
    for spec in &TABLE {
        assert!(
            file.contains(&format!("{} = ", spec.name)) && file.contains(spec.meaning),
            "{}",
            spec.name
        );
        if let Kind::Number { default, range, .. } = spec.kind {
            assert!(
                help.contains(&format!("  {} = {default}, in {}: ", spec.name, range.short())),
                "{help}"
            );
            let outside = match range {
                Range::Angle => f64::INFINITY,
                _ => -1.0,
            };
            let mut p = Parameters::default();
            p.set_number(spec.name, outside).unwrap();
            let message = p.validate().unwrap_err().to_string();
            assert!(
                message.contains(spec.name) && message.contains(range.describe()),
                "{message}"
            );
        }
    }
}

#[test]
fn set_overrides_and_rejects() {
    let mut p = Parameters::default();
    p.set("beta=0.5").unwrap();
    p.set("tension_only=true").unwrap();
    assert_eq!(p.beta, 0.5);
    assert!(p.tension_only);
    let unknown = p.set("gamma=1").unwrap_err().to_string();
    assert!(unknown.contains("gamma") && unknown.contains("mu_f"), "{unknown}");
    assert!(p.set("mu_l=abc").is_err());
    assert!(p.set("mu_l").is_err());
}

#[test]
fn integers_in_toml_are_numbers() {
    let p = Parameters::from_toml_str("mu_f = 20\nbeta = 0.25").unwrap();
    assert_eq!(p.mu_f, 20.0);
    assert_eq!(p.beta, 0.25);
}

#[test]
fn validation_names_parameter_and_range() {
    let p = Parameters {
        phi_f: 1.5,
        ..Parameters::default()
    };
    let msg = p.validate().unwrap_err().to_string();
    assert!(msg.contains("phi_f") && msg.contains("[0, 1]"), "{msg}");
    let p = Parameters {
        mu_l: -1.0,
        ..Parameters::default()
    };
    assert!(p.validate().unwrap_err().to_string().contains("mu_l"));
    // An infinite bulk modulus, in a file or after --set, is pointed to incompressible = true.
    let file = Parameters::from_toml_str("K_s = inf");
    let set = |assignment: &str| {
        let mut p = Parameters::default();
        p.set(assignment).and_then(|_| p.validate()).unwrap_err().to_string()
    };
    for msg in [file.unwrap_err().to_string(), set("K_l=inf")] {
        assert!(msg.contains("incompressible = true") && msg.contains("1e12"), "{msg}");
    }
    assert!(!set("mu_l=inf").contains("incompressible"));
    assert!(validate_compression("d", 1.0).is_err());
    assert!(validate_compression("d", f64::NAN).is_err());
}

#[test]
fn a_shear_modulus_takes_its_bulk_modulus_along_unless_that_is_set_apart() {
    let mut p = Parameters::default();
    p.set_number_keeping_poisson("mu_l", 100.0, &[]).unwrap();
    assert_eq!((p.mu_l, p.K_l), (100.0, 300.0));
    let mut p = Parameters::default();
    p.set_number_keeping_poisson("mu_s", 2.0, &["K_s"]).unwrap();
    assert_eq!((p.mu_s, p.K_s), (2.0, 3.0));
    let mut p = Parameters::default();
    p.set_number_keeping_poisson("beta", 0.5, &[]).unwrap();
    assert_eq!((p.beta, p.K_l, p.K_s), (0.5, 30.0, 3.0));
}

#[test]
fn a_negative_poisson_ratio_and_volume_fractions_over_one_are_warned_of() {
    assert!(Parameters::default().warnings().is_empty());
    let p = Parameters {
        mu_l: 100.0,
        K_l: 30.0,
        phi_m: 0.95,
        ..Parameters::default()
    };
    let warnings = p.warnings();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    // nu = (3 K - 2 mu) / (2 (3 K + mu)) = (90 - 200) / (2 * 190).
    assert!(
        warnings[0].contains("layer") && warnings[0].contains("nu = -0.289"),
        "{warnings:?}"
    );
    assert!(warnings[1].contains("phi_m + phi_f = 1.05"), "{warnings:?}");
    let incompressible = Parameters {
        K_l: 1e-6,
        incompressible: true,
        ..Parameters::default()
    };
    assert!(incompressible.warnings().is_empty());
}
