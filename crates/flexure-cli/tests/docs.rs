//! `docs/cli.md` against the command itself, so the page cannot fall
//! behind: every subcommand has its section, with its usage line, and every
//! option its `--help` lists is in that section (or, for the flexure
//! options, the spatial options and `--json`, in the sections every
//! subcommand shares); every
//! option a section's table lists still exists.

use crate::cli::run;

const PAGE: &str = include_str!("../../../docs/cli.md");

/// The part of the page from `heading` to the next heading of any level 2 or 3.
fn section(heading: &str) -> &'static str {
    let start = PAGE.find(heading).unwrap_or_else(|| panic!("docs/cli.md has no {heading:?}"));
    let body = &PAGE[start + heading.len()..];
    let end = ["\n## ", "\n### "].iter().filter_map(|h| body.find(h)).min().unwrap_or(body.len());
    &body[..end]
}

/// `flexure ARGS --help`, which exits 0.
fn help(args: &[&str]) -> String {
    let mut a = args.to_vec();
    a.push("--help");
    let (code, out, err) = run(&a);
    assert_eq!(code, 0, "{a:?}: {err}");
    out
}

/// The subcommands `flexure --help` lists (without `help`).
fn subcommands() -> Vec<String> {
    let text = help(&[]);
    let list = text.split("Commands:\n").nth(1).expect("flexure --help lists its commands");
    list.lines()
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(String::from)
        .collect()
}

/// The long options (`--name`) a `--help` text lists under `Options:`.
fn options(text: &str) -> Vec<String> {
    let list = text.split("Options:\n").nth(1).unwrap_or("");
    list.lines()
        .map(str::trim_start)
        .map(|l| l.strip_prefix("-h, ").or_else(|| l.strip_prefix("-V, ")).unwrap_or(l))
        .filter(|l| l.starts_with("--"))
        .filter_map(|l| l.split([' ', '\t']).next())
        .filter(|o| !matches!(*o, "--help" | "--version"))
        .map(String::from)
        .collect()
}

/// Whether `text` names `option` as a whole word (`--order` is not found
/// in `--order-x`).
fn names(text: &str, option: &str) -> bool {
    text.match_indices(option).any(|(i, _)| {
        let next = text[i + option.len()..].chars().next();
        !next.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
    })
}

#[test]
fn every_option_of_every_subcommand_is_on_the_page() {
    let shared = [
        section("## What every subcommand shares"),
        section("### The flexure options"),
        section("### The spatial options"),
    ]
    .concat();
    let commands = subcommands();
    assert!(commands.len() >= 12, "{commands:?}");
    let mut missing = Vec::new();
    for cmd in &commands {
        let text = help(&[cmd]);
        let own = section(&format!("### `{cmd}`"));
        let usage = text.lines().find_map(|l| l.strip_prefix("Usage: ")).expect("a usage line");
        if !own.contains(usage) {
            missing.push(format!("{cmd}: its usage line {usage:?}"));
        }
        for option in options(&text) {
            if !names(own, &option) && !names(&shared, &option) {
                missing.push(format!("{cmd} {option}"));
            }
        }
    }
    assert!(missing.is_empty(), "docs/cli.md lacks (refresh it from --help): {missing:#?}");
}

#[test]
fn every_option_on_the_page_exists() {
    let mut stale = Vec::new();
    // The flexure options are those of `deflect`, among others.
    let tables = subcommands().into_iter().map(|c| (format!("### `{c}`"), c));
    for (heading, cmd) in tables.chain([("### The flexure options".to_string(), "deflect".to_string())]) {
        let known = options(&help(&[&cmd]));
        for row in section(&heading).lines().filter_map(|l| l.strip_prefix("| `--")) {
            let option = format!("--{}", row.split(['`', ' ']).next().unwrap_or(""));
            if !known.contains(&option) {
                stale.push(format!("{cmd} {option}"));
            }
        }
    }
    assert!(stale.is_empty(), "docs/cli.md lists options the command no longer has: {stale:?}");
}
