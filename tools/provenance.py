#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Every file in the folders that hold files we did not write has a row in
that folder's README.md saying where it came from:

    | file | source | license | changes |
    |---|---|---|---|
    | `nav/brdc0010.22n` | gps-sdr-sim @ `28ca29a6…` : `brdc0010.22n` | MIT (`LICENSES/gps-sdr-sim-LICENSE.txt`) | none |
    | `scenes/empty.obj` | gnssemu | Apache-2.0 | written for the tests |

The first cell is the file's path from the folder (in backticks); a row whose
source is not gnssemu names its license text, a file under the folder. The
folders are ROOTS below; README.md files and license texts (LICENSES/) need
no row.

    tools/provenance.py --check    exit 1 on a file without a row, a row
                                   without a file, a third-party row without
                                   its license text, or a share-alike license
    tools/provenance.py --list     every third-party row: folder, file, license

Files are those git tracks (every file when the tree is not a git checkout).
"""

import os
import re
import subprocess
import sys

ROOTS = ['tests/data', 'config/nav', 'web', 'tests/fuzz/corpus', 'tests/fuzz/regressions']
OURS = 'gnssemu'
# Nothing share-alike inside the project: such data is read from ../shared/data instead.
SHARE_ALIKE = re.compile(r'\b(A?GPL|LGPL|CC[- ]BY[- ]SA|ODbL|EUPL|OSL)\b', re.IGNORECASE)
LICENSES = ('Apache-2.0', 'MIT', 'BSD-2-Clause', 'BSD-3-Clause', 'MPL-2.0', 'CC-BY-4.0', 'CC0-1.0')
ROW = re.compile(r'^\|\s*`([^`]+)`\s*\|(.*)\|\s*$')


def repo_root():
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def git_checkout(root):
    """True when ROOT is the top of a git work tree (not a folder inside another one)."""
    try:
        top = subprocess.run(['git', '-C', root, 'rev-parse', '--show-toplevel'], check=True,
                             capture_output=True).stdout.decode().strip()
    except (OSError, subprocess.CalledProcessError):
        return False
    return os.path.realpath(top) == os.path.realpath(root)


def files_under(root, folder):
    """Paths relative to FOLDER of the files in it (tracked, if git knows them)."""
    top = os.path.join(root, folder)
    if git_checkout(root):
        out = subprocess.run(['git', '-C', root, 'ls-files', '-z', '--', folder], check=True,
                             capture_output=True).stdout.decode()
        paths = [os.path.relpath(os.path.join(root, p), top) for p in out.split('\0') if p]
    else:
        paths = [os.path.relpath(os.path.join(d, f), top) for d, _, fs in os.walk(top) for f in fs]
    return sorted(p for p in paths if not exempt(p))


def exempt(path):
    parts = path.split(os.sep)
    return parts[-1] == 'README.md' or 'LICENSES' in parts[:-1] or parts[-1].startswith('LICENSE')


def rows_of(readme):
    """{file: (line number, cells after the first)} of the README's table rows."""
    rows = {}
    with open(readme, encoding='utf-8') as fh:
        for n, line in enumerate(fh, 1):
            m = ROW.match(line.strip())
            if m:
                rows[m.group(1)] = (n, [c.strip() for c in m.group(2).split('|')])
    return rows


def check_folder(root, folder, third_party):
    errors = []
    readme = os.path.join(root, folder, 'README.md')
    if not os.path.isfile(readme):
        return [f'{folder}/README.md: missing (a provenance row for every file of {folder}/)']
    rows = rows_of(readme)
    present = files_under(root, folder)
    where = f'{folder}/README.md'
    for p in present:
        if p not in rows:
            errors.append(f'{folder}/{p}: no provenance row in {where} (source, license, changes)')
    for f, (n, cells) in rows.items():
        if f not in present:
            errors.append(f'{where}:{n}: row for `{f}`, which is not a file of {folder}/')
            continue
        if len(cells) < 3:
            errors.append(f'{where}:{n}: `{f}`: needs source, license and changes cells')
            continue
        source, license_cell = cells[0], cells[1]
        if SHARE_ALIKE.search(license_cell):
            errors.append(f'{where}:{n}: `{f}` is under a share-alike license ({license_cell}): '
                          'keep it out of the project (read it from ../shared/data)')
        if not any(lic in license_cell for lic in LICENSES):
            errors.append(f'{where}:{n}: `{f}`: no known license id in "{license_cell}" ({", ".join(LICENSES)})')
        if source == OURS:
            continue
        texts = re.findall(r'`([^`]+)`', license_cell)
        if not texts:
            errors.append(f'{where}:{n}: `{f}` is third-party: name its license text in the license cell')
        for t in texts:
            if not os.path.isfile(os.path.join(root, folder, t)):
                errors.append(f'{where}:{n}: `{f}`: license text {t} not found beside it')
        third_party.append((folder, f, license_cell, source))
    return errors


def main(argv):
    if len(argv) != 2 or argv[1] not in ('--check', '--list'):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    root = repo_root()
    errors, third_party = [], []
    for folder in ROOTS:
        errors += check_folder(root, folder, third_party)
    if argv[1] == '--list':
        for folder, f, lic, source in third_party:
            print(f'{folder}/{f}\t{lic}\t{source}')
        return 0
    for e in errors:
        print(e)
    count = sum(len(files_under(root, f)) for f in ROOTS)
    print(f'provenance: {count} files in {", ".join(ROOTS)}; {len(third_party)} third-party; {len(errors)} problems')
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
