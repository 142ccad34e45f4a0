//! Side-by-side benchmarks against peer crates, measured in the same run.
//!
//! ```text
//! cargo run --release -p benches --bin peers -- ecs --json
//! cargo run --release -p benches --bin peers -- raycast --json
//! cargo run --release -p benches --bin peers -- raster --json
//! ```
//! Each group prints one JSON object per workload (with `--json`) or a table.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let json = args.iter().any(|a| a == "--json");
    let groups: Vec<&str> = args
        .iter()
        .filter(|a| !a.starts_with("--"))
        .map(|s| s.as_str())
        .collect();
    let all = ["ecs", "raycast", "raster"];
    let chosen: Vec<&str> = if groups.is_empty() {
        all.to_vec()
    } else {
        groups
    };
    for group in chosen {
        let rows = match group {
            "ecs" => benches::ecs::run(),
            "raycast" => benches::raycast::run(),
            "raster" => benches::raster::run(),
            other => {
                eprintln!("unknown group `{other}`; expected one of {all:?}");
                std::process::exit(2);
            }
        };
        for row in rows {
            if json {
                println!("{}", row.to_json());
            } else {
                println!("{}", row.to_table_line());
            }
        }
    }
}
