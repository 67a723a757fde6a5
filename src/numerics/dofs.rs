//! How the unknowns of a discretisation are numbered: node by node, each node's components in
//! a row. Every conversion between a node's component and its index in a vector of unknowns
//! (a mesh's, an element's own, or the linear theory's discrete solvers') goes through a
//! [`DofMap`].

/// Component index of `u_x`.
pub const X: usize = 0;
/// Component index of `u_y`.
pub const Y: usize = 1;
/// Component index of `u_z` (three dimensions).
pub const Z: usize = 2;

/// The numbering of the unknowns of nodes with `components` displacement components each:
/// component `c` of node `n` is unknown `components n + c`. The same map numbers an element's
/// own unknowns by its local nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DofMap {
    components: usize,
}

impl DofMap {
    /// Two components per node (plane strain).
    pub const PLANE: DofMap = DofMap { components: 2 };
    /// Three components per node.
    pub const SPACE: DofMap = DofMap { components: 3 };

    /// Components per node in `dimension` dimensions.
    pub const fn of_dimension(dimension: usize) -> DofMap {
        DofMap { components: dimension }
    }

    /// Displacement components per node.
    pub const fn components(self) -> usize {
        self.components
    }

    /// The unknown of component `component` of node `node`.
    #[inline(always)]
    pub const fn dof(self, node: usize, component: usize) -> usize {
        self.components * node + component
    }

    /// The node an unknown belongs to.
    #[inline(always)]
    pub const fn node(self, dof: usize) -> usize {
        dof / self.components
    }

    /// The component an unknown is.
    #[inline(always)]
    pub const fn component(self, dof: usize) -> usize {
        dof % self.components
    }

    /// The global unknown of an element's local unknown `local`, its nodes being `nodes`.
    #[inline(always)]
    pub fn global(self, nodes: &[usize], local: usize) -> usize {
        self.dof(nodes[self.node(local)], self.component(local))
    }

    /// The unknowns of `node`, in component order.
    pub fn node_dofs(self, node: usize) -> std::ops::Range<usize> {
        self.dof(node, 0)..self.dof(node + 1, 0)
    }

    /// Number of unknowns of `nodes` nodes.
    pub const fn count(self, nodes: usize) -> usize {
        self.components * nodes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknowns_round_trip_to_their_node_and_component() {
        for map in [DofMap::PLANE, DofMap::SPACE] {
            for dof in 0..30 {
                assert_eq!(map.dof(map.node(dof), map.component(dof)), dof);
            }
            assert_eq!(map.node_dofs(4).len(), map.components());
            assert_eq!(map.global(&[7, 3], map.dof(1, Y)), map.dof(3, Y));
        }
        assert_eq!(DofMap::PLANE.dof(5, Y), 11);
        assert_eq!(DofMap::SPACE.dof(5, Z), 17);
    }
}
