//! Every option with a bound: 0, negative, huge and non-finite values exit
//! with status 2 and a message naming the option; nothing is printed and
//! nothing is sized by the value first (a huge count used to abort on a
//! failed allocation). Runs the CLI in-process through `flexure_cli::run`.

use crate::cli::run;

const HUGE: [&str; 4] = ["1099511627776", "18446744073709551616", "1e300", "99999999999999999999999999"];
const NOT_FINITE: [&str; 5] = ["nan", "inf", "-inf", "NaN", "infinity"];
const NOT_A_NUMBER: [&str; 3] = ["abc", "", "1,2"];

/// A command, the bounded option given last, and the values it must refuse besides the common ones.
type Bounded = (&'static [&'static str], &'static str, &'static [&'static str]);

const BOUNDED: [Bounded; 5] = [
    (&["kinematics", "--alpha", "0"], "--order", &["0", "-1", "65", "2.5"]),
    (&["compliance"], "--quadrature", &["0", "-1", "1025", "3.0"]),
    (&["connect", "--pose", "1,0.5,0.5"], "--segments", &["0", "-1", "65"]),
    (&["deflect", "--moment", "1"], "--max-iterations", &["0", "-1", "10001"]),
    (&["deflect", "--moment", "1"], "--tolerance", &["0", "-1", "1", "2"]),
];

#[test]
fn bounded_options_reject_out_of_range_values() {
    let mut checked = 0;
    for (before, option, own) in BOUNDED {
        for value in own.iter().chain(&HUGE).chain(&NOT_FINITE).chain(&NOT_A_NUMBER) {
            for json in [false, true] {
                let mut args: Vec<&str> = before.to_vec();
                args.extend([option, *value]);
                if json {
                    args.push("--json");
                }
                let (code, out, err) = run(&args);
                assert_eq!(code, 2, "{args:?}: {out}{err}");
                assert!(err.contains(option), "{args:?}: stderr must name {option}: {err}");
                assert!(out.is_empty(), "{args:?}: {out}");
                checked += 1;
            }
        }
    }
    assert!(checked > 100);
}

/// A sweep's COUNT: from 2 to 10000 values, checked before the values are made.
#[test]
fn sweep_counts_are_bounded() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/paper_tendon.toml");
    for count in ["0", "1", "-3", "10001", "nan", "x"].iter().chain(&HUGE) {
        let tendon = format!("0:1:{count}");
        let sweep = format!("tendon.flexor.tension=0:1:{count}");
        for args in [
            vec!["tendon", "--root-offset", "0.1", "--tip-offset", "0.1", "--sweep", tendon.as_str()],
            vec!["solve", file, "--sweep", sweep.as_str()],
            vec!["draw", file, "--out", "/tmp/never-written.svg", "--sweep", sweep.as_str()],
        ] {
            let (code, out, err) = run(&args);
            assert_eq!(code, 2, "{args:?}: {out}{err}");
            assert!(err.contains("--sweep") && err.contains("COUNT"), "{args:?}: {err}");
        }
    }
}

/// Plain numbers: non-finite values are refused by name.
#[test]
fn numbers_must_be_finite() {
    for option in ["--moment", "--fx", "--fy", "--force", "--length", "--ei"] {
        // `--ei 1,2` is a linear taper (see `sections::`).
        for value in NOT_FINITE.iter().chain(&NOT_A_NUMBER).filter(|v| !(option == "--ei" && **v == "1,2")) {
            let (code, _, err) = run(&["deflect", option, value]);
            assert_eq!(code, 2, "{option} {value}");
            assert!(err.contains(option), "{option} {value}: {err}");
        }
    }
    for value in ["nan", "infdeg", "xdeg", "deg"] {
        let (code, _, err) = run(&["deflect", "--force", "1", "--angle", value]);
        assert_eq!(code, 2, "--angle {value}");
        assert!(err.contains("--angle"), "{err}");
    }
}

/// `--angle 45` is 45 radians, probably meant as degrees: a warning says so,
/// and the answer is still given. Within 2π, or with `deg`, no warning.
#[test]
fn bare_angles_beyond_two_pi_warn() {
    let (code, out, err) = run(&["deflect", "--force", "1", "--angle", "45"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.is_empty());
    assert!(err.starts_with("warning: --angle 45 is read as radians") && err.contains("45deg"), "{err}");
    let (_, _, err) = run(&["connect", "--pose", "90,0.5,0.5"]);
    assert!(err.contains("warning: --pose PHI 90") && err.contains("90deg"), "{err}");
    for quiet in [["--angle", "6.28"], ["--angle", "-6.2"], ["--angle", "400deg"]] {
        let (code, _, err) = run(&["deflect", "--force", "1", quiet[0], quiet[1]]);
        assert_eq!(code, 0, "{err}");
        assert!(err.is_empty(), "{quiet:?}: {err}");
    }
}

/// Input that would overflow an answer is refused before it is used, never
/// printed as a `null` with status 0: U = α1²/2 for α1 = 1e300 would overflow
/// (Eq. 9), and coordinates are bounded by 1e6 rad. (The emitter's own
/// refusal of a non-finite answer is tested beside it, in `src/lib.rs`.)
#[test]
fn non_finite_results_are_errors() {
    for json in [true, false] {
        let mut args = vec!["kinematics", "--alpha", "1e300,0,0"];
        if json {
            args.push("--json");
        }
        let (code, out, err) = run(&args);
        assert_eq!(code, 2);
        assert!(out.is_empty(), "{out}");
        assert!(err.contains("alpha") && err.contains("1e6"), "{err}");
    }
    // --limit used to print `"stability_limit": null` when the load stays stable (a tension does).
    let (code, out, err) = run(&["deflect", "--fx", "1", "--limit", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["stability_limit"], serde_json::json!({"factor": 1000.0, "status": "stable_up_to"}), "{v}");
    assert!(!out.contains("null"));
    // A 1 N compression of a free-tip column loses stability at Euler's load
    // π²/4 (paper Table I; the order-3 model is 1.2e-4 above it, so 1e-3).
    let (code, out, err) = run(&["deflect", "--fx", "-1", "--limit", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let euler = std::f64::consts::PI.powi(2) / 4.0;
    assert_eq!(v["stability_limit"]["status"], "lost", "{v}");
    assert!((v["stability_limit"]["factor"].as_f64().unwrap() / euler - 1.0).abs() < 1e-3, "{v}");
}

/// A file that cannot be written is named.
#[test]
fn failed_writes_name_the_path() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger.toml");
    let (code, out, err) = run(&["draw", file, "--out", "/no/such/dir/x.svg"]);
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert!(err.contains("writing /no/such/dir/x.svg") && err.contains("No such file"), "{err}");
    let (code, _, err) = run(&["reproduce", "--out", "/proc/no-such-dir/report"]);
    assert_eq!(code, 2);
    assert!(err.contains("/proc/no-such-dir/report"), "{err}");
}

/// `--help` and `--version` answer on stdout with status 0; a usage error is status 2.
#[test]
fn help_and_usage() {
    let (code, out, _) = run(&["--help"]);
    assert_eq!(code, 0);
    assert!(out.contains("kinematics"));
    let (code, out, _) = run(&["--version"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("flexure "));
    let (code, out, err) = run(&["no-such-command"]);
    assert_eq!(code, 2);
    assert!(out.is_empty() && err.contains("no-such-command"), "{err}");
}

/// Every file option reads at most 64 MiB (issue 21: `solve /dev/zero` and
/// `deflect --input /dev/zero` read forever, growing by 170 MB/s): each is
/// refused with exit 2, naming the file and the limit, and prints nothing.
#[test]
fn every_file_option_is_bounded() {
    let cases: [&[&str]; 8] = [
        &["solve", "/dev/zero"],
        &["buckle", "/dev/zero"],
        &["draw", "/dev/zero", "--out", "/dev/null"],
        &["draw", "/dev/zero", "--simulate", "1", "--out", "/dev/null"],
        &["modes", "/dev/zero"],
        &["simulate", "/dev/zero", "--duration", "1"],
        &["deflect", "--input", "/dev/zero"],
        &["kinematics", "--input", "/dev/zero"],
    ];
    for args in cases {
        let (code, out, err) = run(args);
        assert_eq!(code, 2, "{args:?}");
        assert!(out.is_empty() && err.contains("/dev/zero: larger than 64 MiB"), "{args:?}: {err}");
    }
}

/// Messages name what was given and what happened (issue 21): a duration
/// too short to sample is blamed on `--duration` (it blamed `--every`,
/// which was not given), a load beyond 1e30 is refused by name instead of
/// stalling with "residual NaN", and long numbers are shown with an exponent.
#[test]
fn messages_name_what_was_given() {
    let finger = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger_dynamics.toml");
    let (code, _, err) = run(&["simulate", finger, "--duration", "5e-324"]);
    assert_eq!(code, 2);
    assert!(err.contains("--duration = 5e-324: must be at least 1e-12 s") && !err.contains("--every"), "{err}");
    let (code, _, err) = run(&["deflect", "--moment", "1e308", "--fy", "1"]);
    assert_eq!(code, 2);
    assert!(err.contains("--moment = 1e308: must be at most 1e30") && !err.contains("NaN"), "{err}");
}
