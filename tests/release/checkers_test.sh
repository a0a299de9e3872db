#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The release checkers catch what they are for, on small trees of their own:
# tools/spdx.py (a source file without its SPDX line; --fix puts it first, or
# after a shebang / doctype, and leaves data alone) and tools/provenance.py
# (a file without a provenance row, a row without a file, a third-party row
# without its license text, a share-alike license).
# Usage: checkers_test.sh SOURCE_DIR
set -euo pipefail
src="$1"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
expect() {  # NAME WANTED_STATUS WANTED_OUTPUT_REGEX COMMAND...
  local name="$1" want="$2" re="$3"; shift 3
  local out rc=0
  out=$("$@" 2>&1) || rc=$?
  if [ "$rc" -eq "$want" ] && grep -Eq -- "$re" <<<"$out"; then echo "ok   $name"; else
    echo "FAIL $name: exit $rc (wanted $want), output:"; echo "$out"; fail=1; fi
}

# spdx.py in a git repository of its own.
t="$tmp/spdx"
mkdir -p "$t/tools" "$t/web" "$t/data"
grep -v "^# SPDX-License-Identifier" "$src/tools/spdx.py" > "$t/tools/spdx.py"  # counted like any new script
printf '#pragma once\nint f();\n' > "$t/a.hpp"
printf '#!/usr/bin/env python3\n"""doc"""\n' > "$t/tools/b.py"
printf '<!DOCTYPE html>\n<html></html>\n' > "$t/web/c.html"
printf 'body {}\n' > "$t/web/d.css"
printf 'add_library(x a.cpp)\n' > "$t/CMakeLists.txt"
printf '$GPGGA,1*00\n' > "$t/data/e.nmea"
printf '{"a": 1}\n' > "$t/data/f.json"
git -C "$t" init -q && git -C "$t" add -A
expect "spdx --check lists the files without the line" 1 "^tools/b.py: no " python3 "$t/tools/spdx.py" --check
expect "spdx --check counts them" 1 "6 source files, 6 without" python3 "$t/tools/spdx.py" --check
expect "spdx --fix" 0 "6 fixed" python3 "$t/tools/spdx.py" --fix
expect "spdx --check after --fix" 0 "6 source files, 0 without" python3 "$t/tools/spdx.py" --check
expect "C++ header: first line" 0 "^// SPDX-License-Identifier: Apache-2.0$" head -1 "$t/a.hpp"
expect "script: shebang stays first" 0 "^#!/usr/bin/env python3 # SPDX-License-Identifier: Apache-2.0 \"\"\"doc\"\"\"$" bash -c "head -3 '$t/tools/b.py' | tr '\n' ' ' | sed 's/ $//'"
expect "HTML: after the doctype" 0 "^<!-- SPDX-License-Identifier: Apache-2.0 -->$" sed -n 2p "$t/web/c.html"
expect "CSS" 0 "^/\* SPDX-License-Identifier: Apache-2.0 \*/$" head -1 "$t/web/d.css"
expect "data is left alone" 0 "^\\\$GPGGA,1\*00 \{\"a\": 1\}$" bash -c "cat '$t/data/e.nmea' '$t/data/f.json' | tr '\n' ' ' | sed 's/ $//'"
expect "spdx --fix twice changes nothing" 0 "0 fixed" python3 "$t/tools/spdx.py" --fix

# provenance.py on a tree that is not a git checkout (every file counts).
p="$tmp/prov"
mkdir -p "$p/tools" "$p/tests/data/LICENSES" "$p/config/nav" "$p/web" "$p/tests/fuzz/corpus" "$p/tests/fuzz/regressions"
cp "$src/tools/provenance.py" "$p/tools/"
for d in config/nav web tests/fuzz/corpus tests/fuzz/regressions; do
  printf '| file | source | license | changes |\n|---|---|---|---|\n' > "$p/$d/README.md"
done
echo x > "$p/tests/data/ours.txt"
echo y > "$p/tests/data/theirs.log"
echo "MIT text" > "$p/tests/data/LICENSES/mit.txt"
readme="$p/tests/data/README.md"
printf '| file | source | license | changes |\n|---|---|---|---|\n| `ours.txt` | gnssemu | Apache-2.0 | written for the tests |\n| `theirs.log` | someone @ `abc` : `x.log` | MIT (`LICENSES/mit.txt`) | none |\n' > "$readme"
expect "provenance: every file has a row" 0 "1 third-party; 0 problems" python3 "$p/tools/provenance.py" --check
echo z > "$p/web/new.js"
expect "provenance: a file without a row" 1 "web/new.js: no provenance row" python3 "$p/tools/provenance.py" --check
rm "$p/web/new.js"
sed -i 's|LICENSES/mit.txt|LICENSES/missing.txt|' "$readme"
expect "provenance: a license text that is not there" 1 "license text LICENSES/missing.txt not found" python3 "$p/tools/provenance.py" --check
sed -i 's|MIT (`LICENSES/missing.txt`)|CC-BY-SA-4.0 (`LICENSES/mit.txt`)|' "$readme"
expect "provenance: a share-alike license" 1 "share-alike license" python3 "$p/tools/provenance.py" --check
sed -i 's|CC-BY-SA-4.0|MIT|' "$readme"
rm "$p/tests/data/ours.txt"
expect "provenance: a row without its file" 1 "row for .ours.txt., which is not a file" python3 "$p/tools/provenance.py" --check

[ $fail -eq 0 ] && echo "1 passed, 0 failed" || echo "0 passed, 1 failed"
exit $fail
