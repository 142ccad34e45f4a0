//! A fuzz campaign: worker threads draw inputs (mutated built-in scenes and
//! corpus files, random heightmaps and OBJ files), check each under
//! `catch_unwind`, and count outcomes; a watchdog reports inputs that run too long.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::mutate::mutate;
use crate::obj_input::random_obj;
use crate::oracle::{Input, Outcome, check};
use crate::png_input::random_png;
use crate::rng::Rng;

/// What a worker is checking now, and since when (`None` between inputs).
type Running = Mutex<Option<(Instant, Input)>>;

/// An input running longer than this is a hang.
pub const HANG_LIMIT: Duration = Duration::from_secs(10);
/// Stack of a worker thread: the main thread's usual 8 MiB, as `softwalk` has.
const WORKER_STACK: usize = 8 << 20;

/// How to run a campaign.
#[derive(Debug, Clone)]
pub struct Config {
    /// Wall-clock time to run for.
    pub duration: Duration,
    /// Worker threads.
    pub threads: usize,
    /// Seed; worker `k` uses `seed + k`.
    pub seed: u64,
    /// Where panicking, hanging and failed-mid-run inputs are saved (none: not saved).
    pub save_dir: Option<PathBuf>,
    /// Files whose mutations are tried besides the built-in scenes (`fuzz/corpus`).
    pub corpus_dir: Option<PathBuf>,
}

/// An input that went wrong, and how.
#[derive(Debug, Clone)]
pub struct Finding {
    /// The input.
    pub input: Input,
    /// The panic message, the error, or the time it ran.
    pub message: String,
}

/// What a campaign saw.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// Inputs checked (scenes, heightmaps, OBJ files).
    pub tried: u64,
    /// Scene, heightmap and OBJ inputs tried.
    pub by_kind: [u64; 3],
    /// Refused with an error.
    pub rejected: u64,
    /// Accepted and run.
    pub accepted: u64,
    /// Accepted but over the per-input memory budget.
    pub over_budget: u64,
    /// Accepted by validation, then failed while building or stepping.
    pub failed_mid_run: Vec<Finding>,
    /// Inputs that panicked.
    pub panics: Vec<Finding>,
    /// Inputs that ran longer than [`HANG_LIMIT`].
    pub hangs: Vec<Finding>,
    /// The longest time one input took.
    pub slowest: Duration,
    /// Wall-clock time of the campaign.
    pub elapsed: Duration,
}

impl Report {
    fn add(&mut self, other: Report) {
        self.tried += other.tried;
        for k in 0..3 {
            self.by_kind[k] += other.by_kind[k];
        }
        self.rejected += other.rejected;
        self.accepted += other.accepted;
        self.over_budget += other.over_budget;
        self.failed_mid_run.extend(other.failed_mid_run);
        self.panics.extend(other.panics);
        self.hangs.extend(other.hangs);
        self.slowest = self.slowest.max(other.slowest);
    }

    /// A few lines for a terminal.
    pub fn summary(&self) -> String {
        let rate = self.tried as f64 / self.elapsed.as_secs_f64().max(1e-9);
        let mut text = format!(
            "inputs tried: {} in {:.1} s ({rate:.0}/s): {} scenes, {} heightmaps, {} OBJ files\n\
             rejected with an error: {}, accepted and run: {}, accepted but over the per-input budget: {}\n\
             panics: {}, hangs (> {} s): {}, accepted by validation but failed mid-run: {}\n\
             slowest input: {:.2} s\n",
            self.tried,
            self.elapsed.as_secs_f64(),
            self.by_kind[0],
            self.by_kind[1],
            self.by_kind[2],
            self.rejected,
            self.accepted,
            self.over_budget,
            self.panics.len(),
            HANG_LIMIT.as_secs(),
            self.hangs.len(),
            self.failed_mid_run.len(),
            self.slowest.as_secs_f64(),
        );
        for (what, list) in [
            ("panic", &self.panics),
            ("hang", &self.hangs),
            ("failed mid-run", &self.failed_mid_run),
        ] {
            for f in list.iter().take(5) {
                text.push_str(&format!("  {what}: {}\n", f.message));
            }
        }
        text
    }
}

/// Checks one input, turning a panic into a [`Finding`].
pub fn check_caught(input: &Input, dir: &Path) -> Result<Outcome, String> {
    catch_unwind(AssertUnwindSafe(|| check(input, dir))).map_err(|payload| {
        payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic with a non-text payload".into())
    })
}

/// The seeds inputs are mutated from: the built-in scenes, then the corpus's scene files.
pub fn seeds(corpus: Option<&Path>) -> Vec<String> {
    let mut seeds: Vec<String> = softwalk_app::scene::builtin_scenes()
        .into_iter()
        .map(|b| b.toml)
        .collect();
    if let Some(dir) = corpus
        && let Ok(entries) = std::fs::read_dir(dir)
    {
        let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        paths.sort();
        for p in paths {
            if let Some(Input::Scene(text)) = Input::from_file(&p) {
                seeds.push(text);
            }
        }
    }
    seeds
}

/// A random input: mostly a mutated seed scene, sometimes a heightmap or an OBJ file.
pub fn next_input(rng: &mut Rng, seeds: &[String]) -> Input {
    match rng.below(20) {
        0..=13 => {
            let seed = &seeds[rng.below(seeds.len())];
            Input::Scene(mutate(seed, rng))
        }
        14..=16 => Input::Heightmap(random_png(rng)),
        _ => Input::Obj(random_obj(rng)),
    }
}

/// Runs a campaign for `config.duration` and reports what it saw. Panics are
/// silenced while it runs (the previous panic hook is restored after).
pub fn run(config: &Config) -> Report {
    let seeds = Arc::new(seeds(config.corpus_dir.as_deref()));
    let stop = Arc::new(AtomicBool::new(false));
    let start = Instant::now();
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let current: Vec<Arc<Running>> = (0..config.threads.max(1))
        .map(|_| Arc::new(Mutex::new(None)))
        .collect();
    let mut workers = Vec::new();
    for (k, slot) in current.iter().enumerate() {
        let (seeds, stop, slot) = (seeds.clone(), stop.clone(), slot.clone());
        let seed = config.seed.wrapping_add(k as u64);
        let dir = std::env::temp_dir().join(format!("softwalk-fuzz-{}-{k}", std::process::id()));
        let spawned = std::thread::Builder::new()
            .name(format!("fuzz-{k}"))
            .stack_size(WORKER_STACK)
            .spawn(move || worker(seed, &seeds, &dir, &stop, &slot));
        if let Ok(handle) = spawned {
            workers.push(handle);
        }
    }
    let mut report = Report::default();
    let mut reported_hangs: Vec<usize> = Vec::new();
    let deadline = start + config.duration;
    // Watch until the deadline, then give running inputs up to HANG_LIMIT to finish.
    while !workers.iter().all(|w| w.is_finished()) {
        let now = Instant::now();
        if now >= deadline {
            stop.store(true, Ordering::Relaxed);
        }
        for (k, slot) in current.iter().enumerate() {
            let running = slot.lock().map(|s| s.clone()).unwrap_or(None);
            if let Some((since, input)) = running
                && now.duration_since(since) > HANG_LIMIT
                && !reported_hangs.contains(&k)
            {
                reported_hangs.push(k);
                report.hangs.push(Finding {
                    input,
                    message: format!("worker {k}: still running after {HANG_LIMIT:?}"),
                });
            }
        }
        if now >= deadline + HANG_LIMIT * 2 {
            break; // Stuck workers are left behind; their inputs are reported as hangs.
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    for w in workers {
        if w.is_finished() {
            match w.join() {
                Ok(part) => report.add(part),
                Err(_) => report.panics.push(Finding {
                    input: Input::Scene(String::new()),
                    message: "the harness itself panicked outside an input".into(),
                }),
            }
        }
    }
    std::panic::set_hook(previous_hook);
    report.elapsed = start.elapsed();
    if let Some(dir) = &config.save_dir {
        save_findings(&report, dir);
    }
    report
}

fn worker(seed: u64, seeds: &[String], dir: &Path, stop: &AtomicBool, slot: &Running) -> Report {
    let mut rng = Rng::new(seed);
    let mut report = Report::default();
    if std::fs::create_dir_all(dir).is_err() {
        return report;
    }
    while !stop.load(Ordering::Relaxed) {
        let input = next_input(&mut rng, seeds);
        let began = Instant::now();
        if let Ok(mut s) = slot.lock() {
            *s = Some((began, input.clone()));
        }
        let outcome = check_caught(&input, dir);
        let took = began.elapsed();
        if let Ok(mut s) = slot.lock() {
            *s = None;
        }
        report.tried += 1;
        report.by_kind[match input {
            Input::Scene(_) => 0,
            Input::Heightmap(_) => 1,
            Input::Obj(_) => 2,
        }] += 1;
        report.slowest = report.slowest.max(took);
        match outcome {
            Ok(Outcome::Rejected) => report.rejected += 1,
            Ok(Outcome::Accepted) => report.accepted += 1,
            Ok(Outcome::OverBudget) => report.over_budget += 1,
            Ok(Outcome::FailedMidRun(message)) => {
                report.failed_mid_run.push(Finding { input, message })
            }
            Err(message) => report.panics.push(Finding { input, message }),
        }
    }
    let _ = std::fs::remove_dir_all(dir);
    report
}

/// Writes each finding's input to `dir` as `KIND-HASH.EXT`.
fn save_findings(report: &Report, dir: &Path) {
    let all = [
        ("panic", &report.panics),
        ("hang", &report.hangs),
        ("failed", &report.failed_mid_run),
    ];
    if all.iter().all(|(_, l)| l.is_empty()) || std::fs::create_dir_all(dir).is_err() {
        return;
    }
    for (kind, list) in all {
        for f in list.iter() {
            let hash = f
                .input
                .bytes()
                .iter()
                .fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
                    (h ^ u64::from(*b)).wrapping_mul(0x100_0000_01b3)
                });
            let path = dir.join(format!("{kind}-{hash:016x}.{}", f.input.extension()));
            let _ = std::fs::write(path, f.input.bytes());
        }
    }
}
