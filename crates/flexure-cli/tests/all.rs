//! The command line's integration tests: one module per subject (one file
//! in `tests/`), linked into one test binary rather than one per file, so a
//! change to the library or the CLI rebuilds one test crate, not nine.
//! Cargo's auto-discovery of `tests/*.rs` is off (`autotests = false` in
//! Cargo.toml), so a new file is added below; `every_test_file_is_compiled`
//! fails until it is.
//!
//! One subject: `cargo test -p flexure-cli --test all fuzz::`.

mod analyses;
mod batch;
mod characterization;
mod cli;
mod docs;
mod draw3d;
mod estimate;
mod examples;
mod export;
mod figures;
mod findings;
mod first_hour;
mod first_mechanism;
mod fuzz;
mod joint;
mod mechanism;
mod modes;
mod options;
mod reproduce;
mod sections;
mod simulate;
mod spatial;
mod spatial_mechanism;

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
