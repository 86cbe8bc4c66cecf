//! Reduced ordered decision diagrams built bottom-up from complete truth tables, every function
//! of a theory in one diagram so equal subfunctions are stored once.

use std::collections::HashMap;

/// One node: test `var`, go `low` when it is false and `high` when it is true. Nodes 0 and 1
/// are the terminals false and true (their fields unused).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Node {
    pub var: u32,
    pub low: u32,
    pub high: u32,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagram {
    pub variables: usize,
    pub nodes: Vec<Node>,
    /// One root a function.
    pub roots: Vec<u32>,
}

impl Diagram {
    /// The diagram of `columns`, each a function's value on every row; row `r` assigns variable
    /// `v` the bit `variables - 1 - v` of `r` (the first variable varies slowest), and variables
    /// are tested in that order. Reduced: no node has equal children, no two nodes are equal.
    pub fn from_columns(variables: usize, columns: &[Vec<bool>]) -> Diagram {
        let terminal = Node {
            var: variables as u32,
            low: 0,
            high: 0,
        };
        let mut builder = Builder {
            variables,
            nodes: vec![
                terminal,
                Node {
                    low: 1,
                    high: 1,
                    ..terminal
                },
            ],
            unique: HashMap::new(),
        };
        let roots = columns
            .iter()
            .map(|column| {
                assert_eq!(column.len(), 1 << variables, "a column has a value a row");
                builder.build(column, 0)
            })
            .collect();
        Diagram {
            variables,
            nodes: builder.nodes,
            roots,
        }
    }

    /// The function under `root` at one assignment.
    pub fn eval(&self, root: u32, assignment: &[bool]) -> bool {
        let mut node = root;
        while node > 1 {
            let n = self.nodes[node as usize];
            node = if assignment[n.var as usize] {
                n.high
            } else {
                n.low
            };
        }
        node == 1
    }

    /// Bytes of one child index in C: two while every node fits.
    pub fn index_bytes(&self) -> usize {
        if self.nodes.len() <= 1 << 16 {
            2
        } else {
            4
        }
    }
}

struct Builder {
    variables: usize,
    nodes: Vec<Node>,
    unique: HashMap<Node, u32>,
}

impl Builder {
    /// The node of the function whose values over the remaining variables (from `var` on) are
    /// `rows`.
    fn build(&mut self, rows: &[bool], var: usize) -> u32 {
        if var == self.variables {
            return u32::from(rows[0]);
        }
        let (low_rows, high_rows) = rows.split_at(rows.len() / 2);
        let low = self.build(low_rows, var + 1);
        let high = self.build(high_rows, var + 1);
        if low == high {
            return low;
        }
        let node = Node {
            var: var as u32,
            low,
            high,
        };
        let next = self.nodes.len() as u32;
        *self.unique.entry(node).or_insert_with(|| {
            self.nodes.push(node);
            next
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_conjunction_is_two_nodes_and_a_constant_none() {
        // a ∧ b over (a, b): rows 00, 01, 10, 11.
        let d = Diagram::from_columns(2, &[vec![false, false, false, true], vec![true; 4]]);
        assert_eq!(d.nodes.len(), 4);
        assert_eq!(d.roots[1], 1);
        for row in 0..4usize {
            let a = [row & 2 != 0, row & 1 != 0];
            assert_eq!(d.eval(d.roots[0], &a), a[0] && a[1]);
        }
    }

    #[test]
    fn equal_subfunctions_are_shared_across_columns() {
        // b, and a ∧ b: the node testing b is one node.
        let d = Diagram::from_columns(
            2,
            &[
                vec![false, true, false, true],
                vec![false, false, false, true],
            ],
        );
        assert_eq!(d.nodes.len(), 4);
    }
}
