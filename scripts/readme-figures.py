#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Rewrites the README's generated tables from the scripts that measure them,
# so that a change of figures is a run of this script, never a hand edit.
# Each table sits between "<!-- generated: NAME by SCRIPT -->" and
# "<!-- end generated: NAME -->".
#
#   scripts/readme-figures.py [--check] [NAME ...]
#
# NAMEs: compact (scripts/compact-table.sh: sizes, errors, load times of the
# test rigs in build/release), examples (scripts/example-lines.sh), tests
# (scripts/test-counts.sh: ctest counts of the presets scripts/test.sh
# builds). Default: those three. --check writes nothing and fails, naming the table,
# when the README differs from what the scripts print now (CI checks
# `examples`, whose figures depend only on the sources). bench
# (scripts/bench.sh 5) and paths (scripts/bench-paths.sh 5) run the
# benchmarks: minutes each, on a quiet machine, so they are never in the
# default set; name them.
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TABLES = {
    'compact': ['scripts/compact-table.sh', 'build/release'],
    'examples': ['scripts/example-lines.sh'],
    'tests': ['scripts/test-counts.sh'],
    # Minutes each, on a quiet machine; never in CI.
    'bench': ['scripts/bench.sh', '5'],
    'paths': ['scripts/bench-paths.sh', '5'],
}


def main(argv):
    check = '--check' in argv
    names = [a for a in argv if a != '--check'] or ['compact', 'examples', 'tests']
    for name in names:
        if name not in TABLES:
            sys.exit(f'scripts/readme-figures.py: unknown table "{name}" (known: {", ".join(TABLES)})')
    path = os.path.join(ROOT, 'README.md')
    with open(path, encoding='utf-8') as f:
        text = f.read()
    failed = []
    for name in names:
        command = TABLES[name]
        pattern = re.compile(r'(<!-- generated: %s by [^>]*-->\n)(.*?)(<!-- end generated: %s -->)' %
                             (re.escape(name), re.escape(name)), re.S)
        if len(pattern.findall(text)) != 1:
            sys.exit(f'scripts/readme-figures.py: README.md: expected one block "<!-- generated: {name} by ... -->"')
        run = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f'scripts/readme-figures.py: {" ".join(command)} failed (exit {run.returncode}); '
                     f'README.md unchanged:\n{run.stderr[-2000:]}')
        table = run.stdout
        current = pattern.search(text).group(2)
        if current != table:
            failed.append(name)
            text = pattern.sub(lambda m: m.group(1) + table + m.group(3), text)
    if check:
        if failed:
            sys.exit('README.md: the generated table(s) ' + ', '.join(failed) +
                     ' differ from what their scripts print; run scripts/readme-figures.py ' + ' '.join(failed))
        return
    with open(path + '.tmp', 'w', encoding='utf-8') as f:
        f.write(text)
    os.replace(path + '.tmp', path)
    print('README.md: ' + (', '.join(failed) + ' rewritten' if failed else 'already up to date'))


if __name__ == '__main__':
    main(sys.argv[1:])
