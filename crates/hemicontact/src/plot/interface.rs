//! The interface along each contact part Γ_C of a 2D solution: contact pressure p, the
//! magnitude of the friction traction ‖σ_τ‖ and the friction bound F (Pa) against the arc
//! length s (m) along the part, with a band showing each point's state (separated, contact
//! without friction, stick, slip). One panel per contact part, side by side. For a contact
//! pair, the panel also shows the pressure on the master side ([`master_pressure`]), at
//! the master nodes along the slave side: action = reaction, seen from both bodies.
//!
//! The values are the contact results of the solution (the columns `pressure`, `bound` and
//! the friction traction of `contact.csv`). A part is walked along its boundary edges from
//! the end with the smaller y (then the smaller x): vertical sides bottom to top, horizontal
//! ones left to right; s is measured from that end.

use super::axes::{self, Axis};
use super::layout::{fit_text, quantity, si_prefix};
use super::legend::{flow, Entry, Swatch};
use super::{Anchor, Figure, Prim, Rgb};
use crate::problem::Problem;
use crate::solver::{ContactResult, FrictionState, NormalState, Solution};
use std::collections::HashMap;

const DARK: Rgb = [30, 30, 30];
const BLUE: Rgb = [31, 119, 180];
const ORANGE: Rgb = [230, 120, 20];
const GREY: Rgb = [120, 120, 120];

/// The state of a contact point as the band shows it, with its colour and name.
pub fn state_of(c: &ContactResult) -> (Rgb, &'static str) {
    match (c.normal_state, c.friction_state) {
        (_, FrictionState::Slip) => ([220, 30, 30], "slip"),
        (_, FrictionState::Stick) => ([20, 80, 220], "stick"),
        (NormalState::Contact, FrictionState::None) => ([90, 90, 90], "contact, no friction"),
        (NormalState::Separated, FrictionState::None) => ([200, 200, 200], "separated"),
    }
}

/// The contact points of one contact boundary in order along it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Along {
    /// Indices into `solution.contact`, in order along the part.
    pub rows: Vec<usize>,
    /// Arc length s (m) of each, from the start of the part.
    pub s: Vec<f64>,
    /// Coordinates of the start (m).
    pub start: [f64; 2],
}

/// Orders the contact points of contact boundary `b` (an index into `problem.contact`) of
/// a 2D solution along the chain of its boundary edges, with their arc lengths. Several
/// disjoint chains follow each other in the order of their starts, s continuing by the
/// straight distance between them.
pub fn along(problem: &Problem, solution: &Solution, b: usize) -> Along {
    let mesh = &problem.mesh;
    let xy = |n: u32| {
        let p = mesh.node(n as usize);
        [p[0], p.get(1).copied().unwrap_or(0.0)]
    };
    let mut nbrs: HashMap<u32, Vec<u32>> = HashMap::new();
    for f in mesh.part_facets(problem.contact[b].part) {
        let v = mesh.facet(f);
        if v.len() != 2 {
            return Along::default();
        }
        nbrs.entry(v[0]).or_default().push(v[1]);
        nbrs.entry(v[1]).or_default().push(v[0]);
    }
    let (lo, hi) = mesh.bounding_box();
    let tol = 1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
    let key = |n: u32| {
        let p = xy(n);
        ((p[1] / tol).round(), p[0], n)
    };
    let mut left: Vec<u32> = nbrs.keys().copied().collect();
    left.sort_unstable();
    let mut seen: HashMap<u32, f64> = HashMap::new();
    let mut chains: Vec<Vec<u32>> = Vec::new();
    while !left.is_empty() {
        let free = |n: &u32| nbrs[n].iter().filter(|m| !seen.contains_key(m)).count();
        let ends: Vec<u32> = left.iter().copied().filter(|n| free(n) <= 1).collect();
        let pool = if ends.is_empty() { &left } else { &ends };
        let start = pool
            .iter()
            .copied()
            .min_by(|a, b| {
                key(*a)
                    .partial_cmp(&key(*b))
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(left[0]);
        let mut chain = vec![start];
        seen.insert(start, 0.0);
        while let Some(&next) = nbrs[chain.last().unwrap_or(&start)]
            .iter()
            .find(|m| !seen.contains_key(m))
        {
            seen.insert(next, 0.0);
            chain.push(next);
        }
        left.retain(|n| !seen.contains_key(n));
        chains.push(chain);
    }
    let mut s = 0.0;
    let mut prev: Option<[f64; 2]> = None;
    for chain in &chains {
        for &n in chain {
            let p = xy(n);
            if let Some(q) = prev {
                s += (p[0] - q[0]).hypot(p[1] - q[1]);
            }
            seen.insert(n, s);
            prev = Some(p);
        }
    }
    let mut rows: Vec<(f64, usize)> = solution
        .contact
        .iter()
        .enumerate()
        .filter(|(_, c)| c.boundary == b)
        .filter_map(|(k, c)| seen.get(&c.node).map(|&s| (s, k)))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    Along {
        start: chains.first().map_or([0.0, 0.0], |c| xy(c[0])),
        s: rows.iter().map(|r| r.0).collect(),
        rows: rows.iter().map(|r| r.1).collect(),
    }
}

/// The size of a traction below which it is round-off of equilibrium and printed as 0:
/// 10⁻⁹ of the solve's stress scale (Pa); 0 (only exact zeros) if the report has no
/// scales.
pub fn traction_floor(solution: &Solution) -> f64 {
    solution
        .report
        .scales
        .as_ref()
        .map_or(0.0, |s| 1e-9 * s.stress.abs())
}

/// The pressure on the master side of a pair (contact boundary `b` with `against`), at
/// the master part's nodes that lie along the slave side: `(s, p_m)` with s the arc length
/// of the node's closest point on the slave chain `al` and
/// `p_m = Σ_i N_{i,m} p_i w_i / w_m`, the slave points' normal forces spread onto the
/// master node m with the shape functions N_{i,m} of their projections, over m's lumped
/// weight `w_m` on the master part. Empty for a boundary without a pair.
pub fn master_pressure(
    problem: &Problem,
    solution: &Solution,
    b: usize,
    al: &Along,
) -> Vec<(f64, f64)> {
    let Some(master) = problem.contact[b].against else {
        return Vec::new();
    };
    let Ok(points) = problem.contact_nodes() else {
        return Vec::new();
    };
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let index: HashMap<(u32, usize), usize> = (0..points.len())
        .map(|i| ((points.node[i], points.boundary[i] as usize), i))
        .collect();
    let mut force: HashMap<u32, f64> = HashMap::new();
    for &k in &al.rows {
        let c = &solution.contact[k];
        let Some(&i) = index.get(&(c.node, c.boundary)) else {
            continue;
        };
        let (len, nodes, coef) = points.stencil(d, i);
        for a in 1..len {
            *force.entry(nodes[a]).or_default() -= coef[a] * c.pressure * c.weight;
        }
    }
    let mut weight: HashMap<u32, f64> = HashMap::new();
    for f in mesh.part_facets(master.part) {
        let (measure, _) = mesh.facet_measure_normal(f);
        for &v in mesh.facet(f) {
            *weight.entry(v).or_default() += measure / d as f64;
        }
    }
    // The slave chain as a polyline in arc length.
    let xy = |n: u32| {
        let p = mesh.node(n as usize);
        [p[0], p.get(1).copied().unwrap_or(0.0)]
    };
    let chain: Vec<([f64; 2], f64)> = al
        .rows
        .iter()
        .zip(&al.s)
        .map(|(&k, &s)| (xy(solution.contact[k].node), s))
        .collect();
    if chain.len() < 2 {
        return Vec::new();
    }
    let mut out: Vec<(f64, f64)> = Vec::new();
    for v in mesh.part_nodes(master.part) {
        let x = xy(v);
        // The closest point on the chain; nodes beyond its ends are not along it.
        let mut best: Option<(f64, f64)> = None;
        for w in chain.windows(2) {
            let ((a, sa), (b, sb)) = (w[0], w[1]);
            let e = [b[0] - a[0], b[1] - a[1]];
            let len2 = e[0] * e[0] + e[1] * e[1];
            if len2 == 0.0 {
                continue;
            }
            let t = ((x[0] - a[0]) * e[0] + (x[1] - a[1]) * e[1]) / len2;
            if !(-1e-9..=1.0 + 1e-9).contains(&t) {
                continue;
            }
            let t = t.clamp(0.0, 1.0);
            let dist = (x[0] - a[0] - t * e[0]).hypot(x[1] - a[1] - t * e[1]);
            if best.is_none_or(|(bd, _)| dist < bd) {
                best = Some((dist, sa + t * (sb - sa)));
            }
        }
        let (Some((_, s)), Some(&w)) = (best, weight.get(&v)) else {
            continue;
        };
        if w > 0.0 {
            out.push((s, force.get(&v).copied().unwrap_or(0.0) / w));
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// Magnitude of the friction traction ‖σ_τ‖ (Pa) of a contact point.
fn friction_magnitude(c: &ContactResult) -> f64 {
    let t = c.friction_traction;
    (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt()
}

/// Panel size (px).
const PANEL: [f64; 2] = [620.0, 540.0];

/// The interface figure of a 2D solution, one panel per contact part; `None` for a 3D
/// solution or one without contact.
pub fn figure(problem: &Problem, solution: &Solution, title: &str) -> Option<Figure> {
    if problem.mesh.dim() != 2 || problem.contact.is_empty() {
        return None;
    }
    let n = problem.contact.len();
    let width = PANEL[0] * n as f64;
    let (lines, size) = fit_text(title, width - 20.0, 16.0, 12.0);
    let top = 12.0 + 1.3 * size * lines.len() as f64;
    let mut fig = Figure::new(width as u32, (PANEL[1] + top) as u32);
    for (k, l) in lines.iter().enumerate() {
        fig.prims.push(Prim::Text {
            pos: [width / 2.0, 8.0 + size + 1.3 * size * k as f64],
            text: l.clone(),
            size,
            anchor: Anchor::Middle,
            color: DARK,
        });
    }
    for b in 0..n {
        let rect = [PANEL[0] * b as f64, top, PANEL[0], PANEL[1]];
        fig.prims.extend(panel(problem, solution, b, rect));
    }
    Some(fig)
}

/// One panel: contact part `b` in the pixel box `rect = (x, y, w, h)`.
fn panel(problem: &Problem, solution: &Solution, b: usize, rect: [f64; 4]) -> Vec<Prim> {
    let [x0, y0, w, h] = rect;
    let mut prims = Vec::new();
    let name = &problem.mesh.part_names()[problem.contact[b].part];
    prims.push(Prim::Text {
        pos: [x0 + w / 2.0, y0 + 16.0],
        text: format!("contact part {name}"),
        size: 14.0,
        anchor: Anchor::Middle,
        color: DARK,
    });
    let al = along(problem, solution, b);
    let pts: Vec<&ContactResult> = al.rows.iter().map(|&k| &solution.contact[k]).collect();
    let floor = traction_floor(solution);
    let clean = |v: f64| if v.abs() <= floor { 0.0 } else { v };
    let p: Vec<f64> = pts.iter().map(|c| clean(c.pressure)).collect();
    let ft: Vec<f64> = pts.iter().map(|c| clean(friction_magnitude(c))).collect();
    let fb: Vec<f64> = pts.iter().map(|c| clean(c.bound)).collect();
    let master = master_pressure(problem, solution, b, &al);
    let pm: Vec<f64> = master.iter().map(|m| clean(m.1)).collect();
    let top = p
        .iter()
        .chain(&ft)
        .chain(&fb)
        .chain(&pm)
        .copied()
        .fold(0.0, f64::max);
    let empty = top <= 0.0;
    let y_hi = if empty { 1.0 } else { 1.08 * top };
    let (factor, unit) = si_prefix(if empty { 1.0 } else { top }, "Pa");
    let s_end = al.s.last().copied().unwrap_or(0.0);
    let s_hi = if s_end > 0.0 { s_end } else { 1.0 };
    // Legend first: its height fixes the plot box.
    let entries = legend_entries(problem, b, &pts, master.is_empty());
    let (l, r) = (x0 + 80.0, x0 + w - 30.0);
    let probe = flow(&entries, x0 + 20.0, x0 + w - 20.0, 0.0, 12.0);
    let legend_h = probe.bottom;
    let band = 12.0;
    let t = y0 + 30.0 + axes::ABOVE + band + 4.0;
    let bottom = y0 + h - legend_h - 12.0 - axes::BELOW;
    let xa = Axis {
        lo: 0.0,
        hi: s_hi,
        px0: l,
        px1: r,
    };
    let ya = Axis {
        lo: 0.0,
        hi: y_hi,
        px0: bottom,
        px1: t,
    };
    let start = format!(
        "arc length s from ({}, {}) (m)",
        super::layout::number(al.start[0]),
        super::layout::number(al.start[1])
    );
    prims.extend(axes::frame(&xa, &ya, [1.0, factor], [&start, ""], true));
    prims.push(Prim::Text {
        pos: [l, t - band - 8.0],
        text: format!("traction ({unit})"),
        size: 12.0,
        anchor: Anchor::Start,
        color: DARK,
    });
    state_band(&mut prims, &pts, &al.s, &xa, t, band);
    let s = &al.s;
    curves(&mut prims, s, [&xa, &ya], [&p, &ft, &fb], &master, &pm);
    if empty {
        prims.push(Prim::Text {
            pos: [0.5 * (l + r), 0.5 * (t + bottom)],
            text: "interface traction 0: every point separated".into(),
            size: 13.0,
            anchor: Anchor::Middle,
            color: [90, 90, 90],
        });
    } else {
        prims.push(Prim::Text {
            pos: [r, t - band - 8.0],
            text: format!(
                "max p = {}",
                quantity(p.iter().copied().fold(0.0, f64::max), "Pa")
            ),
            size: 11.0,
            anchor: Anchor::End,
            color: DARK,
        });
    }
    let placed = flow(
        &entries,
        x0 + 20.0,
        x0 + w - 20.0,
        bottom + axes::BELOW + 8.0,
        12.0,
    );
    prims.extend(placed.prims);
    prims
}

/// The legend entries of the panel of contact part `b` with its points `pts` in order:
/// the curves (the master side's pressure unless `master_empty`) and the states present,
/// with their counts.
fn legend_entries(
    problem: &Problem,
    b: usize,
    pts: &[&ContactResult],
    master_empty: bool,
) -> Vec<Entry> {
    let mut entries = vec![
        Entry::new(
            Swatch::Line {
                color: DARK,
                width: 1.5,
                dashed: false,
            },
            "contact pressure p",
        ),
        Entry::new(
            Swatch::Line {
                color: BLUE,
                width: 2.5,
                dashed: false,
            },
            "friction traction ‖σ_τ‖",
        ),
        Entry::new(
            Swatch::Line {
                color: ORANGE,
                width: 1.5,
                dashed: true,
            },
            "friction bound F",
        ),
    ];
    if let (false, Some(m)) = (master_empty, problem.contact[b].against) {
        entries.insert(
            1,
            Entry::new(
                Swatch::Line {
                    color: GREY,
                    width: 1.5,
                    dashed: true,
                },
                format!(
                    "pressure on the master side {}",
                    problem.mesh.part_names()[m.part]
                ),
            ),
        );
    }
    let mut states: Vec<(Rgb, &str)> = Vec::new();
    for c in pts {
        let st = state_of(c);
        if !states.contains(&st) {
            states.push(st);
        }
    }
    let order = ["separated", "contact, no friction", "stick", "slip"];
    states.sort_by_key(|st| order.iter().position(|o| *o == st.1));
    for (color, label) in &states {
        let count = pts.iter().filter(|c| state_of(c).1 == *label).count();
        entries.push(Entry::new(
            Swatch::Patch { color: *color },
            format!("{label} ({count})"),
        ));
    }
    entries
}

/// The state band above the plot box, whose bottom is `t - 2` px, `band` px high: each
/// point of `pts` (at arc lengths `s`, m) covers half the way to its neighbours; runs of
/// one state are one rectangle.
fn state_band(
    prims: &mut Vec<Prim>,
    pts: &[&ContactResult],
    s: &[f64],
    xa: &Axis,
    t: f64,
    band: f64,
) {
    let edge = |k: usize| {
        if k == 0 {
            s[0]
        } else if k == s.len() {
            s[k - 1]
        } else {
            0.5 * (s[k - 1] + s[k])
        }
    };
    let mut k = 0;
    while k < pts.len() {
        let st = state_of(pts[k]);
        let mut e = k + 1;
        while e < pts.len() && state_of(pts[e]) == st {
            e += 1;
        }
        let (xa0, xa1) = (xa.px(edge(k)), xa.px(edge(e)).max(xa.px(edge(k)) + 1.0));
        prims.push(Prim::Polygon {
            points: vec![
                [xa0, t - band - 2.0],
                [xa1, t - band - 2.0],
                [xa1, t - 2.0],
                [xa0, t - 2.0],
            ],
            fill: st.0,
        });
        k = e;
    }
}

/// The curves against the arc lengths `s` (m) on the axes `[xa, ya]`: the friction
/// traction `ft`, the pressure `p` with its points, the master side's pressure `pm` at the
/// arc lengths of `master` (if any), and the friction bound `fb` (Pa).
fn curves(
    prims: &mut Vec<Prim>,
    s: &[f64],
    [xa, ya]: [&Axis; 2],
    [p, ft, fb]: [&[f64]; 3],
    master: &[(f64, f64)],
    pm: &[f64],
) {
    let curve = |v: &[f64]| -> Vec<[f64; 2]> {
        s.iter()
            .zip(v)
            .map(|(si, vi)| [xa.px(*si), ya.px(*vi)])
            .collect()
    };
    prims.push(Prim::Polyline {
        points: curve(ft),
        color: BLUE,
        width: 2.5,
        dashed: false,
    });
    prims.push(Prim::Polyline {
        points: curve(p),
        color: DARK,
        width: 1.5,
        dashed: false,
    });
    for q in curve(p) {
        prims.push(Prim::Circle {
            center: q,
            radius: 2.0,
            fill: DARK,
        });
    }
    if !master.is_empty() {
        let points: Vec<[f64; 2]> = master
            .iter()
            .zip(pm)
            .map(|(m, v)| [xa.px(m.0), ya.px(*v)])
            .collect();
        for q in &points {
            prims.push(Prim::Polygon {
                points: vec![
                    [q[0] - 2.5, q[1] - 2.5],
                    [q[0] + 2.5, q[1] - 2.5],
                    [q[0] + 2.5, q[1] + 2.5],
                    [q[0] - 2.5, q[1] + 2.5],
                ],
                fill: GREY,
            });
        }
        prims.push(Prim::Polyline {
            points,
            color: GREY,
            width: 1.5,
            dashed: true,
        });
    }
    prims.push(Prim::Polyline {
        points: curve(fb),
        color: ORANGE,
        width: 1.5,
        dashed: true,
    });
}
