#!/usr/bin/env bash
# Rewrites the tables docs/ generates from the declarations (planner parameters, mission types)
# with what the built binary prints: run after changing a declaration (tests/cli_test.sh fails
# until the docs agree). Usage: scripts/update-doc-tables.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${1:-build}/uavplan"
replace() {  # FILE MARKER COMMAND...
  local file=$1 marker=$2
  shift 2
  local table
  table=$("$@")
  python3 - "$file" "$marker" "$table" <<'PY'
import sys
path, marker, table = sys.argv[1:]
text = open(path).read()
begin = text.index("<!-- %s: begin" % marker)
begin = text.index("\n", begin) + 1
end = text.index("<!-- %s: end" % marker)
open(path, "w").write(text[:begin] + table + "\n" + text[end:])
PY
}
replace docs/planners.md planner-params "$bin" info --planners --markdown
replace docs/formats.md mission-types "$bin" info --missions --markdown
