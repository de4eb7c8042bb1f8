#!/usr/bin/env bash
# Checks the C++ sources against the checked-in .clang-format (issue 16): every tracked .cpp/.h
# under src/, apps/, tests/, bench/, include/, python/ and examples/ must be formatted. Run by
# scripts/test.sh; run `clang-format -i FILE` to fix a file.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null; then
  echo "check-format: clang-format is not installed (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
bad=0
checked=0
while IFS= read -r f; do
  checked=$((checked + 1))
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "check-format: $f is not formatted (clang-format -i $f)" >&2
    bad=$((bad + 1))
  fi
done < <(git ls-files '*.cpp' '*.h' | grep -E '^(src|apps|tests|bench|include|python|examples)/')
if [ "$bad" -ne 0 ]; then exit 1; fi
echo "check-format: $checked files formatted"
