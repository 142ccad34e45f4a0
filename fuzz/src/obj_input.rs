//! OBJ inputs: random vertices and faces (indices in and out of range, long
//! polygons, groups), degenerate layouts (a row of triangles, a fan), and
//! mutated text.

use crate::rng::Rng;

/// Most faces a generated OBJ has (the per-input work budget).
pub const MAX_FACES: usize = 20_000;

/// Random OBJ text.
pub fn random_obj(rng: &mut Rng) -> String {
    let mut text = String::new();
    match rng.below(4) {
        0 => layout(&mut text, rng, true),
        1 => layout(&mut text, rng, false),
        _ => scattered(&mut text, rng),
    }
    if rng.one_in(3) {
        let mut bytes = text.into_bytes();
        for _ in 0..1 + rng.below(6) {
            if bytes.is_empty() {
                break;
            }
            let at = rng.below(bytes.len());
            bytes[at] = *rng.pick(b" \n-/0123456789.efvgo#");
        }
        text = String::from_utf8_lossy(&bytes).into_owned();
    }
    text
}

/// A row of equal triangles along X, or a fan around the origin.
fn layout(text: &mut String, rng: &mut Rng, row: bool) {
    let n = 1 + rng.below(MAX_FACES);
    if row {
        for k in 0..n {
            let x = k as f32;
            text.push_str(&format!("v {x} 0 0\nv {x} 0 1\nv {} 0 0\n", x + 1.0));
        }
        for k in 0..n {
            let b = 3 * k + 1;
            text.push_str(&format!("f {b} {} {}\n", b + 1, b + 2));
        }
    } else {
        text.push_str("v 0 0 0\n");
        for k in 0..=n {
            let a = k as f32 / n as f32 * std::f32::consts::TAU;
            text.push_str(&format!("v {} 0 {}\n", 100.0 * a.cos(), 100.0 * a.sin()));
        }
        for k in 0..n {
            text.push_str(&format!("f 1 {} {}\n", k + 3, k + 2));
        }
    }
}

/// Vertices with wild coordinates and faces with wild indices.
fn scattered(text: &mut String, rng: &mut Rng) {
    let vertices = rng.below(40);
    for _ in 0..vertices {
        let c = |rng: &mut Rng| {
            if rng.one_in(10) {
                format!("{:e}", rng.wild_f64())
            } else {
                format!("{}", (rng.below(2000) as f64 - 1000.0) / 100.0)
            }
        };
        text.push_str(&format!("v {} {} {}\n", c(rng), c(rng), c(rng)));
    }
    for _ in 0..rng.below(60) {
        if rng.one_in(10) {
            text.push_str(&format!(
                "{} part{}\n",
                ["o", "g"][rng.below(2)],
                rng.below(3)
            ));
        }
        let corners = 3 + if rng.one_in(5) { rng.below(30) } else { 0 };
        let mut line = "f".to_owned();
        for _ in 0..corners {
            let index: i64 = match rng.below(10) {
                0 => 0,
                1 => -(rng.below(vertices + 2) as i64),
                2 => vertices as i64 + 1 + rng.below(5) as i64,
                _ => 1 + rng.below(vertices.max(1)) as i64,
            };
            line.push_str(&format!(" {index}"));
        }
        text.push_str(&line);
        text.push('\n');
    }
}
