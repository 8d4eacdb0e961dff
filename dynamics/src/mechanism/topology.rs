//! The structure of a mechanism's reaction solve, fixed when the mechanism is built (docs/mechanisms.md §M4).
//!
//! The mechanism is a graph whose vertices are the world and the bodies and whose edges are the joints. A
//! breadth-first search from the world (then from each body not yet reached, the root of a floating
//! component) gives a spanning forest: every body reached through a **tree joint** has that joint as its
//! parent; the other joints close loops (**loop joints**; a second joint between the same two bodies is one).
//!
//! The joint-space matrix `K = J G Jᵀ` couples two joints exactly when they share a body. Its tree part is
//! factored by eliminating, at each vertex v (children before parents), the tree joints that join v to its
//! children: they are coupled only to each other and to v's own parent joint, so the elimination happens in a
//! small dense **front** over `children(v) ∪ {parent(v)}` and creates no fill outside it; what remains of the
//! parent joint's block is passed to the parent vertex's front. A chain is a block-tridiagonal solve; any
//! tree costs O(Σ front²), linear in N for bounded degree.

use std::collections::VecDeque;

/// Which row block of a joint a body sees: the joint's own body (rows in its frame) or its reference body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Side {
    Body,
    Reference,
}

/// Where a joint's multipliers live in the solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Slot {
    /// A tree joint: eliminated in front `front`, its multipliers at `offset` of the tree vector.
    Tree { front: usize, offset: usize },
    /// A loop joint: its multipliers at `offset` of the loop vector.
    Loop { offset: usize },
}

/// One joint seen from one of its bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Incidence {
    pub joint: usize,
    pub side: Side,
    /// Where the joint's block goes in the assembly of this body's contribution.
    pub place: Place,
}

/// Where a joint's rows sit in one body's contribution to K.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Place {
    /// A tree joint: at `local` in the body's front (storage offset `storage`, size `size`), and at `global` in
    /// the tree vector.
    Front {
        storage: usize,
        size: usize,
        local: usize,
        global: usize,
    },
    /// A loop joint, at `offset` in the loop vector.
    Loop { offset: usize },
}

/// A dense front: the tree joints eliminated at one vertex, then the vertex's parent joint. Its variables are
/// two contiguous runs of the tree vector: the eliminated joints' rows (`start..start + eliminated`, consecutive
/// because they are numbered front by front), then the parent joint's (`parent_start..parent_start +
/// parent_size`, eliminated by a later front, so at higher indices).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Front {
    pub start: usize,
    pub eliminated: usize,
    pub parent_start: usize,
    pub parent_size: usize,
    /// The front receiving this front's Schur complement (where the parent joint is eliminated), and the local
    /// index of the parent joint's first variable there.
    pub parent: Option<(usize, usize)>,
    /// Offset of this front's `n × n` matrix in the factor storage.
    pub storage: usize,
}

impl Front {
    pub fn size(&self) -> usize {
        self.eliminated + self.parent_size
    }

    /// The local index of tree variable `variable` in this front, if it is one of the front's.
    pub fn local(&self, variable: usize) -> Option<usize> {
        if (self.start..self.start + self.eliminated).contains(&variable) {
            Some(variable - self.start)
        } else if (self.parent_start..self.parent_start + self.parent_size).contains(&variable) {
            Some(self.eliminated + variable - self.parent_start)
        } else {
            None
        }
    }
}

/// The solve's structure.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Topology {
    /// Per joint: its slot.
    pub slots: Vec<Slot>,
    /// Per body: the joints incident to it.
    pub incidences: Vec<Vec<Incidence>>,
    /// Fronts in elimination order (children before parents).
    pub fronts: Vec<Front>,
    /// Size of the tree and loop multiplier vectors.
    pub tree_size: usize,
    pub loop_size: usize,
    /// Total size of the fronts' dense matrices.
    pub storage: usize,
    /// Per loop joint (by joint index): the tree joints on the cycle it closes (the loop's names in errors).
    pub cycles: Vec<Vec<usize>>,
    /// The joint of each tree variable and of each loop variable.
    pub tree_owner: Vec<usize>,
    pub loop_owner: Vec<usize>,
}

/// A vertex: the world or a body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Vertex {
    World,
    Body(usize),
}

impl Topology {
    /// The structure for `bodies` bodies and joints `(body, reference, rank)` (reference `None` = the world).
    ///
    /// Built by the [`crate::Mechanism`] whenever a body or joint is added (this type is internal); its split of
    /// the joints shows in [`crate::Mechanism::loop_joints`]. A two-rod chain hung from the world is a tree. A third
    /// joint holding the lower rod's end to a world plane closes a loop through the world; the breadth-first tree
    /// then reaches both rods straight from the world, so the elbow is the joint that closes the loop. The reactions
    /// are still solved.
    ///
    /// ```
    /// use dynamics::constraints::VirtualPower;
    /// use dynamics::{Body, Force, Mechanism, Pga, Reference, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?;
    /// let (top, bottom) = (Vector3::new(0.0, 0.0, 0.5), Vector3::new(0.0, 0.0, -0.5)); // body points, m
    /// let mut chain = Mechanism::<Pga>::new();
    /// let (upper, lower) = (chain.add_body("upper", rod)?, chain.add_body("lower", rod)?);
    /// chain.add_force(upper, Force::gravity())?;
    /// chain.add_force(lower, Force::gravity())?;
    /// chain.add_joint(upper, Reference::World, VirtualPower::ball_joint("shoulder", top, Vector3::zeros()))?;
    /// chain.add_joint(lower, upper, VirtualPower::ball_joint("elbow", top, bottom))?;
    /// assert_eq!(chain.loop_joints().count(), 0);
    /// chain.add_joint(lower, Reference::World, VirtualPower::point_on_plane("wrist", bottom, (Vector3::x(), 0.0))?)?;
    /// assert_eq!(chain.loop_joints().map(|j| j.index()).collect::<Vec<_>>(), vec![1]); // the elbow
    ///
    /// let still = UnitQuaternion::identity();
    /// let hanging = |z: f64| State::new(&rod, Vector3::z() * z, &still, Vector3::zeros(), Vector3::zeros());
    /// assert!(chain.rates_at(0.0, &[hanging(-0.5), hanging(-1.5)]).is_ok());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(bodies: usize, joints: &[(usize, Option<usize>, usize)]) -> Topology {
        // Adjacency: per vertex (0 = world, 1 + i = body i), the joints at it.
        let vertex = |v: Vertex| match v {
            Vertex::World => 0,
            Vertex::Body(i) => i + 1,
        };
        let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); bodies + 1];
        // A joint of rank 0 (a free joint model, which constrains nothing) joins no bodies in the solve: it ends as
        // an empty loop slot.
        for (j, &(body, reference, rank)) in joints.iter().enumerate() {
            if rank == 0 {
                continue;
            }
            adjacent[body + 1].push(j);
            adjacent[reference.map_or(0, |r| r + 1)].push(j);
        }
        let other = |j: usize, v: usize| {
            let (body, reference, _) = joints[j];
            let (b, a) = (body + 1, reference.map_or(0, |r| r + 1));
            if v == b {
                a
            } else {
                b
            }
        };

        // Breadth-first spanning forest: parent joint and parent vertex per vertex, in discovery order.
        let mut parent_joint: Vec<Option<usize>> = vec![None; bodies + 1];
        let mut parent_vertex: Vec<Option<usize>> = vec![None; bodies + 1];
        let mut visited = vec![false; bodies + 1];
        let mut is_tree = vec![false; joints.len()];
        let mut order = Vec::with_capacity(bodies + 1);
        for root in std::iter::once(Vertex::World).chain((0..bodies).map(Vertex::Body)) {
            let root = vertex(root);
            if visited[root] {
                continue;
            }
            visited[root] = true;
            let mut queue = VecDeque::from([root]);
            while let Some(v) = queue.pop_front() {
                order.push(v);
                for &j in &adjacent[v] {
                    let w = other(j, v);
                    if !visited[w] {
                        visited[w] = true;
                        is_tree[j] = true;
                        parent_joint[w] = Some(j);
                        parent_vertex[w] = Some(v);
                        queue.push_back(w);
                    }
                }
            }
        }

        // Children (tree joints) per vertex, in joint order.
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); bodies + 1];
        for v in 0..=bodies {
            if let (Some(j), Some(p)) = (parent_joint[v], parent_vertex[v]) {
                children[p].push(j);
            }
        }

        // Tree offsets in elimination order: a vertex's children are eliminated at its front, vertices from the
        // deepest (last discovered) up, so every joint's offset precedes its parent vertex's joints.
        let mut slots = vec![Slot::Loop { offset: 0 }; joints.len()];
        let mut tree_size = 0;
        let mut front_of_vertex: Vec<Option<usize>> = vec![None; bodies + 1];
        let mut fronts: Vec<Front> = Vec::new();
        let mut storage = 0;
        // First pass: offsets of the eliminated joints, front by front.
        let elimination: Vec<usize> = order.iter().rev().copied().collect();
        for &v in &elimination {
            // A vertex gets a front if it eliminates joints. A leaf body's only tree joint is its parent joint,
            // whose block it adds straight into the front that eliminates that joint.
            if children[v].is_empty() {
                continue;
            }
            front_of_vertex[v] = Some(fronts.len());
            let start = tree_size;
            for &j in &children[v] {
                slots[j] = Slot::Tree {
                    front: fronts.len(),
                    offset: tree_size,
                };
                tree_size += joints[j].2;
            }
            fronts.push(Front {
                start,
                eliminated: tree_size - start,
                parent_start: 0,
                parent_size: 0,
                parent: None,
                storage: 0,
            });
        }
        // Second pass: each front's parent-joint variables and the front that eliminates them.
        for &v in &elimination {
            let (Some(f), Some(j)) = (front_of_vertex[v], parent_joint[v]) else {
                continue;
            };
            let Slot::Tree { front, offset } = slots[j] else {
                unreachable!("a parent joint is a tree joint");
            };
            let local = offset - fronts[front].start;
            let entry = &mut fronts[f];
            entry.parent_start = offset;
            entry.parent_size = joints[j].2;
            entry.parent = Some((front, local));
        }
        for front in &mut fronts {
            front.storage = storage;
            storage += front.size() * front.size();
        }

        // Loop joints get offsets in joint order.
        let mut loop_size = 0;
        for (j, slot) in slots.iter_mut().enumerate() {
            if !is_tree[j] {
                *slot = Slot::Loop { offset: loop_size };
                loop_size += joints[j].2;
            }
        }

        let place = |j: usize, v: usize| match slots[j] {
            Slot::Tree { offset, front } => {
                // In the body's own front, or for a leaf body (no front) in the front that eliminates its parent
                // joint.
                let front = &fronts[front_of_vertex[v + 1].unwrap_or(front)];
                let local = front.local(offset).expect("a body's tree joints are in its front");
                Place::Front {
                    storage: front.storage,
                    size: front.size(),
                    local,
                    global: offset,
                }
            }
            Slot::Loop { offset } => Place::Loop { offset },
        };
        let mut incidences: Vec<Vec<Incidence>> = vec![Vec::new(); bodies];
        for (j, &(body, reference, _)) in joints.iter().enumerate() {
            incidences[body].push(Incidence {
                joint: j,
                side: Side::Body,
                place: place(j, body),
            });
            if let Some(r) = reference {
                incidences[r].push(Incidence {
                    joint: j,
                    side: Side::Reference,
                    place: place(j, r),
                });
            }
        }

        let cycles = loop_paths(joints, &is_tree, &order, (&parent_joint, &parent_vertex));

        let mut tree_owner = vec![0; tree_size];
        let mut loop_owner = vec![0; loop_size];
        for (j, slot) in slots.iter().enumerate() {
            let (owner, offset) = match *slot {
                Slot::Tree { offset, .. } => (&mut tree_owner, offset),
                Slot::Loop { offset } => (&mut loop_owner, offset),
            };
            owner[offset..offset + joints[j].2].fill(j);
        }

        Topology {
            slots,
            incidences,
            fronts,
            tree_size,
            loop_size,
            storage,
            cycles,
            tree_owner,
            loop_owner,
        }
    }
}

/// Per joint, the tree joints on the path between a loop joint's two vertices (empty for a tree joint): the loop
/// the joint closes, found by climbing from both vertices to their common ancestor.
fn loop_paths(
    joints: &[(usize, Option<usize>, usize)],
    is_tree: &[bool],
    order: &[usize],
    (parent_joint, parent_vertex): (&[Option<usize>], &[Option<usize>]),
) -> Vec<Vec<usize>> {
    let depth = {
        let mut depth = vec![0usize; parent_joint.len()];
        for &v in order {
            if let Some(p) = parent_vertex[v] {
                depth[v] = depth[p] + 1;
            }
        }
        depth
    };
    (0..joints.len())
        .map(|j| {
            if is_tree[j] {
                return Vec::new();
            }
            let (body, reference, _) = joints[j];
            let (mut u, mut w) = (body + 1, reference.map_or(0, |r| r + 1));
            let mut path = Vec::new();
            while u != w {
                let climb = if depth[u] >= depth[w] { &mut u } else { &mut w };
                match (parent_joint[*climb], parent_vertex[*climb]) {
                    (Some(joint), Some(parent)) => {
                        path.push(joint);
                        *climb = parent;
                    }
                    // Different components cannot be joined by a loop joint (it would be a tree joint).
                    _ => break,
                }
            }
            path.sort_unstable();
            path
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chain_is_a_sequence_of_two_joint_fronts() {
        // world -0- b0 -1- b1 -2- b2, ball joints.
        let joints = [(0, None, 3), (1, Some(0), 3), (2, Some(1), 3)];
        let topology = Topology::new(3, &joints);
        assert_eq!(topology.loop_size, 0);
        assert_eq!(topology.tree_size, 9);
        // Fronts: b1 (eliminates 2, parent 1), b0 (eliminates 1, parent 0), world; the leaf b2 has none.
        let sizes: Vec<(usize, usize)> = topology.fronts.iter().map(|f| (f.eliminated, f.size())).collect();
        assert_eq!(sizes, [(3, 6), (3, 6), (3, 3)]);
        assert!(topology.cycles.iter().all(Vec::is_empty));
    }

    #[test]
    fn the_four_bar_has_one_loop_through_the_world() {
        // crank (0), coupler (1), rocker (2); hinges A world–crank, B crank–coupler, C rocker–coupler, D rocker–world.
        let joints = [(0, None, 5), (1, Some(0), 5), (2, Some(1), 5), (2, None, 5)];
        let topology = Topology::new(3, &joints);
        assert_eq!((topology.tree_size, topology.loop_size), (15, 5));
        // D closes the loop crank–coupler–rocker through the world: its cycle is A, B, C (or the equivalent
        // spanning tree's): every other joint.
        let loops: Vec<usize> = (0..4)
            .filter(|&j| matches!(topology.slots[j], Slot::Loop { .. }))
            .collect();
        assert_eq!(loops.len(), 1);
        let cycle = &topology.cycles[loops[0]];
        assert_eq!(cycle.len(), 3);
        assert!(!cycle.contains(&loops[0]));
    }

    #[test]
    fn two_joints_between_the_same_bodies_make_a_loop() {
        let joints = [(0, None, 3), (0, None, 2)];
        let topology = Topology::new(1, &joints);
        // The body is a leaf: only the world's front, which eliminates its joint.
        assert_eq!(topology.slots[0], Slot::Tree { front: 0, offset: 0 });
        assert_eq!(topology.slots[1], Slot::Loop { offset: 0 });
        assert_eq!(topology.cycles[1], vec![0]);
    }
}
