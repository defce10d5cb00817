//! The uniqueness condition of the paper's Theorem 4:
//! `(μ₀ α_j + c_j L_μ) ‖γ‖² < m_A`.
//!
//! - `m_A`: strong monotonicity constant of the elasticity operator
//!   ([`crate::material::Elasticity::monotonicity`]); the locking penalty is convex and
//!   only adds a monotone part.
//! - `μ₀ = sup μ`, `L_μ` the Lipschitz constant of μ, `c_j` the bound of ∂j and `α_j` its
//!   relaxed-monotonicity constant (see [`crate::contact::friction`]); the largest value of
//!   `μ₀ α_j + c_j L_μ` over the contact boundaries is used.
//! - `‖γ‖`: the norm of the trace operator `V → L²(Γ_C)^d` with `‖v‖_V = ‖ε(v)‖_{L²}`,
//!   computed for the discrete space: `‖γ‖² = max_v ‖v‖²_{Γ_C} / ‖ε(v)‖²`, the largest
//!   eigenvalue of `M_C x = λ K_ε x`, with `K_ε` the matrix of `∫ ε(u):ε(v)` (Hooke with
//!   λ = 0, G = ½) on the free DOFs and `M_C` the lumped boundary mass on Γ_C (the nodal
//!   weights of the contact points, as in the discrete problem). It is found by power
//!   iteration on `K_ε⁻¹ M_C` with the Rayleigh quotient, reusing the symbolic Cholesky
//!   analysis of the problem's pattern.
//!
//! For a user-defined friction coefficient ([`crate::contact::slip_law`]) μ₀ and L_μ are
//! estimates from samples of the law, and the outcome says so ([`Uniqueness::estimated`]).
//!
//! The theorem covers Tresca-type friction bounds `F = μ(‖u_τ‖)`; for Coulomb-type bounds
//! `F = μ p(u_ν)` the check reports that it does not apply.

use super::System;
use crate::assembly::global::Want;
use crate::assembly::BulkAssembler;
use crate::contact::FrictionBound;
use crate::error::Result;
use crate::fem::dofs::FIXED;
use crate::material::{Hooke, Material};
use crate::problem::Problem;
use serde::Serialize;

/// The outcome of the uniqueness check; see the module documentation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Uniqueness {
    /// Whether the condition was evaluated: Theorem 4 covers the problem (contact with
    /// Tresca-type bounds or none) and ‖γ‖ could be computed where needed ([`evaluate`]).
    pub applies: bool,
    /// Why it was not evaluated, if so.
    pub note: Option<String>,
    /// m_A (Pa).
    pub m_a: f64,
    /// Largest μ₀ over the friction laws.
    pub mu0: f64,
    /// Largest L_μ.
    pub l_mu: f64,
    /// Set when μ₀ and L_μ include estimates from samples of user-defined friction laws
    /// (named in the text), which may miss a larger value between the samples; absent
    /// otherwise (and then not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimated: Option<String>,
    /// Largest c_j.
    pub c_j: f64,
    /// Largest α_j.
    pub alpha_j: f64,
    /// The factor `max_b (μ₀ α_j + c_j L_μ)` that multiplies ‖γ‖² (Pa/m, ‖γ‖² being in m;
    /// 0 without friction).
    pub factor: f64,
    /// The trace constant ‖γ‖ (not computed when the theorem does not apply, or when
    /// `factor` is 0 and the condition holds whatever ‖γ‖).
    pub trace_constant: Option<f64>,
    /// Power iterations used for ‖γ‖.
    pub iterations: usize,
    /// Left-hand side `max_b (μ₀ α_j + c_j L_μ) ‖γ‖²` (Pa; NaN when not evaluated).
    pub lhs: f64,
    /// `m_A − lhs` (Pa): positive when the condition holds.
    pub margin: f64,
    /// Whether the condition holds (and the theorem applies).
    pub holds: bool,
}

/// The discrete trace constant ‖γ‖ of the problem's Γ_C (all contact boundaries) and the
/// number of power iterations; `0.0` if there is no contact point. At the points of a
/// contact pair the trace is the jump `u(x_s) − Σ_j N_j u(m_j)` across the interface, whose
/// friction the condition bounds. Always uses the direct
/// (Cholesky) linear solver, whatever `settings.linear_solver` says: the power iteration
/// needs `K_ε⁻¹` to round-off (the ordering and thread settings are used).
///
/// # Errors
/// As [`System::new`] and the factorization of `K_ε`.
pub fn trace_constant(problem: &Problem, settings: &super::SolverSettings) -> Result<(f64, usize)> {
    // The power iteration needs K_ε⁻¹ to round-off: always the direct solver.
    let mut system = System::with_linear_solver(problem, settings, super::LinearSolver::Direct)?;
    if system.contact.is_empty() {
        return Ok((0.0, 0));
    }
    let d = problem.mesh.dim();
    let material = Material::elastic(crate::material::Elasticity::Hooke(Hooke {
        lambda: 0.0,
        mu: 0.5,
    }));
    let bulk = BulkAssembler::new(&problem.mesh, &material);
    let u = vec![0.0; d * problem.mesh.n_nodes()];
    let mut grad = vec![0.0; u.len()];
    let mut k = vec![0.0; system.pattern.nnz()];
    bulk.assemble(&u, &mut grad, Want::Hessian, &system.pattern, Some(&mut k));
    let Some(cholesky) = system.linear_solver.cholesky_mut() else {
        return Err(crate::Error::Breakdown("no Cholesky factorization".into()));
    };
    cholesky.factorize(&system.pattern, &k)?;
    // Lumped boundary mass on the free DOFs: diagonal without pairs; with pairs the mass
    // of the jump, `Σ_i w_i |Σ_a c_a x(v_a)|²` over each point's stencil.
    let n = system.pattern.n();
    let contact = &system.contact;
    let dofs = &system.dofs;
    let mut m = vec![0.0; n];
    for i in 0..contact.len() {
        let (len, nodes, _) = contact.stencil(d, i);
        for &v in &nodes[..len] {
            for c in 0..d {
                let eq = dofs.equation(d * v as usize + c);
                if eq != FIXED {
                    m[eq as usize] += contact.weight[i];
                }
            }
        }
    }
    let paired = contact.has_pairs();
    // y = M x.
    let apply_mass = |x: &[f64], y: &mut [f64]| {
        if !paired {
            for ((yi, xi), mi) in y.iter_mut().zip(x).zip(&m) {
                *yi = xi * mi;
            }
            return;
        }
        y.fill(0.0);
        for i in 0..contact.len() {
            let (len, nodes, coef) = contact.stencil(d, i);
            for c in 0..d {
                let eq = |a: usize| dofs.equation(d * nodes[a] as usize + c);
                let jump: f64 = (0..len)
                    .filter(|&a| eq(a) != FIXED)
                    .map(|a| coef[a] * x[eq(a) as usize])
                    .sum();
                for a in (0..len).filter(|&a| eq(a) != FIXED) {
                    y[eq(a) as usize] += contact.weight[i] * coef[a] * jump;
                }
            }
        }
    };
    let mut x: Vec<f64> = m.iter().map(|&w| if w > 0.0 { 1.0 } else { 0.0 }).collect();
    if paired {
        // A uniform start has no jump (M x = 0 at every pair): start from the slave nodes
        // alone.
        x.fill(0.0);
        for &v in &contact.node {
            for c in 0..d {
                let eq = dofs.equation(d * v as usize + c);
                if eq != FIXED {
                    x[eq as usize] = 1.0;
                }
            }
        }
    }
    let mut mx = vec![0.0; n];
    let mut kx = vec![0.0; n];
    let mut lambda = 0.0;
    let max_iter = 2000;
    for it in 1..=max_iter {
        // x ← K⁻¹ M x, normalized.
        apply_mass(&x, &mut mx);
        x.copy_from_slice(&mx);
        cholesky.solve_in_place(&mut x);
        let s = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        if s == 0.0 {
            return Ok((0.0, it));
        }
        for xi in x.iter_mut() {
            *xi /= s;
        }
        system.pattern.sym_matvec(&k, &x, &mut kx);
        apply_mass(&x, &mut mx);
        let xmx: f64 = x.iter().zip(&mx).map(|(a, b)| a * b).sum();
        let xkx: f64 = x.iter().zip(&kx).map(|(a, b)| a * b).sum();
        let next = xmx / xkx;
        if it > 1 && (next - lambda).abs() <= 1e-10 * next {
            return Ok((next.sqrt(), it));
        }
        lambda = next;
    }
    Ok((lambda.sqrt(), max_iter))
}

/// Evaluates the uniqueness condition for `problem`. ‖γ‖ is computed only when the theorem
/// applies and `μ₀ α_j + c_j L_μ > 0`; otherwise (frictionless contact, or a constant μ
/// with a convex potential) the left-hand side is 0 and the condition holds whatever ‖γ‖.
///
/// # Errors
/// As [`trace_constant`].
pub fn check(problem: &Problem, settings: &super::SolverSettings) -> Result<Uniqueness> {
    let mut u = constants(problem);
    if !u.applies {
        return Ok(u);
    }
    u.lhs = 0.0;
    if u.factor > 0.0 {
        let (g, iterations) = trace_constant(problem, settings)?;
        u.trace_constant = Some(g);
        u.iterations = iterations;
        u.lhs = u.factor * g * g;
    }
    u.margin = u.m_a - u.lhs;
    u.holds = u.lhs < u.m_a;
    Ok(u)
}

/// The constants of the condition, `applies` false with the reason for a Coulomb-type
/// bound, and `lhs`, `margin` NaN, `holds` false (nothing evaluated yet).
fn constants(problem: &Problem) -> Uniqueness {
    let d = problem.mesh.dim();
    // The smallest constant of the materials: the bound must hold in every cell.
    let m_a = problem
        .materials
        .iter()
        .map(|m| m.elasticity.monotonicity(d))
        .fold(f64::INFINITY, f64::min);
    let frictions: Vec<_> = problem
        .contact
        .iter()
        .filter_map(|c| c.friction.as_ref().map(|f| (c.part, f)))
        .collect();
    let coulomb = frictions
        .iter()
        .any(|(_, f)| f.bound == FrictionBound::Coulomb);
    let (mut mu0, mut l_mu, mut c_j, mut alpha_j, mut factor) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut custom: Vec<&str> = frictions
        .iter()
        .filter(|(_, f)| f.mu.is_estimated())
        .map(|(_, f)| f.mu.name())
        .collect();
    custom.dedup();
    let estimated = (!custom.is_empty()).then(|| {
        format!(
            "μ₀ and L_μ are estimates from samples of the user-defined law(s) {} at r = 0 and \
             1e-10 … 100 m, ten per decade (the largest sampled value and secant slope)",
            custom.join(", ")
        )
    });
    for &(part, f) in &frictions {
        let (a, b, c, e) = (
            sup_on_part(problem, part, &f.mu),
            f.mu.lipschitz(),
            f.potential.c_j(),
            f.potential.alpha_j(),
        );
        mu0 = mu0.max(a);
        l_mu = l_mu.max(b);
        c_j = c_j.max(c);
        alpha_j = alpha_j.max(e);
        factor = factor.max(a * e + c * b);
    }
    // Free rigid motions (carried by contact): the elastic energy alone does not control
    // the trace, the constant is infinite.
    let rigid = !coulomb && problem.rigid_motions().is_ok_and(|r| r.any_free());
    let note = if coulomb {
        Some("Theorem 4 covers Tresca-type friction bounds F = μ(‖u_τ‖); a Coulomb-type bound F = μ p(u_ν) is not covered".to_string())
    } else if rigid {
        Some("the Dirichlet conditions leave rigid motions free (contact carries them), so the elastic energy does not bound the trace on Γ_C".to_string())
    } else {
        None
    };
    Uniqueness {
        applies: !coulomb && !rigid,
        note,
        m_a,
        mu0,
        l_mu,
        estimated,
        c_j,
        alpha_j,
        trace_constant: None,
        iterations: 0,
        factor,
        lhs: f64::NAN,
        margin: f64::NAN,
        holds: false,
    }
}

/// `μ₀ = sup μ` of a contact part's coefficient: for a law of the position its largest value
/// at the part's nodes (NaN if the function fails there), otherwise
/// [`crate::contact::FrictionCoefficient::sup`].
fn sup_on_part(problem: &Problem, part: usize, mu: &crate::contact::FrictionCoefficient) -> f64 {
    if !mu.is_field() {
        return mu.sup();
    }
    let positions = problem.part_positions(part);
    let mut values = vec![0.0; positions.len()];
    let slips = vec![0.0; positions.len()];
    match mu.values(&slips, &positions, problem.mesh.dim(), &mut values) {
        Ok(()) => values.iter().fold(0.0, |a: f64, &b| a.max(b)),
        Err(_) => f64::NAN,
    }
}

/// The uniqueness check written to `summary.json` for every solve: [`check`] where it can
/// be evaluated, otherwise `applies: false` with the reason in `note` and the constants of
/// the laws (`lhs`, `margin` NaN, written as `null`):
/// - no contact boundary: there is no friction term, nothing to check;
/// - a Coulomb-type bound (see [`check`]);
/// - an iterative linear solver at a size where `auto` would choose it (large 3D
///   problems): ‖γ‖ needs a Cholesky factorization
///   of the ε–ε stiffness, which that choice exists to avoid;
/// - the computation of ‖γ‖ failed (the error is quoted).
///
/// Exact constraints (Signorini, ideal locking, exact stick/slip) are within the theorem,
/// which is stated for the constraint set `{v_ν ≤ g, ε(v) ∈ B}`.
pub fn evaluate(problem: &Problem, settings: &super::SolverSettings) -> Uniqueness {
    let not_evaluated = |note: String| Uniqueness {
        applies: false,
        note: Some(note),
        ..constants(problem)
    };
    if problem.contact.is_empty() {
        return not_evaluated(
            "no contact boundary: the condition bounds the friction on Γ_C, there is none"
                .to_string(),
        );
    }
    let u = constants(problem);
    if !u.applies {
        return u;
    }
    let iterative = !settings.linear_solver.cholesky_affordable(
        problem.mesh.dim(),
        problem.dof_map().n_free(),
        &settings.processes,
    );
    if iterative && u.factor > 0.0 {
        return not_evaluated(
            "not evaluated: the trace constant ‖γ‖ needs a Cholesky factorization of the ε–ε \
             stiffness, and this problem uses an iterative linear solver at a size where \
             the factorization is not affordable"
                .to_string(),
        );
    }
    match check(problem, settings) {
        Ok(u) => u,
        Err(e) => not_evaluated(format!(
            "not evaluated: the trace constant ‖γ‖ could not be computed ({e})"
        )),
    }
}
