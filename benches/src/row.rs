use std::time::Instant;

/// One workload's result: its name and a time in nanoseconds per implementation.
#[derive(Debug, Clone)]
pub struct Row {
    /// Workload name.
    pub workload: String,
    /// `(key, nanoseconds)` pairs, e.g. `("ours_ns", 1234.0)`.
    pub times: Vec<(&'static str, Option<f64>)>,
}

impl Row {
    /// A row with the given timings (`None` prints as `null`: the peer has no such workload).
    pub fn new(workload: impl Into<String>, times: Vec<(&'static str, Option<f64>)>) -> Self {
        Row {
            workload: workload.into(),
            times,
        }
    }

    /// One JSON object.
    pub fn to_json(&self) -> String {
        let mut map = serde_json::Map::new();
        map.insert("workload".into(), self.workload.clone().into());
        for (k, v) in &self.times {
            map.insert((*k).into(), v.map(|x| x.round()).into());
        }
        serde_json::Value::Object(map).to_string()
    }

    /// A human-readable line.
    pub fn to_table_line(&self) -> String {
        let cols: Vec<String> = self
            .times
            .iter()
            .map(|(k, v)| match v {
                Some(ns) => format!("{k}={:.1}us", ns / 1000.0),
                None => format!("{k}=n/a"),
            })
            .collect();
        format!("{:<24} {}", self.workload, cols.join("  "))
    }
}

/// Median time in nanoseconds of `f` over enough runs to fill about `budget_ms`
/// (at least 5 runs), after one warm-up run.
pub fn time_ns(budget_ms: u64, mut f: impl FnMut()) -> f64 {
    f();
    let start = Instant::now();
    f();
    let one = start.elapsed().as_nanos().max(1) as u64;
    let runs = ((budget_ms * 1_000_000) / one).clamp(5, 10_000);
    let samples = (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_nanos() as f64
        })
        .collect();
    median(samples)
}

/// The median of `samples` (not empty).
fn median(mut samples: Vec<f64>) -> f64 {
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

/// Median times in nanoseconds of each of `fs`, measured in rounds until
/// about `budget_ms` have passed (at least 5 rounds). A round runs every one
/// of them, in an order that rotates from round to round, as a block: one
/// untimed warm-up run, then `RUNS_PER_BLOCK` (four) timed runs.
///
/// Timings on a shared machine drift: a slow spell of seconds would land on
/// whichever workload [`time_ns`] happens to be timing then, and move the
/// ratio between two workloads by tens of percent. In short blocks, every
/// workload sees the same spells, so their ratios hold; the warm-up run keeps
/// each block's timings free of what the previous workload left in the
/// caches and the allocator.
pub fn time_interleaved_ns<const N: usize>(budget_ms: u64, fs: [&mut dyn FnMut(); N]) -> [f64; N] {
    let mut samples: [Vec<f64>; N] = std::array::from_fn(|_| Vec::new());
    let start = Instant::now();
    let mut round = 0;
    while round < 5 || (start.elapsed().as_millis() as u64) < budget_ms && round < 10_000 {
        for k in 0..N {
            let which = (round + k) % N;
            fs[which]();
            for _ in 0..RUNS_PER_BLOCK {
                let t = Instant::now();
                fs[which]();
                samples[which].push(t.elapsed().as_nanos() as f64);
            }
        }
        round += 1;
    }
    samples.map(median)
}

/// Timed runs per block of [`time_interleaved_ns`].
const RUNS_PER_BLOCK: usize = 4;
