//! The library's integration tests: one module per subject (one file in
//! `tests/`), linked into one test binary rather than one per file, so a
//! change to the library rebuilds one test crate, not twenty-two. Cargo's
//! auto-discovery of `tests/*.rs` is off (`autotests = false` in
//! Cargo.toml), so a new file is added below; `every_test_file_is_compiled`
//! fails until it is. `allocation.rs` is a binary of its own: its counting
//! global allocator would serve every test here.
//!
//! One subject: `cargo test -p flexure --test all basis::`.

mod auto_solve;
mod basis;
mod buckling;
mod compliance;
mod connect;
mod contact_corner;
mod contact_file;
mod contact_gap;
mod contact_jet;
mod contact_rolling;
mod contact_shape;
mod contact_statics;
mod coordinates;
mod dynamics_contact;
mod dynamics_integrate;
mod dynamics_integrate_event;
mod dynamics_mass;
mod dynamics_mechanism;
mod dynamics_mechanism_modes;
mod dynamics_modes;
mod dynamics_simulation;
mod dynamics_vibration;
mod eigen_estimate;
mod elastica;
mod elastica_path;
mod energy;
mod estimate;
mod export;
mod file_spatial;
mod findings;
mod format;
mod joints;
mod kinematics;
mod layers;
mod mechanism;
mod mechanism_derivatives;
mod mechanism_files;
mod mechanism_weight;
mod ode;
mod plausible;
mod prb;
mod quadrature;
mod reference;
mod reference_contact;
mod right_angle_cantilever;
mod rod;
mod section;
mod section_exact;
mod section_spatial;
mod seeded;
mod segments;
mod sincos;
mod solver;
mod space;
mod space_spatial;
mod spatial_dynamics;
mod spatial_eigen_estimates;
mod spatial_energy;
mod spatial_estimate;
mod spatial_examples;
mod spatial_files;
mod spatial_findings;
mod spatial_flexure_mass;
mod spatial_kinematics;
mod spatial_mechanism;
mod spatial_mechanism_derivatives;
mod spatial_shape;
mod spatial_statics;
mod spatial_validation;
mod stability_limit;
mod stages;
mod statics;
mod stops;
mod tendon;

/// Every `tests/*.rs` file is a module here or a `[[test]]` target of
/// Cargo.toml: with auto-discovery off, a file named in neither would
/// silently never run.
#[test]
fn every_test_file_is_compiled() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = std::fs::read_to_string(dir.join("tests/all.rs")).unwrap();
    let manifest = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
    let mut files = 0;
    for entry in std::fs::read_dir(dir.join("tests")).unwrap() {
        let entry = entry.unwrap();
        let name = entry.file_name().into_string().unwrap();
        let (module, path) = match name.strip_suffix(".rs") {
            Some(stem) => (format!("mod {stem};"), format!("path = \"tests/{name}\"")),
            None if entry.path().is_dir() => (String::new(), format!("path = \"tests/{name}/")),
            None => continue,
        };
        files += 1;
        let declared = root.lines().any(|line| line.trim() == module) || manifest.contains(&path);
        assert!(declared, "tests/{name} belongs to no test target: add `{module}` to tests/all.rs");
    }
    assert!(files >= 2, "only {files} test files found in {}", dir.display());
}
