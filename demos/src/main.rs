//! The `softwalk` command-line program.
fn main() {
    println!("softwalk: placeholder");
}
