#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""SPDX license lines in the project's own source files.

    tools/spdx.py --check [PATH...]   list files without the line, exit 1 if any
    tools/spdx.py --fix [PATH...]     insert it as the first line (after a shebang,
                                      an HTML doctype or a Python coding line)

Without PATH: every file `git ls-files` lists. Which files get the line is a
rule on the file's type, never a list of names, so new files are covered:

  C/C++ (.cpp .hpp .h .c .cc), JavaScript (.js .mjs)   // SPDX-...
  CSS (.css)                                           /* SPDX-... */
  HTML (.html)                                         <!-- SPDX-... -->
  Python, shell, CMake (.py .sh .bash .cmake, CMakeLists.txt,
  any file starting with #!), systemd units (.service) # SPDX-...
  man pages (.1 .. .8)                                 .\\" SPDX-...

Everything else is left alone: data (RINEX, almanacs, receiver logs, meshes,
fuzz corpora and dictionaries), golden outputs (.nmea .ubx .csv .txt), JSON,
TOML configurations, Markdown, images, license texts, and generated tables
(.inc). Third-party files keep their own terms: their provenance is in the
README.md of the folder that holds them (tools/provenance.py checks it).
"""

import os
import re
import subprocess
import sys

LICENSE = 'Apache-2.0'
TAG = 'SPDX-License-Identifier: ' + LICENSE
HEAD_LINES = 5  # the line must be within the first lines of the file

SLASH = ('// ', '')
HASH = ('# ', '')
BY_SUFFIX = {
    '.cpp': SLASH, '.hpp': SLASH, '.h': SLASH, '.c': SLASH, '.cc': SLASH,
    '.js': SLASH, '.mjs': SLASH,
    '.css': ('/* ', ' */'),
    '.html': ('<!-- ', ' -->'),
    '.py': HASH, '.sh': HASH, '.bash': HASH, '.cmake': HASH, '.service': HASH,
}
MAN_PAGE = re.compile(r'\.[1-8]$')
CODING = re.compile(rb'^#.*coding[:=]')


def comment_style(path, first_line):
    """(prefix, suffix) of a comment line for PATH, or None: no header wanted."""
    name = os.path.basename(path)
    suffix = os.path.splitext(name)[1]
    if name == 'CMakeLists.txt':
        return HASH
    if suffix in BY_SUFFIX:
        return BY_SUFFIX[suffix]
    if MAN_PAGE.search(name):
        return ('.\\" ', '')
    if first_line.startswith(b'#!'):
        return HASH
    return None


def read_head(path):
    with open(path, 'rb') as fh:
        return fh.read()


def has_tag(data):
    head = data.split(b'\n', HEAD_LINES)[:HEAD_LINES]
    return any(TAG.encode() in line for line in head)


def insert_at(lines):
    """Index of the line the header goes before: after a shebang, an HTML
    doctype, and a Python coding line that must stay in the first two lines."""
    i = 0
    if lines and (lines[0].startswith(b'#!') or lines[0].lower().startswith(b'<!doctype')):
        i = 1
    if len(lines) > i and CODING.match(lines[i]):
        i += 1
    return i


def tracked_files(root):
    out = subprocess.run(['git', '-C', root, 'ls-files', '-z'], check=True, capture_output=True).stdout
    return [os.path.join(root, p) for p in out.decode().split('\0') if p]


def wanted(path):
    """(data, style) for a file that must carry the line, else None."""
    if not os.path.isfile(path) or os.path.islink(path):
        return None
    data = read_head(path)
    style = comment_style(path, data.split(b'\n', 1)[0])
    return (data, style) if style else None


def main(argv):
    if len(argv) < 2 or argv[1] not in ('--check', '--fix'):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    try:
        root = subprocess.run(['git', 'rev-parse', '--show-toplevel'], check=True, capture_output=True,
                              cwd=here).stdout.decode().strip()
    except (OSError, subprocess.CalledProcessError):
        root = ''
    if os.path.realpath(root or '/nonexistent') != os.path.realpath(here):
        if not argv[2:]:
            print(f'spdx: {here} is not a git checkout, so there is no list of tracked files: skipped')
            return 77
        root = here
    paths = argv[2:] or tracked_files(root)
    missing = []
    checked = 0
    for path in paths:
        w = wanted(path)
        if w is None:
            continue
        data, (prefix, suffix) = w
        checked += 1
        if has_tag(data):
            continue
        missing.append(os.path.relpath(path, root))
        if argv[1] == '--fix':
            lines = data.split(b'\n')
            lines.insert(insert_at(lines), (prefix + TAG + suffix).encode())
            with open(path, 'wb') as fh:
                fh.write(b'\n'.join(lines))
    if argv[1] == '--check':
        for p in missing:
            print(f'{p}: no "{TAG}" line in its first {HEAD_LINES} lines (tools/spdx.py --fix adds it)')
        print(f'spdx: {checked} source files, {len(missing)} without the line')
        return 1 if missing else 0
    print(f'spdx: {checked} source files, {len(missing)} fixed')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
