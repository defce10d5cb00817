//! Built-in scenarios.

/// The paper's example as plain elasticity: the square (0,4)², clamped at the
/// bottom, compressed by `f_N = (0, −900)` N/m on top, E = 2000 Pa, ν = 0.3, plane strain,
/// with the symmetric nested cut pattern. Contact, friction and locking are added by the
/// paper-model issue. `{n}` is replaced by the number of squares per side.
pub const PAPER_ELASTIC: &str = r#"
title = "Paper example (Barboteu-Han-Migorski 2018), plain elasticity"

[mesh]
kind = "rectangle"
size = [4.0, 4.0]
n = [{n}, {n}]
pattern = "symmetric"

[material]
young = 2000.0
poisson = 0.3
plane = "strain"

[[dirichlet]]
part = "bottom"

[[loads.traction]]
part = "top"
value = [0.0, -900.0]
"#;

/// The plain-elastic paper scenario with `n × n` squares.
pub fn paper_elastic(n: usize) -> String {
    PAPER_ELASTIC.replace("{n}", &n.to_string())
}

/// The parts the paper's example adds to [`PAPER_ELASTIC`]: nearly locking with limited
/// compressibility θ = κ² = 0.16 and compliance `{c_kappa}`.
const PAPER_LOCKING: &str = r#"
[locking]
set = "limited-compressibility"
theta = 0.16
treatment = "penalty"
c_kappa = {c_kappa}
"#;

/// One vertical side `{part}` of the paper's example facing a rigid foundation at gap
/// g = 0.4 with normal compliance c_ν = 10⁴ and Coulomb-type friction
/// `F = μ(‖u_τ‖) p(u_ν)`, j = ‖·‖, `μ(r) = 0.3 e^{−100 r} + 0.1`.
const PAPER_CONTACT: &str = r#"
[[contact]]
part = "{part}"
gap = 0.4
law = "normal-compliance"
c_nu = 10000.0
[contact.friction]
bound = "coulomb"
potential = { kind = "norm" }
mu = { law = "exponential", a = 0.4, b = 0.1, beta = 100.0 }
"#;

/// The paper's example with `n × n` squares and locking compliance `c_kappa` (Pa):
/// [`PAPER_ELASTIC`] (E = 2000 Pa, ν = 0.3, plane strain — the paper's printed formula —
/// clamped at the bottom, `f_N = (0, −900)` N/m on top) plus the locking penalty and both
/// vertical sides in frictional contact (see the constants above).
pub fn paper(n: usize, c_kappa: f64) -> String {
    let title_elastic = "title = \"Paper example (Barboteu-Han-Migorski 2018), plain elasticity\"";
    let title =
        format!("title = \"Paper example (Barboteu-Han-Migorski 2018), C_kappa = {c_kappa:?}\"");
    let mut text = paper_elastic(n).replace(title_elastic, &title);
    text.push_str(&PAPER_LOCKING.replace("{c_kappa}", &format!("{c_kappa:?}")));
    for part in ["left", "right"] {
        text.push_str(&PAPER_CONTACT.replace("{part}", part));
    }
    text
}

#[cfg(test)]
mod tests {
    /// The composed paper scenario has the paper's title and both contact sides.
    #[test]
    fn paper_text_is_composed() {
        let t = super::paper(8, 1.0e4);
        assert!(t.contains("C_kappa = 10000.0") && !t.contains("plain elasticity"));
        assert_eq!(t.matches("[[contact]]").count(), 2);
        assert!(t.contains("c_kappa = 10000.0"));
    }
}
