//! The stability matrix of docs/stability.md, asserted: for every classic failure mode, what the
//! naive formula does (measured here, so the table cannot claim a failure that does not happen) and
//! what `phong` does instead. The rows live in `tools/src/stability_cases.rs`, shared with the
//! accuracy example that writes the document.

use phong_tools::stability_cases;

use stability_cases::cases;

#[test]
fn naive_code_fails_as_the_matrix_says() {
    for case in cases() {
        let out = (case.naive.run)();
        assert!(
            (case.naive.check)(&out),
            "{}: naive `{}` was claimed to give {}, but gave {out:?}",
            case.mode,
            case.naive.code,
            case.naive.claim
        );
    }
}

#[test]
fn phong_handles_every_row_as_the_matrix_says() {
    for case in cases() {
        let out = (case.phong.run)();
        assert!(
            (case.phong.check)(&out),
            "{}: `{}` was claimed to give {}, but gave {out:?}",
            case.mode,
            case.phong.code,
            case.phong.claim
        );
    }
}

#[test]
fn the_matrix_covers_every_failure_mode_of_the_issue() {
    let modes: Vec<&str> = cases().iter().map(|c| c.mode).collect();
    for wanted in [
        "cut-off",
        "halo",
        "pow(0, 0)",
        "negative pow base",
        "normalize(0)",
        "degenerate triangle",
        "L = −V",
        "d = 0",
        "singular",
        "mirrored",
        "subnormal",
        "NaN",
    ] {
        assert!(
            modes.iter().any(|m| m.contains(wanted)),
            "no row for `{wanted}` in {modes:?}"
        );
    }
}

#[test]
fn docs_stability_md_is_current() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/stability.md");
    let on_disk = std::fs::read_to_string(path).expect("docs/stability.md exists");
    assert!(
        on_disk == stability_cases::markdown(),
        "docs/stability.md is stale: run `cargo run --release -p phong-tools --bin accuracy`"
    );
}
