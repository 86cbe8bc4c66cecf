//! The choices one ringlet meets (which time tests came due, what a free type holds when it is
//! read), walked as a tree, leaf by leaf: a ringlet is run once per leaf from its start, each
//! run following the path of choices taken so far and opening a new branch where it meets a
//! choice the path does not reach yet. A ringlet that reads nothing free has one leaf.

/// The path to the current leaf: for each choice met, the branch taken and how many there are.
#[derive(Debug, Default)]
pub struct Choices {
    path: Vec<(u32, u32)>,
    /// How many choices the current run has met.
    met: usize,
}

impl Choices {
    /// The branch to take at the next choice, of `branches` (at least one).
    pub fn branch(&mut self, branches: usize) -> usize {
        let taken = match self.path.get(self.met) {
            Some(&(taken, _)) => taken,
            None => {
                self.path.push((0, branches.max(1) as u32));
                0
            }
        };
        self.met += 1;
        taken as usize
    }

    /// Moves to the next leaf, ready for a new run; false once every leaf was visited.
    pub fn advance(&mut self) -> bool {
        self.path.truncate(self.met);
        self.met = 0;
        while let Some((taken, branches)) = self.path.pop() {
            if taken + 1 < branches {
                self.path.push((taken + 1, branches));
                return true;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The leaves of a run that meets a choice of 2, then (on its first branch only) one of 3.
    #[test]
    fn every_leaf_once_in_order() {
        let mut choices = Choices::default();
        let mut leaves = Vec::new();
        loop {
            let a = choices.branch(2);
            let b = if a == 0 {
                Some(choices.branch(3))
            } else {
                None
            };
            leaves.push((a, b));
            if !choices.advance() {
                break;
            }
        }
        assert_eq!(
            leaves,
            [(0, Some(0)), (0, Some(1)), (0, Some(2)), (1, None)]
        );
    }

    #[test]
    fn a_run_with_no_choice_is_one_leaf() {
        let mut choices = Choices::default();
        assert!(!choices.advance());
    }
}
