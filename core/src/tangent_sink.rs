//! Where a contribution (an interface, a contact) adds its tangent. A contribution declares
//! node lists, its blocks, in [`crate::model::Contribution::coupled_nodes`] and adds every
//! entry as (block, local index, global dof). The model computes each block's slots in the
//! sparsity pattern once, at `Model::finalize`, as it does for the elements, so an entry costs
//! one table lookup instead of a search in the pattern.

use crate::sparse::{NO_SLOT, SparsityPattern};

/// The receiver of a contribution's tangent entries.
pub trait TangentSink {
    /// K[r, c] += v for the entry of the contribution's `block`-th node list `nodes`
    /// (`coupled_nodes()[block]`) at local index `(la, lb)` = (a dpn + i, b dpn + j), which is
    /// the global entry `(r, c)` = (nodes[a] dpn + i, nodes[b] dpn + j): dof i of its a-th node,
    /// dof j of its b-th node. Both are given, so a sink may use either.
    fn add(&mut self, block: usize, local: (usize, usize), global: (usize, usize), v: f64);
}

/// A closure of the global dofs is a sink (dense or hashed assembly in tests).
impl<F: FnMut(usize, usize, f64)> TangentSink for F {
    fn add(&mut self, _block: usize, _local: (usize, usize), (r, c): (usize, usize), v: f64) {
        self(r, c, v)
    }
}

/// The slots of one contribution's blocks: for block k with n dofs, an n x n row-major table
/// of pattern slots ([`NO_SLOT`] where a dof is constrained).
#[derive(Debug, Clone, Default)]
pub struct BlockSlots {
    offsets: Vec<usize>,
    sizes: Vec<usize>,
    slots: Vec<u32>,
}

impl BlockSlots {
    /// The slot tables of `blocks` (node lists), with `dof_of(node, component)` the free dof or
    /// None, `dpn` dofs per node; every pair of a block's free dofs must be in `pattern`.
    pub fn new(
        blocks: &[Vec<usize>],
        dpn: usize,
        pattern: &SparsityPattern,
        dof_of: impl Fn(usize, usize) -> Option<usize>,
    ) -> Self {
        let mut table = Self::default();
        let (mut dofs, mut slots) = (Vec::new(), Vec::new());
        for nodes in blocks {
            dofs.clear();
            dofs.extend(nodes.iter().flat_map(|&node| (0..dpn).map(move |c| (node, c))).map(|(n, c)| dof_of(n, c)));
            pattern.element_slots(&dofs, &mut slots);
            table.offsets.push(table.slots.len());
            table.sizes.push(dofs.len());
            table.slots.extend_from_slice(&slots);
        }
        table
    }

    /// The slot of local entry (la, lb) of `block`, or [`NO_SLOT`].
    #[inline]
    pub fn slot(&self, block: usize, (la, lb): (usize, usize)) -> u32 {
        let n = self.sizes[block];
        debug_assert!(la < n && lb < n, "local entry ({la}, {lb}) outside block {block} of {n} dofs");
        self.slots[self.offsets[block] + la * n + lb]
    }
}

/// The model's sink: entries go through the precomputed slots into the tangent values.
pub(crate) struct SlotSink<'a> {
    pub values: &'a mut [f64],
    pub blocks: &'a BlockSlots,
    /// For the debug check that a block entry's slot is its global entry's.
    pub pattern: &'a SparsityPattern,
    pub free_index: &'a [usize],
}

impl TangentSink for SlotSink<'_> {
    #[inline]
    fn add(&mut self, block: usize, local: (usize, usize), (r, c): (usize, usize), v: f64) {
        let s = self.blocks.slot(block, local);
        debug_assert_eq!(
            (s != NO_SLOT).then_some(s as usize),
            match (self.free_index[r], self.free_index[c]) {
                (fr, fc) if fr != usize::MAX && fc != usize::MAX => self.pattern.slot(fr, fc),
                _ => None,
            },
            "block {block} local entry {local:?} is not global entry ({r}, {c})"
        );
        if s != NO_SLOT {
            self.values[s as usize] += v;
        }
    }
}

/// A sink that passes each block's entries on to `inner` only if none of the block's diagonal
/// entries (summed over the block's calls) is negative: a point whose interface law has a
/// negative normal stiffness (an attractive tail, a softening branch) adds nothing. For a
/// normal-only law a point's block is rank one, -k N N^T (x) n n^T, so this keeps exactly its
/// positive-curvature points; the tangent left is the convex part a descent method wants. A
/// block is judged on its consecutive entries (the contributions give a point's entries
/// together); [`ConvexSink::finish`] judges the last one.
pub(crate) struct ConvexSink<'a, S: TangentSink> {
    inner: &'a mut S,
    block: Option<usize>,
    entries: Vec<((usize, usize), (usize, usize), f64)>,
    /// Summed diagonal entries of the current block, by local index.
    diagonal: Vec<(usize, f64)>,
}

impl<'a, S: TangentSink> ConvexSink<'a, S> {
    pub fn new(inner: &'a mut S) -> Self {
        Self { inner, block: None, entries: Vec::new(), diagonal: Vec::new() }
    }

    /// Passes the current block on if it has no negative diagonal entry.
    pub fn finish(&mut self) {
        if let Some(block) = self.block.take()
            && self.diagonal.iter().all(|&(_, d)| d >= 0.0)
        {
            for &(local, global, v) in &self.entries {
                self.inner.add(block, local, global, v);
            }
        }
        self.entries.clear();
        self.diagonal.clear();
    }
}

impl<S: TangentSink> TangentSink for ConvexSink<'_, S> {
    fn add(&mut self, block: usize, local: (usize, usize), global: (usize, usize), v: f64) {
        if self.block != Some(block) {
            self.finish();
            self.block = Some(block);
        }
        if local.0 == local.1 {
            match self.diagonal.iter_mut().find(|(l, _)| *l == local.0) {
                Some((_, d)) => *d += v,
                None => self.diagonal.push((local.0, v)),
            }
        }
        self.entries.push((local, global, v));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two overlapping blocks on a 3-node chain, node 0 fixed: each block entry lands in the
    /// slot of its global entry, and constrained entries have none.
    /// Blocks with a negative summed diagonal entry are left out, the others passed on whole.
    #[test]
    fn the_convex_sink_leaves_out_the_blocks_of_negative_stiffness() {
        let mut kept = Vec::new();
        let mut inner = |r: usize, c: usize, v: f64| kept.push((r, c, v));
        let mut sink = ConvexSink::new(&mut inner);
        // block 0: rank one, positive (kept); block 1: rank one, negative (left out); block 2:
        // a diagonal entry given in two parts summing to a positive value (kept)
        for (block, k) in [(0, 2.0), (1, -3.0)] {
            for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                let sign = if a == b { 1.0 } else { -1.0 };
                sink.add(block, (a, b), (block * 2 + a, block * 2 + b), sign * k);
            }
        }
        sink.add(2, (0, 0), (4, 4), -1.0);
        sink.add(2, (0, 0), (4, 4), 1.5);
        sink.finish();
        let expected = vec![(0, 0, 2.0), (0, 1, -2.0), (1, 0, -2.0), (1, 1, 2.0), (4, 4, -1.0), (4, 4, 1.5)];
        assert_eq!(kept, expected);
    }

    #[test]
    fn block_slots_are_the_pattern_slots_of_the_global_entries() {
        let dof_of = |node: usize, _c: usize| node.checked_sub(1);
        let cells = [vec![0, 1], vec![1, 2]];
        let pattern = SparsityPattern::from_cells(2, 3, 1, cells.iter().map(|c| c.as_slice()), dof_of);
        let blocks = vec![vec![2, 1], vec![0, 1]];
        let table = BlockSlots::new(&blocks, 1, &pattern, dof_of);
        for (k, nodes) in blocks.iter().enumerate() {
            for (a, &na) in nodes.iter().enumerate() {
                for (b, &nb) in nodes.iter().enumerate() {
                    let expected = match (dof_of(na, 0), dof_of(nb, 0)) {
                        (Some(r), Some(c)) => pattern.slot(r, c).map(|s| s as u32).unwrap(),
                        _ => NO_SLOT,
                    };
                    assert_eq!(table.slot(k, (a, b)), expected, "block {k} ({a}, {b})");
                }
            }
        }
        let free_index = vec![usize::MAX, 0, 1];
        let mut values = vec![0.0; pattern.nnz()];
        let mut sink = SlotSink { values: &mut values, blocks: &table, pattern: &pattern, free_index: &free_index };
        sink.add(0, (0, 1), (2, 1), 2.5);
        sink.add(1, (0, 1), (0, 1), 7.0); // constrained row: dropped
        assert_eq!(values[pattern.slot(1, 0).unwrap()], 2.5);
        assert_eq!(values.iter().sum::<f64>(), 2.5);
    }
}
