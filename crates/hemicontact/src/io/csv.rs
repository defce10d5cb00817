//! The contact table of a solution (`contact.csv`): one row per contact point.

use crate::problem::Problem;
use crate::solver::Solution;

/// A text field of a CSV row (RFC 4180): as is, or in double quotes with inner quotes
/// doubled when it holds a comma, a quote or a line break (a scenario title such as
/// `Paper example (…), C_kappa = 1e4`, a Gmsh part name).
pub fn field(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\"")).into()
    } else {
        text.into()
    }
}

/// The contact-node table: one row per contact point, comma-separated, with a header.
///
/// Columns: node, boundary (part name), x, y, z, weight, u_nu, gap, u_tau_1, u_tau_2, slip,
/// pressure, bound, force_normal, force_tangential_1, force_tangential_2, normal_state
/// (separated/contact), friction_state (none/stick/slip), normal_residual,
/// friction_residual, nu_x, nu_y, nu_z (the point's unit contact normal ν_i, outward from
/// the body: against an obstacle, the opposite of the obstacle's normal), force_scale and
/// slip_scale (the point's own scales its residuals and its stick threshold are relative
/// to, see [`crate::solver::certificate`]).
pub fn contact_csv(problem: &Problem, solution: &Solution) -> String {
    let mesh = &problem.mesh;
    let mut out = String::from(
        "node,boundary,x,y,z,weight,u_nu,gap,u_tau_1,u_tau_2,slip,pressure,bound,\
         force_normal,force_tangential_1,force_tangential_2,normal_state,friction_state,normal_residual,friction_residual,\
         nu_x,nu_y,nu_z,force_scale,slip_scale\n",
    );
    // The contact points in the order of the solution's rows (a solved problem has them).
    let points = problem.contact_nodes().unwrap_or_default();
    for (i, c) in solution.contact.iter().enumerate() {
        let nu = points.normal.get(i).copied().unwrap_or([f64::NAN; 3]);
        let x = mesh.node(c.node as usize);
        let xyz: Vec<f64> = (0..3).map(|i| x.get(i).copied().unwrap_or(0.0)).collect();
        let part = field(&mesh.part_names()[problem.contact[c.boundary].part]);
        out.push_str(&format!(
            "{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e}\n",
            c.node,
            part,
            xyz[0],
            xyz[1],
            xyz[2],
            c.weight,
            c.u_nu,
            c.gap,
            c.u_tau[0],
            c.u_tau[1],
            c.slip,
            c.pressure,
            c.bound,
            c.force_normal,
            c.force_tangential[0],
            c.force_tangential[1],
            c.normal_state.name(),
            c.friction_state.name(),
            c.normal_residual,
            c.friction_residual,
            nu[0],
            nu[1],
            nu[2],
            c.force_scale,
            c.slip_scale
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    /// Plain text stays as is; a comma, a quote or a line break is quoted (RFC 4180).
    #[test]
    fn fields_with_separators_are_quoted() {
        assert_eq!(super::field("left"), "left");
        assert_eq!(super::field("a, b"), "\"a, b\"");
        assert_eq!(super::field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(super::field("two\nlines"), "\"two\nlines\"");
    }
}
