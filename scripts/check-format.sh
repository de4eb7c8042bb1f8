#!/usr/bin/env bash
# Checks the C++ sources against the checked-in .clang-format (issue 16): every tracked .cpp/.h
# under src/, apps/, modules/, tests/, bench/, include/, python/ and examples/ must be formatted. Run by
# scripts/test.sh; run `clang-format -i FILE` to fix a file. Files go to clang-format forty at a
# time, one batch per core (a process per file cost a minute: clang-format's start-up, 600 times).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null; then
  echo "check-format: clang-format is not installed (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
files=$(git ls-files '*.cpp' '*.h' | grep -E '^(src|apps|modules|tests|bench|include|python|examples)/')
checked=$(printf '%s\n' "$files" | wc -l)
# --dry-run --Werror reports "FILE:LINE:COL: error: code should be clang-formatted" per difference
# and exits non-zero; any other failure (a file that cannot be read) fails the check too.
report=$(printf '%s\n' "$files" | xargs -d '\n' -P "$(nproc)" -n 40 clang-format --dry-run --Werror 2>&1) \
  && status=0 || status=$?
bad=$(printf '%s\n' "$report" | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)
if [ -n "$bad" ]; then
  while IFS= read -r f; do echo "check-format: $f is not formatted (clang-format -i $f)" >&2; done <<< "$bad"
  exit 1
fi
if [ "$status" -ne 0 ]; then
  printf '%s\n' "$report" >&2
  echo "check-format: clang-format failed (exit $status)" >&2
  exit 1
fi
echo "check-format: $checked files formatted"
