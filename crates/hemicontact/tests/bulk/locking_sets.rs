//! The scalings a locking set provides to the solver, against their definitions:
//! [`LockingSet::size`] is θ, κ² or r, and [`LockingSet::gradient_norm_sq_at_boundary`] is
//! `|∂Q|²` at strains on ∂B = {Q = 0} (Frobenius norm of `∂Q/∂ε` for Prager's set and the
//! ball; for limited compressibility the derivative of Q with respect to `tr ε`, ±1), in 2D
//! and 3D; and the material's one encoding of locking.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::material::{
    Elasticity, Hooke, Locking, LockingPenalty, LockingSet, Material, StrainEnergy,
};
use hemicontact::tensor::Sym;

/// A few strains of dimension `dim` with a nonzero deviator and trace.
fn strains(dim: usize) -> Vec<Sym> {
    let ms = [
        [[0.3, 0.1, -0.2], [0.1, -0.5, 0.05], [-0.2, 0.05, 0.4]],
        [[-0.7, 0.2, 0.0], [0.2, 0.1, 0.3], [0.0, 0.3, -0.1]],
        [[0.01, -0.03, 0.02], [-0.03, 0.02, 0.0], [0.02, 0.0, 0.05]],
    ];
    ms.iter().map(|m| Sym::from_matrix(dim, m)).collect()
}

/// `eps` moved onto ∂B of `set`.
fn on_boundary(set: LockingSet, eps: &Sym) -> Sym {
    let d = eps.dim;
    match set {
        LockingSet::LimitedCompressibility { theta } => {
            let target = theta * eps.trace().signum();
            eps.add_scaled((target - eps.trace()) / d as f64, &Sym::identity(d))
        }
        LockingSet::Prager { kappa } => {
            let dev = eps.deviator();
            let vol = eps.add_scaled(-1.0, &dev);
            vol.add_scaled(std::f64::consts::SQRT_2 * kappa / dev.norm(), &dev)
        }
        LockingSet::Ball { r } => eps.scaled(r / eps.norm()),
    }
}

const SETS: [LockingSet; 3] = [
    LockingSet::LimitedCompressibility { theta: 0.16 },
    LockingSet::Prager { kappa: 0.3 },
    LockingSet::Ball { r: 0.25 },
];

#[test]
fn size_is_the_threshold_of_each_set() {
    assert_eq!(SETS[0].size(), 0.16);
    assert_eq!(SETS[1].size(), 0.3 * 0.3);
    assert_eq!(SETS[2].size(), 0.25);
}

#[test]
fn gradient_norm_at_the_boundary_is_that_of_dq_there() {
    for dim in [2, 3] {
        for set in SETS {
            for eps in strains(dim) {
                let b = on_boundary(set, &eps);
                assert!(set.q(&b).abs() < 1e-12 * set.size(), "{set:?}: not on ∂B");
                let expected = match set {
                    // dQ/d(tr ε) by central differences along the identity (tr changes by
                    // t·d/d = t).
                    LockingSet::LimitedCompressibility { .. } => {
                        let h = 1e-6;
                        let i = Sym::identity(dim).scaled(1.0 / dim as f64);
                        let dq = (set.q(&b.add_scaled(h, &i)) - set.q(&b.add_scaled(-h, &i)))
                            / (2.0 * h);
                        dq * dq
                    }
                    _ => {
                        let g = set.dq(&b);
                        g.dot(&g)
                    }
                };
                let got = set.gradient_norm_sq_at_boundary();
                assert!(
                    (got - expected).abs() < 1e-9 * expected,
                    "{set:?} d={dim}: |∂Q|² = {expected}, method {got}"
                );
            }
        }
    }
}

#[test]
fn material_without_locking_is_its_elasticity() {
    let hooke = Elasticity::Hooke(Hooke {
        lambda: 100.0,
        mu: 50.0,
    });
    let plain = Material::elastic(hooke);
    assert_eq!(plain.locking, Locking::None);
    assert_eq!(plain.locking.set(), None);
    // A penalty with C_κ = 0 adds nothing; an ideal set adds nothing to the stored energy
    // (its stress comes from the cell multipliers).
    let zero = Material {
        elasticity: hooke,
        locking: Locking::Penalty(LockingPenalty {
            set: SETS[0],
            c_kappa: 0.0,
        }),
    };
    let ideal = Material {
        elasticity: hooke,
        locking: Locking::Ideal(SETS[1]),
    };
    for eps in strains(3) {
        for m in [&zero, &ideal] {
            assert_eq!(m.energy(&eps), plain.energy(&eps));
            assert_eq!(m.stress(&eps), plain.stress(&eps));
            assert_eq!(m.tangent(&eps), plain.tangent(&eps));
        }
    }
    assert_eq!(ideal.locking.ideal(), Some(SETS[1]));
    assert_eq!(zero.locking.penalty().map(|p| p.set), Some(SETS[0]));
}
