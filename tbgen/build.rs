//! Compiles the built-in scenarios in: every `scenarios/<table>/*.toml`
//! (except `scenarios/bench/`, the benchmark scenarios `make bench` reads
//! by path) becomes one `(file, text)` entry of `builtin::FILES`, in folder
//! then file-name order. `builtin::all` lists them in registry order.

use std::fmt::Write as _;
use std::path::Path;

// Paths are relative to the package (`../scenarios`), in what cargo records
// and in the generated `include_str!`s (through `CARGO_MANIFEST_DIR` when
// tbgen compiles): a target folder copied from another checkout of the
// workspace must neither watch nor compile in that checkout's scenarios.
fn main() {
    let manifest = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let root = Path::new(&manifest).join("../scenarios");
    println!("cargo:rerun-if-changed=../scenarios");
    let mut dirs: Vec<_> = std::fs::read_dir(&root)
        .expect("scenarios/ next to tbgen/")
        .map(|e| e.expect("a readable scenarios/ entry").path())
        .filter(|p| p.is_dir() && p.file_name().is_some_and(|n| n != "bench"))
        .collect();
    dirs.sort();
    let mut out = String::from("&[\n");
    for dir in dirs {
        let folder = dir
            .file_name()
            .unwrap()
            .to_str()
            .expect("a UTF-8 folder name");
        println!("cargo:rerun-if-changed=../scenarios/{folder}");
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .expect("a readable scenarios/<table>/")
            .map(|e| e.expect("a readable scenario file").path())
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        files.sort();
        for file in files {
            let name = file
                .file_name()
                .unwrap()
                .to_str()
                .expect("a UTF-8 file name");
            let rel = format!("{folder}/{name}");
            writeln!(
                out,
                "    ({rel:?}, include_str!(concat!(env!(\"CARGO_MANIFEST_DIR\"), {:?}))),",
                format!("/../scenarios/{rel}")
            )
            .unwrap();
        }
    }
    out.push(']');
    let dest =
        Path::new(&std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("builtin_files.rs");
    std::fs::write(dest, out).expect("OUT_DIR is writable");
}
