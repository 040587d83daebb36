//! Every ```console example of README.md and docs/guide/*.md is a test
//! (issue 28 item 3): each `$ sticky ARGS` line runs the built binary from
//! the repository root, and the lines below it must be its output (stdout
//! and stderr together), exactly — `...` on a line of its own matches any
//! lines, `[..]` any text within a line. A non-zero exit is expected only
//! where the block says `? failed`. Blocks marked ```text or ```sh are not
//! run. To refresh the examples after a deliberate change of output:
//! `TRYCMD=overwrite cargo test --release --test console`, then read the diff.

#[test]
fn console_examples_of_readme_and_guide() {
    trycmd::TestCases::new()
        .register_bin("sticky", trycmd::cargo::cargo_bin!("sticky"))
        .case("README.md")
        .case("docs/guide/*.md");
}
