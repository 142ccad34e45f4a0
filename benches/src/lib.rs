//! Peer comparison harness (see `src/bin/peers.rs`).
