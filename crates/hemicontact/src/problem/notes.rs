//! The notes on a problem worth telling the user, warnings that do not stop a run
//! ([`Problem::notes`]).

use super::Problem;

impl Problem {
    /// Notes worth telling the user, warnings that do not stop a run: each contact part that
    /// shares nodes with a Dirichlet part (nodes with every displacement component
    /// prescribed are not contact nodes (a node on Γ_D is never a contact node);
    /// nodes on a roller keep contact on their free components), and each contact part that
    /// turns corners (nodes split into one contact point per direction; see
    /// [`crate::contact::nodes`]), and each rigid obstacle that its contact part's mesh does
    /// not resolve: smaller than the part's elements, or reaching into the body between its
    /// nodes ([`crate::contact::placement::resolution_notes`]).
    pub fn notes(&self) -> Vec<String> {
        let names = self.mesh.part_names();
        let full = self.fully_prescribed();
        let mut notes = Vec::new();
        for c in &self.contact {
            let contact = self.mesh.part_nodes(c.part);
            for b in self.dirichlet.iter().filter(|b| b.part != c.part) {
                let shared: Vec<u32> = self
                    .mesh
                    .part_nodes(b.part)
                    .into_iter()
                    .filter(|v| contact.binary_search(v).is_ok())
                    .collect();
                if shared.is_empty() {
                    continue;
                }
                let excluded = shared.iter().filter(|&&v| full[v as usize]).count();
                let others = if excluded < shared.len() {
                    "; the others keep contact on their free components"
                } else {
                    ""
                };
                notes.push(format!(
                    "contact part `{}` shares {} node(s) with Dirichlet part `{}`: {excluded} of \
                     them, with every displacement component prescribed, are not contact nodes{others}",
                    names[c.part],
                    shared.len(),
                    names[b.part]
                ));
            }
        }
        let Ok(points) = self.contact_nodes() else {
            return notes;
        };
        for (b, c) in self.contact.iter().enumerate() {
            let nodes: Vec<u32> = (0..points.len())
                .filter(|&i| points.boundary[i] as usize == b)
                .map(|i| points.node[i])
                .collect();
            // Points of one boundary are ordered by node: corners are runs of equal nodes.
            let corners = nodes.chunk_by(|a, b| a == b).filter(|r| r.len() > 1);
            let (n_corners, n_points) = corners.fold((0, 0), |(n, p), r| (n + 1, p + r.len()));
            if n_corners > 0 {
                notes.push(format!(
                    "contact part `{}` turns corners (facet normals more than {}° apart) at \
                     {n_corners} node(s): they are {n_points} contact points, one per \
                     direction, as if the part were split there",
                    names[c.part],
                    crate::contact::nodes::CORNER_ANGLE_DEG,
                ));
            }
        }
        notes.extend(self.obstacle_notes());
        notes
    }

    /// The notes on the rigid obstacles that their contact part's mesh does not resolve
    /// (part of [`Problem::notes`]): an obstacle smaller than the part's elements, or one
    /// reaching into the body between the part's nodes
    /// ([`crate::contact::placement::resolution_notes`]). Empty without obstacles.
    pub fn obstacle_notes(&self) -> Vec<String> {
        if self.contact.iter().all(|c| c.obstacle.is_none()) {
            return Vec::new();
        }
        let Ok(points) = self.contact_nodes() else {
            return Vec::new();
        };
        let carried = self.carried_displacement();
        self.contact
            .iter()
            .enumerate()
            .flat_map(|(b, c)| {
                crate::contact::placement::resolution_notes(
                    &self.mesh,
                    b,
                    c,
                    &points,
                    carried.as_deref(),
                )
            })
            .collect()
    }
}
