//! # Verification: the friction law's input
//!
//! - **`potential` is a table like `mu`**: `{ kind = "norm" }`, `{ kind = "nonconvex",
//!   a = … }`, `{ kind = "regularized", rho = … }` give the same laws as the deprecated
//!   bare names with sibling parameters, which are still read, with a note naming the new
//!   form; both forms at once, an unknown kind or a parameter of another kind are refused
//!   naming the field and what is allowed.
//! - **The numerical regularization is a law parameter**: `[contact.friction]
//!   regularization` sets it per part (default 10⁻⁸); the deprecated `[solver.outer]
//!   friction_regularization` still sets it for every part, with a note; both with
//!   different values are a contradiction naming both keys; it is refused with exact
//!   stick/slip, with the smooth law (19) and outside (0, 0.01).
//! - **Exact stick/slip only for the norm's potentials**: `exact = true` with the
//!   regularized law is refused.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::contact::{Friction, FrictionPotential, NormTreatment};
use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::Error;

/// A 2 × 2 square clamped at the bottom with its left side in frictional contact; the
/// `[contact.friction]` table holds `friction`, and `extra` is appended to the file.
fn square(friction: &str, extra: &str) -> String {
    format!(
        "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [2, 2]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"bottom\"\n\
         [[contact]]\npart = \"left\"\ngap = 0.1\nc_nu = 100.0\n\
         [contact.friction]\nbound = \"coulomb\"\nmu = {{ law = \"constant\", mu = 0.3 }}\n\
         {friction}\n{extra}"
    )
}

fn problem(text: &str) -> (Problem, Vec<String>) {
    let scenario = Scenario::from_str(text, "test.toml").unwrap();
    match scenario.into_problem_with_notes() {
        Ok(p) => p,
        Err(e) => panic!("refused: {e}\n{text}"),
    }
}

fn friction(text: &str) -> (Friction, Vec<String>) {
    let (p, notes) = problem(text);
    (p.contact()[0].friction.clone().expect("friction"), notes)
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

/// The parse error of `text`, as displayed.
fn parse_error_of(text: &str) -> String {
    match Scenario::from_str(text, "test.toml") {
        Ok(_) => panic!("parsed:\n{text}"),
        Err(e @ Error::Parse { .. }) => e.to_string(),
        Err(e) => panic!("not a parse error: {e}"),
    }
}

fn assert_names(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "`{p}` missing from: {message}");
    }
}

#[test]
fn table_and_deprecated_forms_give_identical_problems() {
    for (new, old) in [
        ("potential = { kind = \"norm\" }", "potential = \"norm\""),
        (
            "potential = { kind = \"nonconvex\", a = 0.5 }",
            "potential = \"nonconvex\"\na = 0.5",
        ),
        (
            "potential = { kind = \"regularized\", rho = 0.001 }",
            "potential = \"regularized\"\nrho = 0.001",
        ),
    ] {
        let (p_new, notes_new) = problem(&square(new, ""));
        let (p_old, notes_old) = problem(&square(old, ""));
        assert_eq!(p_new.contact(), p_old.contact(), "{new} vs {old}");
        assert_eq!(p_new.materials(), p_old.materials());
        assert!(
            !notes_new.iter().any(|n| n.contains("deprecated")),
            "{notes_new:?}"
        );
        let note = notes_old
            .iter()
            .find(|n| n.contains("deprecated"))
            .unwrap_or_else(|| panic!("no deprecation note for {old}: {notes_old:?}"));
        assert_names(note, &["contact[0].friction.potential", "kind ="]);
    }
    // The values themselves.
    let (f, _) = friction(&square("potential = { kind = \"nonconvex\", a = 0.5 }", ""));
    assert_eq!(
        f.potential,
        FrictionPotential::Nonconvex {
            a: 0.5,
            unit: 1.0,
            treatment: NormTreatment::Smoothed {
                regularization: 1e-8
            }
        }
    );
    let (f, _) = friction(&square(
        "potential = { kind = \"regularized\", rho = 0.001 }",
        "",
    ));
    assert_eq!(f.potential, FrictionPotential::Regularized { rho: 0.001 });
    // Without `potential`: the norm.
    let (f, _) = friction(&square("", ""));
    assert!(matches!(f.potential, FrictionPotential::Norm { .. }));
}

#[test]
fn both_forms_at_once_are_refused() {
    let e = error_of(&square(
        "potential = { kind = \"nonconvex\", a = 0.5 }\na = 0.5",
        "",
    ));
    assert_names(
        &e,
        &[
            "contact[0].friction.a",
            "one form only",
            "potential = { kind",
        ],
    );
    let e = error_of(&square(
        "potential = { kind = \"regularized\", rho = 0.001 }\nrho = 0.001",
        "",
    ));
    assert_names(&e, &["contact[0].friction.rho", "one form only"]);
}

#[test]
fn unknown_kind_names_the_field_and_the_allowed_kinds() {
    for text in [
        square("potential = { kind = \"cubic\" }", ""),
        square("potential = \"cubic\"", ""),
    ] {
        let e = parse_error_of(&text);
        assert_names(
            &e,
            &["potential", "cubic", "norm", "nonconvex", "regularized"],
        );
    }
    // A parameter of another kind, or none at all.
    let e = parse_error_of(&square("potential = { kind = \"norm\", a = 0.5 }", ""));
    assert_names(&e, &["potential", "a"]);
    let e = parse_error_of(&square("potential = { kind = \"nonconvex\" }", ""));
    assert_names(&e, &["potential", "missing field `a`"]);
    let e = parse_error_of(&square("potential = 3", ""));
    assert_names(
        &e,
        &[
            "potential",
            "{ kind = \"norm\" }",
            "expected a friction potential",
        ],
    );
}

#[test]
fn out_of_range_parameters_name_the_table_field() {
    let e = error_of(&square("potential = { kind = \"nonconvex\", a = 1.5 }", ""));
    assert_names(&e, &["contact[0].friction.potential.a", "1.5", "0 < a < 1"]);
    let e = error_of(&square(
        "potential = { kind = \"regularized\", rho = -1.0 }",
        "",
    ));
    assert_names(&e, &["contact[0].friction.potential.rho", "-1", "> 0"]);
    // The deprecated form keeps its field names.
    let e = error_of(&square("potential = \"nonconvex\"\na = 1.5", ""));
    assert_names(&e, &["contact[0].friction.a", "0 < a < 1"]);
}

#[test]
fn regularization_is_a_parameter_of_each_law() {
    let regularization = |text: &str| friction(text).0.potential.regularization();
    assert_eq!(regularization(&square("", "")), Some(1e-8));
    assert_eq!(
        regularization(&square("regularization = 1e-6", "")),
        Some(1e-6)
    );
    assert_eq!(
        regularization(&square(
            "potential = { kind = \"nonconvex\", a = 0.5 }\nregularization = 1e-7",
            ""
        )),
        Some(1e-7)
    );
    // Exact stick/slip has none.
    let (f, _) = friction(&square("exact = true", ""));
    assert!(f.is_exact());
    assert_eq!(f.potential.regularization(), None);
}

#[test]
fn deprecated_outer_key_sets_every_law_with_a_note() {
    let (new, notes_new) = problem(&square("regularization = 1e-6", ""));
    let (old, notes_old) = problem(&square(
        "",
        "[solver.outer]\nfriction_regularization = 1e-6\n",
    ));
    assert_eq!(new.contact(), old.contact());
    assert!(!notes_new.iter().any(|n| n.contains("deprecated")));
    let note = notes_old
        .iter()
        .find(|n| n.contains("deprecated"))
        .expect("a deprecation note");
    assert_names(
        note,
        &[
            "solver.outer.friction_regularization",
            "[contact.friction]",
            "regularization",
        ],
    );
    // Both, equal: consistent.
    let (both, _) = problem(&square(
        "regularization = 1e-6",
        "[solver.outer]\nfriction_regularization = 1e-6\n",
    ));
    assert_eq!(both.contact(), new.contact());
}

#[test]
fn deprecated_and_new_key_with_different_values_are_a_contradiction() {
    let e = error_of(&square(
        "regularization = 1e-6",
        "[solver.outer]\nfriction_regularization = 1e-7\n",
    ));
    assert_names(
        &e,
        &[
            "contact[0].friction.regularization",
            "solver.outer.friction_regularization",
            "1e-7",
        ],
    );
}

#[test]
fn regularization_where_nothing_is_smoothed_or_out_of_range_is_refused() {
    let e = error_of(&square("exact = true\nregularization = 1e-6", ""));
    assert_names(&e, &["contact[0].friction.regularization", "exact = true"]);
    let e = error_of(&square(
        "potential = { kind = \"regularized\", rho = 0.001 }\nregularization = 1e-6",
        "",
    ));
    assert_names(&e, &["contact[0].friction.regularization", "rho"]);
    for bad in ["0.0", "0.1", "-1e-8", "nan"] {
        let e = error_of(&square(&format!("regularization = {bad}"), ""));
        assert_names(&e, &["contact[0].friction.regularization", "(0, 0.01)"]);
    }
    let e = error_of(&square(
        "",
        "[solver.outer]\nfriction_regularization = 0.1\n",
    ));
    assert_names(&e, &["solver.outer.friction_regularization", "(0, 0.01)"]);
}

#[test]
fn exact_stick_slip_of_the_smooth_law_is_refused() {
    let e = error_of(&square(
        "potential = { kind = \"regularized\", rho = 0.001 }\nexact = true",
        "",
    ));
    assert_names(&e, &["contact[0].friction.exact", "norm", "nonconvex"]);
}
