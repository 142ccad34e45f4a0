//! Text mutations of TOML scene files: numbers swapped for boundary values,
//! lines deleted, duplicated or moved, keys and tables inserted, bytes flipped.

use crate::rng::Rng;

/// Values that sit on or beyond the edges of what a scene accepts.
const INTERESTING: &[&str] = &[
    "0",
    "0.0",
    "-0.0",
    "1",
    "-1",
    "2",
    "1e-45",
    "1.0e-45",
    "-1e-45",
    "1e-7",
    "0.5",
    "0.999999",
    "1.000001",
    "11.999",
    "12.0",
    "60.0",
    "89.9",
    "3.4e38",
    "-3.4e38",
    "1e30",
    "-1e30",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "65535",
    "65536",
    "8192",
    "8193",
    "10000",
    "100000",
    "1000000",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "-9223372036854775808",
    "0.004166667",
    "0.05",
    "0.0041",
    "0.051",
    "[]",
    "[0.0]",
    "[1.0, 2.0]",
    "[1e30, 1e30]",
    "\"\"",
    "\"x\"",
    "true",
    "{}",
];

/// Keys that scenes use somewhere, for insertions in the wrong place.
const KEYS: &[&str] = &[
    "kind",
    "angle_deg",
    "direction_deg",
    "amplitude",
    "wavelength",
    "seed",
    "octaves",
    "gain",
    "height",
    "blade_width",
    "density",
    "every",
    "width",
    "dt",
    "duration",
    "beta",
    "alpha",
    "resolution",
    "size_x",
    "size_z",
    "max_height",
    "x",
    "z",
    "path",
    "height_scale",
    "points",
    "corner_radius",
    "bogus",
    "start",
    "length",
    "heading_deg",
    "gif",
    "apng",
    "contact_sheet_columns",
];

/// Table headers scenes use, for insertions anywhere.
const TABLES: &[&str] = &[
    "[terrain]",
    "[terrain.shape]",
    "[[terrain.regions]]",
    "[terrain.base_slope]",
    "[sim]",
    "[render]",
    "[camera]",
    "[camera.mode]",
    "[[grass]]",
    "[[characters]]",
    "[characters.body]",
    "[characters.path]",
    "[[materials]]",
    "[materials.gait]",
];

/// Kinds of the tagged tables.
const KINDS: &[&str] = &[
    "\"flat\"",
    "\"slope\"",
    "\"dunes\"",
    "\"noise\"",
    "\"heightmap\"",
    "\"straight\"",
    "\"waypoints\"",
    "\"follow\"",
    "\"fixed\"",
    "\"medium\"",
    "\"small\"",
];

/// `text` changed by one to four random mutations.
pub fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut out = text.to_owned();
    for _ in 0..1 + rng.below(4) {
        out = mutate_once(&out, rng);
    }
    out
}

fn mutate_once(text: &str, rng: &mut Rng) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    if lines.is_empty() {
        lines.push(String::new());
    }
    let at = rng.below(lines.len());
    match rng.below(12) {
        0..=3 => replace_value(&mut lines[at], rng),
        4 => {
            lines.remove(at);
        }
        5 => {
            let copy = lines[at].clone();
            let to = rng.below(lines.len() + 1);
            lines.insert(to, copy);
        }
        6 => {
            let other = rng.below(lines.len());
            lines.swap(at, other);
        }
        7 => {
            let value = random_value(rng);
            lines.insert(at, format!("{} = {value}", rng.pick(KEYS)));
        }
        8 => lines.insert(at, (*rng.pick(TABLES)).to_owned()),
        9 => {
            if let Some((key, _)) = lines[at].split_once('=') {
                lines[at] = format!("{key}= {}", rng.pick(KINDS));
            }
        }
        10 => return flip_bytes(text, rng),
        _ => {
            // Repeat a table with its body: many regions, patches or characters.
            let copies = if rng.one_in(20) {
                2000
            } else {
                1 + rng.below(8)
            };
            let block: Vec<String> = lines[at..(at + 4).min(lines.len())].to_vec();
            for _ in 0..copies {
                lines.extend(block.iter().cloned());
            }
        }
    }
    let mut joined = lines.join("\n");
    joined.push('\n');
    joined
}

/// Replaces the value of a `key = value` line, or a number inside the line.
fn replace_value(line: &mut String, rng: &mut Rng) {
    let value = random_value(rng);
    if let Some((key, _)) = line.split_once('=') {
        *line = format!("{key}= {value}");
    } else {
        line.push_str(&format!(" {value}"));
    }
}

/// A boundary value, or a random number.
fn random_value(rng: &mut Rng) -> String {
    match rng.below(3) {
        0 => format!("{:e}", rng.wild_f64()),
        1 => format!("{}", rng.wild_f64() as i64),
        _ => (*rng.pick(INTERESTING)).to_owned(),
    }
}

/// A few random byte changes (the result is kept only if it is still UTF-8).
fn flip_bytes(text: &str, rng: &mut Rng) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for _ in 0..1 + rng.below(4) {
        if bytes.is_empty() {
            break;
        }
        let at = rng.below(bytes.len());
        match rng.below(3) {
            0 => bytes[at] = *rng.pick(b" =[]{}\".,#\n0123456789e-"),
            1 => {
                bytes.remove(at);
            }
            _ => bytes.truncate(at),
        }
    }
    String::from_utf8(bytes).unwrap_or_else(|_| text.to_owned())
}
