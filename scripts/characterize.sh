#!/usr/bin/env bash
# Regenerates crates/flexure-cli/tests/data/characterization.json: every
# subcommand's --json answer on the examples and on single-joint calls, which
# `cargo test` then holds to 1e-12 relative (the Seam issue's "no answer
# changes"). Run it only after a change meant to change answers, and say
# which answers and why in the commit.
set -euo pipefail
cd "$(dirname "$0")/.."
FLEXURE_BLESS=1 cargo test -p flexure-cli --test all characterization:: -- --exact characterization::no_answer_changes
git diff --stat -- crates/flexure-cli/tests/data/characterization.json
