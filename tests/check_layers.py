#!/usr/bin/python3
"""Checks the include order between the folders of src/ (docs/architecture.md).

Usage: check_layers.py PROJECT_DIR      checks the project; exit status 1 on any violation
       check_layers.py --self-test      runs the checker on made-up trees that break each rule

The order is read from src/layers.txt: one folder per line, lowest first; a file of src/ may
include headers of its own folder and of folders listed before it, never of one listed after.
`private FOLDER/HEADER` lines name headers that only files of their own folder may include.
Front ends (apps/, examples/, python/) include the public headers only; tests/, bench/ and
fuzz/ may include internal headers, but no private one. docs/architecture.md must describe
every folder in a heading of its own ("### `src/FOLDER/`"), in the order of src/layers.txt.

Each violation is printed as one line: file:line: what is wrong.
"""

import os
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]')
SOURCE_SUFFIXES = ('.h', '.hpp', '.cpp', '.cc', '.inc', '.in')
FRONT_ENDS = ('apps', 'examples', 'python')
INTERNAL_USERS = ('tests', 'bench', 'fuzz')
DOC_HEADING = re.compile(r'^###\s+`src/([A-Za-z0-9_]+)/`')


def read_layers(root, problems):
    """The folders in order and the private headers, from src/layers.txt."""
    path = os.path.join(root, 'src', 'layers.txt')
    order, private = [], set()
    try:
        lines = open(path, encoding='utf-8').read().splitlines()
    except OSError as e:
        problems.append(f'src/layers.txt: cannot read: {e.strerror}')
        return order, private
    for number, line in enumerate(lines, 1):
        words = line.split('#', 1)[0].split()
        if not words:
            continue
        if words[0] == 'private' and len(words) == 2 and '/' in words[1]:
            private.add(words[1])
        elif len(words) == 1 and '/' not in words[0]:
            if words[0] in order:
                problems.append(f'src/layers.txt:{number}: folder "{words[0]}" listed twice')
            order.append(words[0])
        else:
            problems.append(f'src/layers.txt:{number}: expected a folder name or '
                            f'"private FOLDER/HEADER", found "{line.strip()}"')
    return order, private


def source_files(top):
    for directory, dirs, files in os.walk(top):
        dirs.sort()
        for name in sorted(files):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.join(directory, name)


def includes(path):
    """(line number, included name) of every #include of a file."""
    with open(path, encoding='utf-8', errors='replace') as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                yield number, m.group(1)


def target_of(root, path, name, folders):
    """The src/ header an include names, as FOLDER/REST (None: public or third-party)."""
    first = name.split('/', 1)[0]
    if first in folders and '/' in name:
        return os.path.normpath(name)
    # A name relative to the including file (e.g. "../model/plant_store.h" or "tube.h").
    candidate = os.path.normpath(os.path.join(os.path.dirname(path), name))
    src = os.path.join(root, 'src')
    if os.path.isfile(candidate) and candidate.startswith(src + os.sep):
        return os.path.relpath(candidate, src)
    return None


def check_tree(root):
    """Every violation in the project at `root`, as printable lines."""
    problems = []
    order, private = read_layers(root, problems)
    rank = {folder: i for i, folder in enumerate(order)}
    src = os.path.join(root, 'src')
    folders = sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
    for folder in folders:
        if folder not in rank:
            problems.append(f'src/{folder}/: folder not listed in src/layers.txt '
                            f'(add it where it belongs: {" < ".join(order)})')
    for folder in order:
        if folder not in folders:
            problems.append(f'src/layers.txt: lists "{folder}", which is not a folder of src/')
    for header in sorted(private):
        if not os.path.isfile(os.path.join(src, header)):
            problems.append(f'src/layers.txt: private header "{header}" does not exist')

    def report(path, number, name, why):
        problems.append(f'{os.path.relpath(path, root)}:{number}: #include "{name}": {why}')

    for folder in folders:
        for path in source_files(os.path.join(src, folder)):
            for number, name in includes(path):
                target = target_of(root, path, name, folders)
                if target is None:
                    continue
                to = target.split(os.sep, 1)[0]
                if to == folder:
                    continue
                if target in private:
                    report(path, number, name, f'{target} is private to src/{to}/')
                elif folder in rank and to in rank and rank[to] > rank[folder]:
                    report(path, number, name,
                           f'{folder} may not include {to}, which is above it '
                           f'(order: {" < ".join(order)})')
    for top in FRONT_ENDS + INTERNAL_USERS:
        for path in source_files(os.path.join(root, top)):
            for number, name in includes(path):
                target = target_of(root, path, name, folders)
                if target is None:
                    continue
                if top in FRONT_ENDS:
                    report(path, number, name,
                           f'{top}/ uses the public API only (include "plantarch/...")')
                elif target in private:
                    report(path, number, name,
                           f'{target} is private to src/{target.split(os.sep, 1)[0]}/')
    check_doc(root, order, problems)
    return problems


def check_doc(root, order, problems):
    """docs/architecture.md has one heading per folder, in the order of src/layers.txt."""
    path = os.path.join(root, 'docs', 'architecture.md')
    try:
        lines = open(path, encoding='utf-8').read().splitlines()
    except OSError as e:
        problems.append(f'docs/architecture.md: cannot read: {e.strerror}')
        return
    described = []
    for number, line in enumerate(lines, 1):
        m = DOC_HEADING.match(line)
        if m:
            described.append((m.group(1), number))
    names = [name for name, _ in described]
    if names != order:
        problems.append(f'docs/architecture.md: folder headings are {" < ".join(names)}; '
                        f'src/layers.txt says {" < ".join(order)}')


# ---- self-test ---------------------------------------------------------------------------


def write(root, relative, text):
    path = os.path.join(root, relative)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


def self_test():
    """Builds a clean tree (no problems), then breaks each rule once and expects its line."""
    failures = []
    with tempfile.TemporaryDirectory() as root:
        write(root, 'src/layers.txt', '# lowest first\nbase\nmiddle\ntop\nprivate top/hub.h\n')
        write(root, 'src/base/util.h', '#pragma once\n')
        write(root, 'src/middle/part.h', '#include "base/util.h"\n#include <vector>\n')
        write(root, 'src/middle/part.cpp', '#include "part.h"\n#include "plantarch/Api.h"\n')
        write(root, 'src/top/hub.h', '#include "middle/part.h"\n')
        write(root, 'src/top/facade.cpp', '#include "hub.h"\n#include "../base/util.h"\n')
        write(root, 'apps/main.cpp', '#include "plantarch/Api.h"\n')
        write(root, 'tests/part_test.cpp', '#include "middle/part.h"\n')
        write(root, 'docs/architecture.md',
              '# Layers\n### `src/base/`\ntext\n### `src/middle/`\n### `src/top/`\n')
        clean = check_tree(root)
        if clean:
            failures.append(f'a clean tree reported: {clean}')
        cases = [
            ('src/base/util.h', '#pragma once\n#include "middle/part.h"\n',
             'src/base/util.h:2: #include "middle/part.h": base may not include middle'),
            ('src/base/util.h', '#include "../top/facade.cpp"\n',
             'src/base/util.h:1: #include "../top/facade.cpp": base may not include top'),
            ('src/middle/part.cpp', '#include "top/hub.h"\n',
             'src/middle/part.cpp:1: #include "top/hub.h": top/hub.h is private to src/top/'),
            ('tests/part_test.cpp', '\n#include "top/hub.h"\n',
             'tests/part_test.cpp:2: #include "top/hub.h": top/hub.h is private to src/top/'),
            ('apps/main.cpp', '#include "middle/part.h"\n',
             'apps/main.cpp:1: #include "middle/part.h": apps/ uses the public API only'),
            ('src/extra/new.h', '#pragma once\n',
             'src/extra/: folder not listed in src/layers.txt'),
            ('docs/architecture.md', '### `src/middle/`\n### `src/base/`\n### `src/top/`\n',
             'docs/architecture.md: folder headings are middle < base < top'),
            ('src/layers.txt', 'base\nmiddle\ntop\nprivate top/gone.h\n',
             'src/layers.txt: private header "top/gone.h" does not exist'),
        ]
        for relative, text, expected in cases:
            path = os.path.join(root, relative)
            old = open(path, encoding='utf-8').read() if os.path.exists(path) else None
            write(root, relative, text)
            found = check_tree(root)
            if len(found) != 1 or not found[0].startswith(expected):
                failures.append(f'breaking {relative}: expected one line starting '
                                f'"{expected}", got {found}')
            if old is None:
                os.remove(path)
                os.rmdir(os.path.dirname(path))
            else:
                write(root, relative, old)
    for f in failures:
        print(f)
    return 1 if failures else 0


def main(argv):
    if argv[1:] == ['--self-test']:
        return self_test()
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    problems = check_tree(os.path.abspath(argv[1]))
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
