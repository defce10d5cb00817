//! Tests of the figures of solved problems: the paper's example on a coarse mesh, with
//! and without contact.

use super::deformed::{self, Options};
use super::layout::{inside, overlaps, round_down_125, Rect};
use super::scales::{arrow_points, magnification, max_traction, thin};
use super::{interface, text_width, Anchor, Figure, Prim};
use crate::problem::Problem;
use crate::scenario::{builtin, Scenario};
use crate::solver::{solve, Solution, SolverSettings};

/// The paper's example on an `n × n` mesh, with the foundations at `gap` (m).
fn solved(n: usize, gap: f64) -> (Problem, Solution) {
    let text = builtin::paper(n, 1.0e4).replace("gap = 0.4", &format!("gap = {gap}"));
    let problem = Scenario::from_str(&text, "test")
        .and_then(|s| s.into_problem())
        .expect("scenario");
    let solution = solve(&problem, &SolverSettings::default()).expect("solve");
    assert!(solution.report.converged);
    (problem, solution)
}

/// The box of a text primitive (anchor applied).
fn text_rect(p: &Prim) -> Option<Rect> {
    match p {
        Prim::Text {
            pos,
            text,
            size,
            anchor,
            ..
        } => {
            let w = text_width(text, *size);
            let x = match anchor {
                Anchor::Start => pos[0],
                Anchor::Middle => pos[0] - w / 2.0,
                Anchor::End => pos[0] - w,
            };
            Some([x, pos[1] - 0.8 * size, x + w, pos[1] + 0.25 * size])
        }
        _ => None,
    }
}

fn texts(fig: &Figure) -> Vec<String> {
    fig.prims
        .iter()
        .filter_map(|p| match p {
            Prim::Text { text, .. } => Some(text.clone()),
            _ => None,
        })
        .collect()
}

#[test]
fn magnification_is_one_two_or_five_times_a_power_of_ten() {
    for (size, max_u) in [
        (4.0, 1e-3),
        (4.0, 3.3e-4),
        (1.0, 7e-6),
        (2.0, 0.05),
        (4.0, 1.6),
    ] {
        let m = magnification(size, max_u);
        assert_eq!(m, round_down_125(m).max(1.0), "{m}");
        // The largest displacement, magnified, is at most a tenth of the body and more
        // than a fiftieth of it (1-2-5 steps are at most 2.5 apart), unless m = 1.
        assert!(
            m == 1.0 || m * max_u <= 0.1 * size * (1.0 + 1e-12),
            "{size} {max_u}: {m}"
        );
        assert!(m == 1.0 || m * max_u > 0.1 * size / 2.5 * (1.0 - 1e-12));
    }
    assert_eq!(magnification(4.0, 1e-3), 200.0);
    assert_eq!(magnification(4.0, 0.0), 1.0);
}

#[test]
fn arrows_are_thinned_to_the_cap_evenly() {
    assert_eq!(thin(5, 40), vec![0, 1, 2, 3, 4]);
    let k = thin(129, 40);
    assert_eq!(k.len(), 40);
    assert_eq!((k[0], k[39]), (0, 128));
    let gaps: Vec<usize> = k.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(gaps.iter().all(|&g| g == 3 || g == 4), "{gaps:?}");
    let (problem, solution) = solved(16, 0.4);
    let touching = solution
        .contact
        .iter()
        .filter(|c| c.normal_state == crate::solver::NormalState::Contact)
        .count();
    assert!(touching > 2 * 3, "{touching} points in contact");
    let all = vec![true; problem.mesh.n_nodes()];
    for cap in [3, 10, 40] {
        let chosen = arrow_points(&problem, &solution, &all, cap, 0.0);
        let n = chosen.iter().filter(|&&c| c).count();
        assert_eq!(n, touching.min(cap * problem.contact.len()), "cap {cap}");
    }
    // One arrow per 1 m of contact at most: the contact zones are shorter than 4 m.
    let n = arrow_points(&problem, &solution, &all, 40, 1.0)
        .iter()
        .filter(|&&c| c)
        .count();
    assert!(n <= 2 * 4, "{n}");
}

#[test]
fn a_contact_free_case_says_zero() {
    // Foundations 10 m away: no point touches, the tractions are round-off.
    let (problem, solution) = solved(4, 10.0);
    assert_eq!(max_traction(&solution), 0.0);
    let fig = deformed::figure(&problem, &solution, "free");
    let t = texts(&fig);
    assert!(
        t.iter()
            .any(|s| s == "interface traction 0 (no point in contact)"),
        "{t:?}"
    );
    assert!(!fig.prims.iter().any(|p| matches!(p, Prim::Arrow { .. })));
    let fig = interface::figure(&problem, &solution, "free").expect("2D with contact");
    assert!(texts(&fig)
        .iter()
        .any(|s| s.starts_with("interface traction 0")));
}

#[test]
fn titles_and_legends_stay_inside_their_panels() {
    let (problem, solution) = solved(8, 0.4);
    let long = "A very long title that names the scenario, its material, its contact law, \
                its friction law and the mesh, far wider than any panel of the figure";
    let cases = [
        (&problem, &solution, long.to_string()),
        (&problem, &solution, "short".to_string()),
    ];
    let fig = deformed::side_by_side(&cases);
    let pw = f64::from(fig.width) / 2.0;
    let panels: [Rect; 2] = [
        [0.0, 0.0, pw, f64::from(fig.height)],
        [pw, 0.0, 2.0 * pw, f64::from(fig.height)],
    ];
    // Every text lies inside one panel (legends do not run into the neighbour), and the
    // texts of the left panel overlap no text of the right one.
    let boxes: Vec<Rect> = fig.prims.iter().filter_map(text_rect).collect();
    for b in &boxes {
        assert!(
            panels.iter().any(|p| inside(*b, *p)),
            "{b:?} crosses a panel edge"
        );
    }
    for a in boxes.iter().filter(|b| inside(**b, panels[0])) {
        for b in boxes.iter().filter(|b| inside(**b, panels[1])) {
            assert!(!overlaps(*a, *b));
        }
    }
    for fig in [
        deformed::figure_with(&problem, &solution, long, Options::default()),
        interface::figure(&problem, &solution, long).expect("2D with contact"),
    ] {
        let canvas = [0.0, 0.0, f64::from(fig.width), f64::from(fig.height)];
        for b in fig.prims.iter().filter_map(text_rect) {
            assert!(inside(b, canvas), "{b:?} outside {canvas:?}");
        }
    }
}

#[test]
fn the_traction_scale_is_stated_with_a_reference_arrow_and_the_magnification() {
    let (problem, solution) = solved(8, 0.4);
    let fig = deformed::figure(&problem, &solution, "t");
    let t = texts(&fig);
    assert!(
        t.iter()
            .any(|s| s.starts_with("interface traction R/w (max ")
                && s.contains("): this arrow = ")
                && s.ends_with("Pa")),
        "{t:?}"
    );
    assert!(
        t.iter()
            .any(|s| s.contains("displacements × ") || s.contains("displacements at true scale")),
        "{t:?}"
    );
}

#[test]
fn the_interface_is_walked_along_each_part_from_its_lower_end() {
    let (problem, solution) = solved(8, 0.4);
    for b in 0..problem.contact.len() {
        let al = interface::along(&problem, &solution, b);
        // 7 free nodes per vertical side of the 4 m square at n = 8 (the bottom corner is
        // clamped): s from 0.5 m to 3.5 m, then the top corner at 4 m.
        assert_eq!(al.rows.len(), 8);
        assert_eq!(al.start[1], 0.0);
        for (k, s) in al.s.iter().enumerate() {
            assert!((s - 0.5 * (k + 1) as f64).abs() < 1e-12, "{:?}", al.s);
            let node = solution.contact[al.rows[k]].node as usize;
            assert!((problem.mesh.node(node)[1] - s).abs() < 1e-12);
        }
    }
}

#[test]
fn a_mesh_too_fine_to_draw_cell_by_cell_is_drawn_as_an_image() {
    // Cells of 5 px or more are drawn as polygons (with their edges); smaller ones as one
    // image sampled at the resolution of the picture, in the place the polygons took.
    let count = |fig: &Figure| {
        let images = fig
            .prims
            .iter()
            .filter(|p| matches!(p, Prim::Raster(_)))
            .count();
        let polygons = fig
            .prims
            .iter()
            .filter(|p| matches!(p, Prim::Polygons { .. }))
            .count();
        (images, polygons)
    };
    let (problem, solution) = solved(8, 0.4);
    let (images, polygons) = count(&deformed::figure(&problem, &solution, "coarse"));
    assert_eq!(images, 0);
    assert!(polygons > 1, "{polygons} colour bands");
    let (problem, solution) = solved(128, 0.4);
    let fig = deformed::figure(&problem, &solution, "fine");
    assert_eq!(count(&fig), (1, 0));
    assert!(texts(&fig).iter().any(|t| t.contains("too small to draw")));
}
