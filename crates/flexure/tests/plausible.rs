//! Input that is implausible as given: sections thicker than the flexure is
//! long, refused alike in the plane and in space; numbers in the wrong unit,
//! told with what was probably meant; and a continuation that stops at
//! rounding, said as such (issue "the first hour", items 2; "robust",
//! item 5).

use flexure::mechanism::file::{Document, habits, spatial_from_toml};
use flexure::section::{Profile, SectionSpec, SpatialSection, thinner_than_long};
use flexure::spatial::{SpatialFlexure, SpatialSpec};
use flexure::{Error, Flexure, StaticsData, TipLoad, deflect};

/// The planar refusal and the spatial one are one check: the same message
/// for a 2 m thick section on a 1 m flexure, rectangle and rod alike.
#[test]
fn a_spatial_section_thicker_than_long_is_refused_as_the_planar_one() {
    let c = Profile::Constant;
    let planar =
        SectionSpec { modulus: Some(200e9), width: Some(c(1e-3)), thickness: Some(c(2.0)), ..Default::default() };
    let e = Flexure::new(1.0, 1.0, 3).unwrap().with_section(planar.section().unwrap().unwrap()).unwrap_err();
    let spatial =
        SpatialSpec { modulus: Some(200e9), width: Some(c(1e-3)), thickness: Some(c(2.0)), ..Default::default() };
    let s = spatial.build().unwrap_err();
    assert_eq!(e.to_string(), s.to_string());
    assert_eq!(s.to_string(), thinner_than_long("thickness", 1.0, [(0.0, 2.0)]).unwrap_err().to_string());
    // A round rod by its diameter; equal to the length is a (stubby) flexure still.
    let rod = |d: f64| SpatialFlexure::new(0.01, SpatialSection::circle(200e9, 0.3, c(d)).unwrap(), [3; 3]);
    let e = rod(0.02).unwrap_err().to_string();
    assert!(e.starts_with("invalid diameter = 0.02 m at t = 0, on a flexure of length 0.01 m"), "{e}");
    assert!(rod(0.01).is_ok());
    // A taper is thickest at an end: its tip here.
    let taper = SpatialSection::rectangle(
        200e9,
        flexure::section::Shear::Poisson(0.3),
        c(0.01),
        Profile::Linear { root: 1e-3, tip: 0.015 },
    )
    .unwrap();
    let e = SpatialFlexure::new(0.01, taper, [3; 3]).unwrap_err().to_string();
    assert!(e.contains("thickness = 0.015 m at t = 1"), "{e}");
}

/// A spatial file refuses it too, placed at the key.
#[test]
fn a_spatial_file_refuses_a_section_thicker_than_long_at_its_key() {
    let text = "dimension = 3\n[[joint]]\nname = \"leg\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
                length = 0.01\nmodulus = 1e9\nwidth = 0.01\nthickness = 0.02\n";
    let e = spatial_from_toml(text).unwrap_err().to_string();
    assert!(e.starts_with("line 10, column 13: joint \"leg\": thickness = 0.02 m at t = 0"), "{e}");
}

/// A shape or material without a modulus is refused by name, as the planar
/// SectionSpec refuses it, not ignored.
#[test]
fn a_spatial_section_without_a_modulus_refuses_the_keys_it_would_ignore() {
    let c = Profile::Constant;
    let cases: [(&str, SpatialSpec); 5] = [
        ("diameter", SpatialSpec { diameter: Some(c(1e-3)), ..Default::default() }),
        ("width", SpatialSpec { width: Some(c(1e-3)), ..Default::default() }),
        ("thickness", SpatialSpec { thickness: Some(c(1e-3)), ..Default::default() }),
        ("poisson", SpatialSpec { poisson: Some(0.3), ..Default::default() }),
        ("shear_modulus", SpatialSpec { shear_modulus: Some(8e10), ..Default::default() }),
    ];
    for (name, spec) in cases {
        match spec.build() {
            Err(Error::InvalidParameter { name: n, .. }) => assert_eq!(n, name),
            other => panic!("{name}: expected a refusal naming it, got {other:?}"),
        }
    }
}

/// GPa given as Pa (the first hour's `--modulus 200`): the continuation
/// stalls with a residual at rounding, 4e-14 N·m against a tolerance of
/// 2e-14 N·m (1e-12 of F·L = 0.02 N·m). The message says the state reached
/// is in equilibrium and the step could not advance, and points at the
/// units, never "did not converge".
#[test]
fn a_stall_at_rounding_is_not_called_non_convergence() {
    let ei = flexure::bending_stiffness(200.0, 0.01, 2e-4, None).unwrap();
    let f = Flexure::new(0.04, ei, 3).unwrap();
    let mut data = StaticsData::new(&f);
    let e = deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: 0.5 }, &mut data, &Default::default()).unwrap_err();
    let Error::ContinuationStalled { rounding, residual, .. } = &e else { panic!("expected a stall, got {e}") };
    assert!(*rounding && *residual < 1e-12, "{e}");
    let text = e.to_string();
    assert!(!text.contains("did not converge"), "{text}");
    assert!(text.contains("in equilibrium") && text.contains("stopped at rounding"), "{text}");
    assert!(text.contains("check the units (a modulus in Pa"), "{text}");
    // The steel it was meant to be bends, answered.
    let ei = flexure::bending_stiffness(200e9, 0.01, 2e-4, None).unwrap();
    let f = Flexure::new(0.04, ei, 3).unwrap();
    let mut data = StaticsData::new(&f);
    assert!(deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: 0.5 }, &mut data, &Default::default()).is_ok());
}

/// The file habits, each placed at its key: a modulus in GPa, a length in
/// millimetres (with a section, and without one beside millimetre offsets),
/// and a spatial origin whose third number is the planar angle; none for
/// the same file written right.
#[test]
fn habits_are_told_at_their_keys_with_what_was_meant() {
    let joint = |extra: &str| {
        format!(
            "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\n{extra}\n\
             [[joint]]\nname = \"c\"\nkind = \"flexure\"\nparent = \"b\"\nchild = \"d\"\norigin = [0.03, 0.0, 0.0]\nlength = 0.012\nei = 1e-3\n"
        )
    };
    let found =
        habits(&Document::parse(&joint("length = 0.04\nmodulus = 200\nwidth = 0.01\nthickness = 2e-4")).unwrap());
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].starts_with("line 7, column 11: joint \"a\": modulus = 200 is read as Pa"), "{found:?}");
    assert!(found[0].ends_with("write 200e9 if GPa were meant"), "{found:?}");
    let found =
        habits(&Document::parse(&joint("length = 40\nmodulus = 2e11\nwidth = 0.01\nthickness = 2e-4")).unwrap());
    assert!(found.len() == 1 && found[0].contains("length = 40 is read as metres") && found[0].contains("write 0.04"));
    let found = habits(&Document::parse(&joint("length = 15\nei = 1.4558e-3")).unwrap());
    assert!(found.len() == 1 && found[0].starts_with("line 6, column 10: joint \"a\": length = 15 is read as metres"));
    assert!(
        found[0].contains("every other length of the mechanism is 0.03 m or less") && found[0].contains("write 0.015")
    );
    assert!(
        habits(&Document::parse(&joint("length = 0.015\nmodulus = 2e11\nwidth = 0.01\nthickness = 2e-4")).unwrap())
            .is_empty()
    );
    // In space: the planar habit origin = [x, y, φ], and the same file with rpy.
    let spatial = |rpy: &str| {
        format!(
            "dimension = 3\n[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\n\
             origin = [0.0, 0.0, 1.5708]\n{rpy}length = 0.03\nei = 1e-3\n"
        )
    };
    let found = habits(&Document::parse(&spatial("")).unwrap());
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].starts_with("line 7, column 10: joint \"a\": origin's third number 1.5708 is read as z = 1.5708 m")
    );
    assert!(found[0].contains("rpy = [0.0, 0.0, 1.5708]"), "{found:?}");
    assert!(habits(&Document::parse(&spatial("rpy = [0.0, 0.0, 0.5]\n")).unwrap()).is_empty());
    // A planar file's origin holds its angle: nothing to tell.
    assert!(
        habits(&Document::parse(&joint("length = 0.03\nei = 1e-3\norigin = [0.0, 0.0, 1.5708]")).unwrap()).is_empty()
    );
}
