//! # Verification: scenario input that must be refused
//!
//! - **Only regular files of bounded size are read**: `/dev/zero` (a device that never
//!   ends), a folder, and a file one byte over [`MAX_SCENARIO_BYTES`] are refused with an
//!   I/O error naming the path; a valid scenario padded with a comment to exactly the limit
//!   is read.
//! - **Contradictory boundary conditions name both entries**: two `[[dirichlet]]` entries
//!   prescribing one component with different values on one part, or at the corner node
//!   shared by two parts; a `[[contact]]` part given twice; a traction component on a
//!   component a Dirichlet entry prescribes on the same part; a contact part that is also a
//!   Dirichlet part. Consistent redundancy (equal values, disjoint components, a traction
//!   on the free component of a roller) is accepted.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::scenario::{Scenario, MAX_SCENARIO_BYTES};
use hemicontact::Error;

mod common;

/// A 2 × 2 square (parts bottom, right, top, left) with `extra` TOML appended.
fn square(extra: &str) -> String {
    format!(
        "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [2, 2]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n{extra}"
    )
}

/// The scenario error of `text`, as displayed.
fn error_of(text: &str) -> String {
    let scenario = Scenario::from_str(text, "test.toml").unwrap();
    match scenario.into_problem() {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e @ Error::Scenario { .. }) => e.to_string(),
        Err(e) => panic!("not a scenario error: {e}"),
    }
}

fn accepted(text: &str) {
    let scenario = Scenario::from_str(text, "test.toml").unwrap();
    if let Err(e) = scenario.into_problem() {
        panic!("refused: {e}\n{text}");
    }
}

fn assert_names(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "`{p}` missing from: {message}");
    }
}

#[test]
fn dev_zero_is_refused_as_not_a_regular_file() {
    let start = std::time::Instant::now();
    let e = Scenario::from_file(std::path::Path::new("/dev/zero")).unwrap_err();
    assert!(matches!(e, Error::Io { .. }), "{e}");
    assert_names(&e.to_string(), &["/dev/zero", "not a regular file"]);
    assert!(start.elapsed().as_secs() < 2);
}

#[test]
fn folder_is_refused_as_not_a_regular_file() {
    let dir = common::fresh_dir("scenario-input");
    let e = Scenario::from_file(&dir).unwrap_err();
    assert_names(
        &e.to_string(),
        &[&dir.display().to_string(), "not a regular file"],
    );
}

#[test]
fn size_limit_is_inclusive_and_one_byte_more_is_refused() {
    let dir = common::fresh_dir("scenario-input");
    let base = square("[[dirichlet]]\npart = \"bottom\"\n");
    let limit = usize::try_from(MAX_SCENARIO_BYTES).unwrap();
    // A comment line "#xxx…\n" pads the text to exactly the limit.
    let mut at_limit = base.clone();
    at_limit.push('#');
    at_limit.push_str(&"x".repeat(limit - base.len() - 2));
    at_limit.push('\n');
    assert_eq!(at_limit.len(), limit);
    let ok = dir.join("at-limit.toml");
    std::fs::write(&ok, &at_limit).unwrap();
    Scenario::from_file(&ok).unwrap().into_problem().unwrap();

    let over = dir.join("over.toml");
    std::fs::write(&over, format!("{at_limit} ")).unwrap();
    let e = Scenario::from_file(&over).unwrap_err().to_string();
    assert_names(
        &e,
        &[
            "over.toml",
            &format!("{} bytes", limit + 1),
            &MAX_SCENARIO_BYTES.to_string(),
        ],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn two_dirichlet_values_on_one_part_are_a_contradiction() {
    let e = error_of(&square(
        "[[dirichlet]]\npart = \"bottom\"\n\
         [[dirichlet]]\npart = \"left\"\ncomponents = [\"x\"]\n\
         [[dirichlet]]\npart = \"bottom\"\nvalue = [0.0, 0.5]\n",
    ));
    assert_names(
        &e,
        &[
            "test.toml",
            "dirichlet[2].value",
            "dirichlet[0]",
            "u_y",
            "0.5",
            "[0.0, 0.5]",
            "bottom",
        ],
    );
}

#[test]
fn overlapping_components_with_different_values_are_a_contradiction() {
    // dirichlet[1] prescribes x only, but with a value other than dirichlet[0]'s x.
    let e = error_of(&square(
        "[[dirichlet]]\npart = \"bottom\"\nvalue = [0.0, 0.0]\n\
         [[dirichlet]]\npart = \"bottom\"\ncomponents = [\"x\"]\nvalue = [0.25, 0.0]\n",
    ));
    assert_names(&e, &["dirichlet[1].value", "dirichlet[0]", "u_x", "0.25"]);
}

#[test]
fn different_values_at_a_shared_corner_are_a_contradiction() {
    // The bottom is clamped; the left side is pulled 0.1 m along x: the corner (0, 0)
    // belongs to both.
    let e = error_of(&square(
        "[[dirichlet]]\npart = \"bottom\"\n\
         [[dirichlet]]\npart = \"left\"\ncomponents = [\"x\"]\nvalue = [0.1, 0.0]\n",
    ));
    assert_names(
        &e,
        &[
            "dirichlet[1].value",
            "dirichlet[0]",
            "u_x",
            "[0.0, 0.0]",
            "bottom",
            "left",
        ],
    );
}

#[test]
fn consistent_dirichlet_entries_are_accepted() {
    // Equal values at the shared corners (0, 0) and (0, 1), disjoint components on one
    // part (top: y by one entry, x by another), an exact repeat.
    accepted(&square(
        "[[dirichlet]]\npart = \"bottom\"\n\
         [[dirichlet]]\npart = \"left\"\ncomponents = [\"x\"]\n\
         [[dirichlet]]\npart = \"top\"\ncomponents = [\"y\"]\nvalue = [0.0, -0.1]\n\
         [[dirichlet]]\npart = \"top\"\ncomponents = [\"x\"]\nvalue = [0.0, 0.3]\n\
         [[dirichlet]]\npart = \"bottom\"\n",
    ));
}

#[test]
fn same_contact_part_twice_is_a_contradiction() {
    let e = error_of(&square(
        "[[dirichlet]]\npart = \"bottom\"\n\
         [[contact]]\npart = \"left\"\nc_nu = 100.0\n\
         [[contact]]\npart = \"right\"\nc_nu = 100.0\n\
         [[contact]]\npart = \"left\"\nc_nu = 200.0\n",
    ));
    assert_names(&e, &["contact[2].part", "\"left\"", "contact[0]"]);
}

#[test]
fn contact_on_a_dirichlet_part_names_the_dirichlet_entry() {
    let e = error_of(&square(
        "[[dirichlet]]\npart = \"bottom\"\n\
         [[dirichlet]]\npart = \"left\"\ncomponents = [\"x\"]\n\
         [[contact]]\npart = \"left\"\nc_nu = 100.0\n",
    ));
    assert_names(&e, &["contact[0].part", "\"left\"", "dirichlet[1]"]);
}

#[test]
fn traction_on_a_prescribed_component_is_a_contradiction() {
    let e = error_of(&square(
        "[[dirichlet]]\npart = \"bottom\"\n\
         [[dirichlet]]\npart = \"top\"\ncomponents = [\"y\"]\nvalue = [0.0, -0.01]\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [0.0, -900.0]\n",
    ));
    assert_names(
        &e,
        &[
            "loads.traction[0].value",
            "dirichlet[1]",
            "u_y",
            "-900",
            "top",
        ],
    );
}

#[test]
fn traction_on_the_free_component_of_a_roller_is_accepted() {
    accepted(&square(
        "[[dirichlet]]\npart = \"bottom\"\n\
         [[dirichlet]]\npart = \"top\"\ncomponents = [\"y\"]\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [50.0, 0.0]\n",
    ));
}
