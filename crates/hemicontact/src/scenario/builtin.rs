//! Built-in scenarios.

/// The paper's example (SPEC §5) as plain elasticity: the square (0,4)², clamped at the
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
