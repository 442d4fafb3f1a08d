#!/usr/bin/env bash
# Regenerates crates/flexure-cli/tests/data/characterization.json: every
# subcommand's --json answer on the examples and on single-joint calls, which
# `cargo test` then holds to 1e-12 relative (the Seam issue's "no answer
# changes").
#
#   scripts/characterize.sh         appends the answers of calls added at the
#                                   end of the test's list; every answer the
#                                   file holds is kept byte for byte (the diff
#                                   only adds, and a comma after the last entry)
#   scripts/characterize.sh --all   rewrites every answer: only after a change
#                                   meant to change answers, and say which
#                                   answers and why in the commit
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
    "") mode=new ;;
    --all) mode=all ;;
    *) echo "usage: $0 [--all]" >&2; exit 2 ;;
esac
FLEXURE_BLESS=$mode cargo test -p flexure-cli --test all characterization:: -- --exact characterization::no_answer_changes
git diff --stat -- crates/flexure-cli/tests/data/characterization.json
