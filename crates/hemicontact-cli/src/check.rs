//! `hemicontact check`: validates a scenario and prints its sizes, material, laws (in
//! words), boundary parts, free rigid motions and the uniqueness condition.

use crate::console::Console;
use crate::{say, RunContext};
use anyhow::{Context, Result};
use hemicontact::display::significant;
use hemicontact::problem::Problem;
use hemicontact::solver::SolverSettings;
use std::path::Path;

/// `hemicontact check FILE`.
pub fn check(ctx: &RunContext, file: &Path) -> Result<()> {
    let c = &ctx.console;
    let scenario = ctx.read_scenario(file)?;
    let (problem, notes) = scenario.into_problem_with_notes()?;
    let settings = scenario.settings()?;
    // The scales of the dimensionless solve: data too far apart to represent the
    // displacements would fail every solve, so they fail the check too.
    hemicontact::solver::scaling::Scales::of(&problem)
        .with_context(|| format!("{}: the problem cannot be solved", scenario.source))?;
    print_problem(c, &problem, &settings, &scenario.source);
    print_notes(c, &notes);
    // Rigid motions not blocked by a Dirichlet condition that contact carries (those it
    // does not carry were refused above).
    for motion in problem.rigid_motions()?.describe_all() {
        say!(c, "free rigid motion carried by contact: {motion}");
    }
    let iterative = !settings.linear_solver.cholesky_affordable(
        problem.mesh().dim(),
        problem.dof_map().n_free(),
        &settings.processes,
    );
    if !problem.contact().is_empty() && iterative {
        say!(
            c,
            "uniqueness (Theorem 4): not checked — the discrete trace constant needs a Cholesky \
             factorization, and this scenario uses an iterative linear solver at a size \
             where the factorization is not affordable"
        );
    } else if !problem.contact().is_empty() {
        print_uniqueness(
            c,
            &hemicontact::solver::uniqueness::check(&problem, &settings)?,
        );
    }
    say!(c, "ok: {} is valid", file.display());
    Ok(())
}

fn print_problem(c: &Console, problem: &Problem, settings: &SolverSettings, source: &str) {
    let mesh = problem.mesh();
    let dofs = problem.dof_map();
    say!(c, "scenario   {source}");
    say!(c, "dimension  {}", mesh.dim());
    say!(c, "nodes      {}", mesh.n_nodes());
    say!(c, "cells      {}", mesh.n_cells());
    say!(
        c,
        "DOFs       {} ({} free, {} prescribed)",
        dofs.n_dofs(),
        dofs.n_free(),
        dofs.n_dofs() - dofs.n_free()
    );
    let names = mesh.region_names();
    for (k, material) in problem.materials().iter().enumerate() {
        // The cell regions each material fills, for a body of several.
        let parts: Vec<&str> = problem
            .region_material()
            .iter()
            .enumerate()
            .filter(|&(_, &m)| m as usize == k)
            .map(|(r, _)| names.get(r).map_or("", String::as_str))
            .collect();
        if !parts.is_empty() {
            say!(c, "material {k} in {}", parts.join(", "));
        }
        let h = material.elasticity.small_strain_hooke(mesh.dim());
        say!(c, "Lamé       λ = {:.6e} Pa, G = {:.6e} Pa", h.lambda, h.mu);
        use hemicontact::material::Locking;
        match material.locking {
            Locking::Ideal(set) => {
                say!(
                    c,
                    "locking    {set}, ideal (exact constraint, augmented Lagrangian)"
                )
            }
            Locking::Penalty(p) if p.c_kappa > 0.0 => {
                say!(
                    c,
                    "locking    {}, penalty C_κ = {} Pa",
                    p.set,
                    significant(p.c_kappa)
                )
            }
            _ => say!(c, "locking    none"),
        }
    }
    match hemicontact::solver::scaling::Scales::of(problem) {
        Ok(scales) => say!(
            c,
            "scales     length {:e} m, stress {:e} Pa, displacement {:e} m (the solve is dimensionless in these)",
            scales.length,
            scales.stress,
            scales.displacement
        ),
        Err(e) => say!(c, "scales     {e}"),
    }
    say!(
        c,
        "certificate tolerance {:e} (relative residuals of every law)",
        settings.certificate_tolerance
    );
    for (k, contact) in problem.contact().iter().enumerate() {
        match (&contact.obstacle, &contact.against) {
            (None, Some(master)) => say!(
                c,
                "contact[{k}] part `{}` (slave side) against part `{}` (master side) of \
                 another body: node-to-segment, gaps and normals from the two parts' geometry",
                mesh.part_names()[contact.part],
                mesh.part_names()[master.part],
            ),
            (None, None) => say!(
                c,
                "contact[{k}] part `{}`: gap {} m",
                mesh.part_names()[contact.part],
                significant(contact.gap),
            ),
            (Some(o), _) => say!(
                c,
                "contact[{k}] part `{}`: {}",
                mesh.part_names()[contact.part],
                o.spec
            ),
        }
        say!(c, "  normal   {}", contact.normal);
        match &contact.friction {
            None => say!(c, "  friction none (frictionless)"),
            Some(f) => {
                say!(c, "  friction {}", f.bound);
                say!(c, "  μ        {}", f.mu);
                say!(c, "  j        {}", f.potential);
            }
        }
    }
    say!(
        c,
        "contact points {}",
        problem.contact_nodes().map_or(0, |p| p.len())
    );
    say!(c, "boundary parts:");
    for (p, name) in mesh.part_names().iter().enumerate() {
        let facets = mesh.part_facets(p).count();
        let nodes = mesh.part_nodes(p).len();
        let mut roles = Vec::new();
        if problem.dirichlet().iter().any(|b| b.part == p) {
            roles.push("Dirichlet");
        }
        if problem.tractions().iter().any(|t| t.part == p) {
            roles.push("Neumann");
        }
        if problem.contact().iter().any(|c| c.part == p) {
            roles.push("contact");
        }
        let role = if roles.is_empty() {
            "free".to_string()
        } else {
            roles.join(" + ")
        };
        say!(
            c,
            "  {name:<10} {facets:>6} facets {nodes:>6} nodes  {role}"
        );
    }
}

/// Prints the notes of a scenario (warnings that do not stop the run) to standard error.
pub fn print_notes(c: &Console, notes: &[String]) {
    for n in notes {
        c.warn(format_args!("note: {n}"));
    }
}

fn print_uniqueness(c: &Console, u: &hemicontact::solver::uniqueness::Uniqueness) {
    say!(
        c,
        "uniqueness (Theorem 4): m_A = {:.6e}, μ₀ = {}, L_μ = {}, c_j = {}, α_j = {}",
        u.m_a,
        significant(u.mu0),
        significant(u.l_mu),
        significant(u.c_j),
        significant(u.alpha_j)
    );
    if let Some(estimated) = &u.estimated {
        say!(c, "  {estimated}");
    }
    match (&u.note, u.trace_constant) {
        (Some(note), _) => say!(c, "  not applicable: {note}"),
        (None, Some(g)) => say!(
            c,
            "  ‖γ‖ = {g:.6e} ({} power iterations); (μ₀α_j + c_jL_μ)‖γ‖² = {:.6e} {} m_A: condition {} (margin {:.6e})",
            u.iterations,
            u.lhs,
            if u.holds { "<" } else { "≥" },
            if u.holds { "holds" } else { "FAILS" },
            u.margin
        ),
        (None, None) => say!(
            c,
            "  μ₀α_j + c_jL_μ = 0: the condition holds whatever ‖γ‖ (margin {:.6e})",
            u.margin
        ),
    }
}
