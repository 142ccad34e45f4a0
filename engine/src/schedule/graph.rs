//! Resolving ordering constraints into one fixed order.

use std::collections::BTreeSet;

/// Topological order of `count` nodes under `edges` (`(a, b)`: a runs before b).
/// Among ready nodes the smallest index (insertion order) goes first, so the
/// result is deterministic. On a cycle, returns the nodes of one cycle in order.
pub(crate) fn topological_order(
    count: usize,
    edges: &[(usize, usize)],
) -> Result<Vec<usize>, Vec<usize>> {
    let mut successors = vec![Vec::new(); count];
    let mut in_degree = vec![0usize; count];
    for &(a, b) in edges {
        successors[a].push(b);
        in_degree[b] += 1;
    }
    let mut ready: BTreeSet<usize> = (0..count).filter(|&n| in_degree[n] == 0).collect();
    let mut order = Vec::with_capacity(count);
    while let Some(node) = ready.pop_first() {
        order.push(node);
        for &next in &successors[node] {
            in_degree[next] -= 1;
            if in_degree[next] == 0 {
                ready.insert(next);
            }
        }
    }
    if order.len() == count {
        return Ok(order);
    }
    Err(find_cycle(&successors, &in_degree))
}

/// A cycle among the nodes left with a positive in-degree: every such node
/// has a predecessor also left, so walking predecessors must revisit a node.
fn find_cycle(successors: &[Vec<usize>], in_degree: &[usize]) -> Vec<usize> {
    let left = |n: usize| in_degree[n] > 0;
    let mut predecessor = vec![None; successors.len()];
    for (a, nexts) in successors.iter().enumerate() {
        for &b in nexts {
            if left(a) && left(b) && predecessor[b].is_none() {
                predecessor[b] = Some(a);
            }
        }
    }
    let start = (0..successors.len())
        .find(|&n| left(n))
        .expect("a cycle leaves nodes");
    let mut seen_at = vec![None; successors.len()];
    let mut path = Vec::new();
    let mut node = start;
    while seen_at[node].is_none() {
        seen_at[node] = Some(path.len());
        path.push(node);
        node = predecessor[node].expect("a node left after sorting has a predecessor left");
    }
    let mut cycle = path.split_off(seen_at[node].expect("revisited"));
    cycle.reverse();
    // Start the cycle at its earliest-inserted node for a stable message.
    let first = cycle
        .iter()
        .enumerate()
        .min_by_key(|(_, n)| **n)
        .map(|(i, _)| i)
        .unwrap_or(0);
    cycle.rotate_left(first);
    cycle
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ties_go_to_insertion_order() {
        assert_eq!(topological_order(4, &[]), Ok(vec![0, 1, 2, 3]));
        assert_eq!(topological_order(4, &[(3, 0)]), Ok(vec![1, 2, 3, 0]));
    }

    #[test]
    fn cycle_is_reported_in_order() {
        // 0 -> 1 -> 2 -> 0, and 3 hangs off 2.
        let cycle = topological_order(4, &[(0, 1), (1, 2), (2, 0), (2, 3)]).unwrap_err();
        assert_eq!(cycle, vec![0, 1, 2]);
    }

    #[test]
    fn self_edge_is_a_cycle() {
        assert_eq!(topological_order(2, &[(1, 1)]), Err(vec![1]));
    }
}
