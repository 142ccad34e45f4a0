//! The `softwalk` program's library: scenes, the command line and outputs.
