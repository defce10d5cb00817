//! The evaluation of the convexified energy of a [`System`] ([`System::evaluate`]): energy,
//! gradient and generalized Hessian for given frozen contact quantities, into the work
//! arrays of an [`Evaluation`].

use super::{Evaluation, System};
use crate::assembly::global::{IdealLocking, Want};
use crate::assembly::BulkAssembler;
use crate::problem::Problem;
use crate::rigid::NEWTON_SHIFT;
use crate::solver::constraints::AugmentedLagrangian;
use crate::solver::frozen::Frozen;

impl System {
    /// Convexified energy `E_k(u) = Σ_T |T| (W + Ψ)(ε_T(u)) + contact terms − f·u` for the
    /// frozen quantities `frozen`; the gradient goes to `out.grad` (and the bulk part minus
    /// `f` to `out.grad_bulk`), and with `hessian` the Hessian to `out.hess`. A user-defined
    /// compliance law that fails leaves its error in `out.law_error` and returns NaN.
    ///
    /// On several processes, `problem` and `u` are this process's part
    /// ([`System::for_solve`]): it assembles the cells of its part (counting the energy of
    /// those it owns) and its contact points (counting the energy of its own; its ghost
    /// points complete its master nodes' rows), so the gradients are complete at its own
    /// nodes; their entries at its ghost nodes are set to NaN (partial there, never read).
    /// The energies and the work of the loads are summed over the processes
    /// ([`crate::parallel::Processes::sum`] of three numbers, the one exchange of an evaluation).
    pub fn evaluate(
        &mut self,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
        out: &mut Evaluation,
        hessian: bool,
    ) -> f64 {
        let want = if hessian {
            Want::Hessian
        } else {
            Want::Gradient
        };
        let hess = if hessian {
            Some(out.hess.as_mut_slice())
        } else {
            None
        };
        let bulk = BulkAssembler {
            ideal: ideal_locking(&self.continuation.penalties, problem, frozen),
            ..BulkAssembler::of(problem, &problem.mesh)
        };
        let e_bulk = bulk.assemble_parallel(
            u,
            &mut out.grad_bulk,
            want,
            &self.pattern,
            hess,
            &mut self.workspace,
        );
        let mut contact = self.contact_assembler(problem);
        let share = &self.share;
        if let Err(e) = contact.normal_responses(u, hessian, &mut out.normal) {
            out.law_error.get_or_insert(e);
            return f64::NAN;
        }
        contact.responses = &out.normal;
        let hc = if hessian {
            Some((out.hess.as_mut_slice(), self.contact_slots.as_slice()))
        } else {
            None
        };
        let work = subtract_external(&mut out.grad_bulk, &self.f_ext, u, |k| share.counts_dof(k));
        // A ghost node's bulk gradient is partial here: unknown (none on one process).
        share.unknown_where_uncounted(&mut out.grad_bulk);
        out.grad.copy_from_slice(&out.grad_bulk);
        let e_contact = contact.assemble(u, &frozen.contact(), &mut out.grad, hc);
        let mut e = [e_bulk, e_contact, work];
        share.sum(&mut e);
        let [e_bulk, e_contact, work] = e;
        if hessian && self.rigid.any_free() {
            // Free rigid motions carried by contact: shift the Newton matrix (not the
            // energy) on their bodies, see `rigid::NEWTON_SHIFT`. Decided on the whole
            // problem's bodies: a process without a node of them still takes part in the
            // maximum.
            if out.rigid_shift == 0.0 {
                let mut max = [self
                    .rigid_slots
                    .iter()
                    .fold(0.0f64, |m, &k| m.max(out.hess[k]))];
                if let Err(e) = self.processes.max(&mut max) {
                    out.law_error.get_or_insert(e);
                    return f64::NAN;
                }
                out.rigid_shift = NEWTON_SHIFT * max[0];
            }
            for &k in &self.rigid_slots {
                out.hess[k] += out.rigid_shift;
            }
        }
        // A failed reduction of the solver's (MPI's error) ends the solve with that error.
        if let Some(e) = self.share.failure() {
            out.law_error.get_or_insert(e);
            return f64::NAN;
        }
        e_bulk + e_contact - work
    }
}

/// `grad ← grad − f_ext`; returns the work of the external forces `f_ext · u` (J, J/m in
/// 2D) over the DOFs `counted`, in order.
fn subtract_external(
    grad: &mut [f64],
    f_ext: &[f64],
    u: &[f64],
    counted: impl Fn(usize) -> bool,
) -> f64 {
    let mut work = 0.0;
    for (k, ((g, f), x)) in grad.iter_mut().zip(f_ext).zip(u).enumerate() {
        *g -= f;
        if counted(k) {
            work += f * x;
        }
    }
    work
}

/// The ideal-locking term of `problem` with the penalties `penalties` and the cell
/// multipliers of `frozen`.
pub(crate) fn ideal_locking<'a>(
    penalties: &'a AugmentedLagrangian,
    problem: &Problem,
    frozen: &'a Frozen,
) -> Option<IdealLocking<'a>> {
    problem.has_ideal_locking().then(|| IdealLocking {
        sets: penalties.locking_sets(),
        r: penalties.locking(),
        multipliers: &frozen.multipliers.locking,
    })
}
