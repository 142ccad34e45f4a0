//! The worker thread count: what `--threads` asks for, at most the machine's cores.

/// Threads to run with when `requested` (by `--threads`; `None` = all cores)
/// meets a machine of `cores` cores: never more than `cores`, since extra
/// workers only contend for them (1000 threads made rendering 100x slower).
/// The second value is the warning to print when the request was clamped.
pub(crate) fn clamp_threads(requested: Option<u32>, cores: usize) -> (usize, Option<String>) {
    let cores = cores.max(1);
    match requested {
        None => (cores, None),
        Some(t) if t as usize > cores => (
            cores,
            Some(format!(
                "--threads {t} is more than the {cores} core{} of this machine; using {cores}",
                if cores == 1 { "" } else { "s" }
            )),
        ),
        Some(t) => (t.max(1) as usize, None),
    }
}

/// The number of cores this process may run on (1 when unknown).
pub(crate) fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_above_the_cores_are_clamped_with_a_warning() {
        assert_eq!(clamp_threads(None, 8), (8, None));
        assert_eq!(clamp_threads(Some(2), 8), (2, None));
        assert_eq!(clamp_threads(Some(8), 8), (8, None));
        let (threads, warning) = clamp_threads(Some(1000), 2);
        assert_eq!(threads, 2);
        let warning = warning.unwrap();
        assert!(warning.contains("--threads 1000"), "{warning}");
        assert!(warning.contains("using 2"), "{warning}");
        assert_eq!(clamp_threads(Some(4), 0).0, 1);
    }
}
