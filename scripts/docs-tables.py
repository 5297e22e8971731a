#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Rewrites the documents' generated tables (README.md and docs/*.md) from
# the scripts that measure them, so that a change of figures is a run of
# this script, never a hand edit. Each table sits, once in all the
# documents, between "<!-- generated: NAME by SCRIPT -->" and
# "<!-- end generated: NAME -->".
#
#   scripts/docs-tables.py [--check] [NAME ...]
#
# NAMEs: compact (scripts/compact-table.sh: sizes, errors, load times of the
# test rigs in build/release), examples (scripts/example-lines.sh), tests
# (scripts/test-counts.sh: ctest counts of the presets scripts/test.sh
# builds). Default: those three. --check writes nothing and fails, naming the table,
# when a document differs from what the scripts print now (CI checks
# `examples`, whose figures depend only on the sources). bench
# (scripts/bench.sh 5), paths (scripts/bench-paths.sh 5) and bakes
# (scripts/bench-bake.py: Pip at 256-4096 px, a 90,000-vertex mesh) and
# animator (scripts/bench-animator.sh 5: the update beside the frame) and web
# (scripts/bench-web.sh 7: WebAssembly in Chromium against native) run the
# benchmarks: minutes each, on a quiet machine, so they are never in the
# default set; name them.
import glob
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
    'bakes': ['scripts/bench-bake.py', 'build/release'],
    'animator': ['scripts/bench-animator.sh', '5'],
    'web': ['scripts/bench-web.sh', '7'],
}


def main(argv):
    check = '--check' in argv
    names = [a for a in argv if a != '--check'] or ['compact', 'examples', 'tests']
    for name in names:
        if name not in TABLES:
            sys.exit(f'scripts/docs-tables.py: unknown table "{name}" (known: {", ".join(TABLES)})')
    paths = [os.path.join(ROOT, 'README.md')] + sorted(glob.glob(os.path.join(ROOT, 'docs', '*.md')))
    texts = {}
    for path in paths:
        with open(path, encoding='utf-8') as f:
            texts[path] = f.read()
    failed, changed = [], set()
    for name in names:
        command = TABLES[name]
        pattern = re.compile(r'(<!-- generated: %s by [^>]*-->\n)(.*?)(<!-- end generated: %s -->)' %
                             (re.escape(name), re.escape(name)), re.S)
        holders = [p for p in paths if pattern.search(texts[p])]
        if len(holders) != 1 or len(pattern.findall(texts[holders[0]])) != 1:
            where = ', '.join(os.path.relpath(p, ROOT) for p in holders) or 'none'
            sys.exit(f'scripts/docs-tables.py: expected one block "<!-- generated: {name} by ... -->" '
                     f'in README.md and docs/*.md, found it in: {where}')
        path = holders[0]
        rel = os.path.relpath(path, ROOT)
        run = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f'scripts/docs-tables.py: {" ".join(command)} failed (exit {run.returncode}); '
                     f'{rel} unchanged:\n{run.stderr[-2000:]}')
        table = run.stdout
        if pattern.search(texts[path]).group(2) != table:
            failed.append(f'{name} ({rel})')
            changed.add(path)
            texts[path] = pattern.sub(lambda m: m.group(1) + table + m.group(3), texts[path])
    if check:
        if failed:
            sys.exit('the generated table(s) ' + ', '.join(failed) +
                     ' differ from what their scripts print; run scripts/docs-tables.py ' +
                     ' '.join(f.split(' ')[0] for f in failed))
        return
    for path in changed:
        with open(path + '.tmp', 'w', encoding='utf-8') as f:
            f.write(texts[path])
        os.replace(path + '.tmp', path)
    print(', '.join(failed) + ' rewritten' if failed else 'the generated tables are already up to date')

if __name__ == '__main__':
    main(sys.argv[1:])
