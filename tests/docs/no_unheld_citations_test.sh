#!/usr/bin/env bash
# Fails when a tracked file cites a document the repository does not hold ("seed 00N l.NNNN",
# "spec §N", "Spec 00N": cite "Kuriyama 1996, sec. 6.3.2" and list the work in docs/references.md) or
# carries a work log (round numbers, times of day, machine load): the history of how a number
# was reached lives in git; measured numbers come from scripts/bench.sh.
#   tests/docs/no_unheld_citations_test.sh [REPOSITORY]
# Exit 0: clean; 1: offending lines listed; 77 (skipped): not a git checkout.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="${1:-$(cd "$here/../.." && pwd)}"
self="tests/docs/no_unheld_citations_test.sh"

# Prints the offending lines of the tracked text files of repository $1; returns 1 if any.
offending() {
  local hits
  hits="$(git -C "$1" grep -I -n -E -e '[Ss]eeds? 00' -e '[Ss]pec §' -e '[Ss]pec 00[0-4]' -e '[Ss]ession[ -][0-9]' -e 'UTC' -e 'load ~?[0-9]' -e 'load average (of |about |~)?[0-9]' \
    -- . ':(exclude)docs/references.md' ":(exclude)$self" || true)"
  if [ -n "$hits" ]; then
    printf '%s\n' "$hits"
    return 1
  fi
}

if ! git -C "$repo" rev-parse --git-dir >/dev/null 2>&1; then
  echo "not a git checkout: $repo (skipped)"
  exit 77
fi

# The check itself must see each kind of line, and pass a clean tree.
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
git -C "$scratch" init -q
printf 'x = 1;  // Kuriyama 1996, sec. 6.3.2, eq. (6.1)\n' >"$scratch/clean.cpp"
git -C "$scratch" add clean.cpp
if ! offending "$scratch" >/dev/null; then
  echo "self-test: a clean tree was reported" >&2
  exit 1
fi
for line in '// seed 001 l.2258' 'Seed 003 Ex. 1' '// see spec §4.3' '// Spec 003 §5.3' 'measured in session 8' 'the session-7 campaign' 'at 22:25 UTC' 'load 1.3-1.4' 'at load ~1.3' '(load average 9 on 2 cores)'; do
  printf '%s\n' "$line" >"$scratch/dirty.md"
  git -C "$scratch" add dirty.md
  if offending "$scratch" >/dev/null; then
    echo "self-test: '$line' was not reported" >&2
    exit 1
  fi
done

if ! offending "$repo"; then
  echo "The lines above cite documents the repository does not hold, or carry a work log." >&2
  echo "Cite papers as 'Kuriyama 1996, sec. 6.3.2, eq. (6.1)' (docs/references.md); leave" >&2
  echo "measurement history to git and numbers to scripts/bench.sh (docs/benchmarks.md)." >&2
  exit 1
fi
echo "no unheld citations or work logs in $(git -C "$repo" ls-files | wc -l) tracked files"
