#!/usr/bin/env bash
# Mutation smoke test: do the tests of ffd/, widgets/ and geometry/ notice small wrong changes?
#   scripts/mutation-smoke.sh [--count N] [--seed S] [--timeout SECONDS] [--jobs J]
#                             [--work DIR] [--list] [--only PATTERN]
# Draws N (default 60) seeded mutations from every source file under ffd/src, widgets/src and
# geometry/src (selected by path pattern, so added files take part): flip a sign, flip a
# comparison or a logical operator, change a constant by 1, swap an index or a coordinate,
# drop a term. Applies them one at a time, rebuilds only the test binary of the mutated
# module (ffd/ -> ffd_tests, widgets/ -> widgets_tests, geometry/src/<topic>/ ->
# geometry_<topic>_tests, geometry/src/*.cpp -> geometry_core_tests), runs it with a timeout and
# counts the mutant as caught when a test fails, crashes or times out. Mutants that do not
# compile are replaced by the next draw (they say nothing about the tests).
#
# The mutations are applied to a copy of the tracked (and new, unignored) files under
# --work (default build-mutation/tree), built in <work>/build with the app off; the working tree
# itself is never modified. Each mutated file is restored right after its run, and on exit,
# Ctrl-C or SIGTERM (a try/finally plus signal handlers).
#
# Prints one line per mutant, the survivors with their diffs, and "caught X of Y (Z %)".
# Exit status 0 when the baseline passes (the score is a report, not a gate); 2 on a bad
# argument or a failing baseline. --list prints the drawn mutants without building anything.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if ! command -v python3 >/dev/null 2>&1; then
  echo "mutation-smoke: python3 is needed (scripts/setup-deps.sh installs it)" >&2
  exit 2
fi
exec python3 "$root/scripts/mutation_smoke.py" --root "$root" "$@"
