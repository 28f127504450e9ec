#!/usr/bin/python3
"""Checks the include order between the folders of src/ (docs/architecture.md).

Usage: check_layers.py PROJECT_DIR      checks the project; exit status 1 on any violation
       check_layers.py --self-test      runs the checker on made-up trees that break each rule

The order is read from src/layers.txt: one folder per line, lowest first; a file of src/ may
include headers of its own folder and of folders listed before it, never of one listed after.
`private FOLDER/HEADER` lines name headers that only files of their own folder may include.
`public HEADER FOLDER` lines name the folder that implements each public header of
include/plantarch/ (for a header of types only, the lowest folder that owns them): a file of
src/ may include a public header only from that folder or above it, and a public header may
include another only when that one's folder is not above its own, so a call never goes up
through the public API either. Every public header is mapped.
Front ends (apps/, builder/, examples/, python/) include the public headers and their own
headers only (and the builder's server.h, which the command line starts); tests/, bench/ and fuzz/ may include internal headers, but no private one. docs/architecture.md must describe
every folder in a heading of its own ("### `src/FOLDER/`"), in the order of src/layers.txt.

Each violation is printed as one line: file:line: what is wrong.
"""

import os
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')
SOURCE_SUFFIXES = ('.h', '.hpp', '.cpp', '.cc', '.inc', '.in')
FRONT_ENDS = ('apps', 'builder', 'examples', 'python')
# Headers one front end includes from another: the builder's server, which the command line
# starts (plantarch builder).
ENTRY_HEADERS = ('builder/server/server.h',)
INTERNAL_USERS = ('tests', 'bench', 'fuzz')
DOC_HEADING = re.compile(r'^###\s+`src/([A-Za-z0-9_]+)/`')


def read_layers(root, problems):
    """The folders in order, the private headers and the public headers' folders, from
    src/layers.txt."""
    path = os.path.join(root, 'src', 'layers.txt')
    order, private, public = [], set(), {}
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
        elif words[0] == 'public' and len(words) == 3 and '/' not in words[1]:
            if words[1] in public:
                problems.append(f'src/layers.txt:{number}: public header "{words[1]}" '
                                f'mapped twice')
            public[words[1]] = (words[2], number)
        elif len(words) == 1 and '/' not in words[0]:
            if words[0] in order:
                problems.append(f'src/layers.txt:{number}: folder "{words[0]}" listed twice')
            order.append(words[0])
        else:
            problems.append(f'src/layers.txt:{number}: expected a folder name, '
                            f'"private FOLDER/HEADER" or "public HEADER FOLDER", '
                            f'found "{line.strip()}"')
    return order, private, public


def source_files(top):
    for directory, dirs, files in os.walk(top):
        dirs.sort()
        for name in sorted(files):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.join(directory, name)


def includes(path, quoted_only=False):
    """(line number, included name) of every #include of a file (or of its "..." ones)."""
    with open(path, encoding='utf-8', errors='replace') as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m and not (quoted_only and m.group(1) == '<'):
                yield number, m.group(2)


PUBLIC = 'plantarch/'


def public_header(name):
    """The public header an include names ("Context.h" for "plantarch/Context.h"), or None."""
    if name.startswith(PUBLIC) and '/' not in name[len(PUBLIC):]:
        return name[len(PUBLIC):]
    return None


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


def foreign_header(root, top, path, name):
    """Where a front end's quoted include lands outside its own folder `top` (relative to the
    including file, from the project's root, or through another front end's folder, which
    the build puts on the include path), or None: its own header or a generated one."""
    inside = os.path.join(root, top) + os.sep
    here = os.path.normpath(os.path.join(os.path.dirname(path), name))
    if here.startswith(inside) and os.path.isfile(here):
        return None
    for base in ('',) + FRONT_ENDS:
        candidate = os.path.normpath(os.path.join(root, base, name))
        if os.path.isfile(candidate):
            return None if candidate.startswith(inside) else os.path.relpath(candidate, root)
    return None


def check_tree(root):
    """Every violation in the project at `root`, as printable lines."""
    problems = []
    order, private, public = read_layers(root, problems)
    rank = {folder: i for i, folder in enumerate(order)}
    headers = os.path.join(root, 'include', 'plantarch')
    present = sorted(n for n in os.listdir(headers) if n.endswith('.h')) \
        if os.path.isdir(headers) else []
    for name in present:
        if name not in public:
            problems.append(f'include/plantarch/{name}: not mapped to the folder that '
                            f'implements it (add "public {name} FOLDER" to src/layers.txt)')
    for name, (folder, number) in sorted(public.items()):
        if name not in present:
            problems.append(f'src/layers.txt:{number}: public header "{name}" does not exist')
        elif folder not in rank:
            problems.append(f'src/layers.txt:{number}: public header "{name}" mapped to '
                            f'"{folder}", which is not a layer')

    def layer_of(name):
        entry = public.get(name)
        return entry[0] if entry and entry[0] in rank else None
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
                header = public_header(name)
                to = layer_of(header) if header else None
                if to and folder in rank and rank[to] > rank[folder]:
                    report(path, number, name,
                           f'{folder} may not include {name}, which src/{to}/ implements '
                           f'above it (order: {" < ".join(order)})')
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
    for name in present:
        own = layer_of(name)
        if own is None:
            continue
        path = os.path.join(headers, name)
        for number, included in includes(path):
            other = public_header(included)
            to = layer_of(other) if other else None
            if to and rank[to] > rank[own]:
                report(path, number, included,
                       f'{name} (src/{own}/) may not include {included}, which src/{to}/ '
                       f'implements above it')
    for top in FRONT_ENDS + INTERNAL_USERS:
        for path in source_files(os.path.join(root, top)):
            for number, name in includes(path, quoted_only=top in FRONT_ENDS):
                target = target_of(root, path, name, folders)
                foreign = None if target or public_header(name) or top not in FRONT_ENDS \
                    or name in ENTRY_HEADERS else foreign_header(root, top, path, name)
                if foreign:
                    report(path, number, name, f'{top}/ includes the public API and its own '
                           f'headers only, not {foreign}')
                    continue
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
        layers = ('# lowest first\nbase\nmiddle\ntop\nprivate top/hub.h\n'
                  'public Types.h base\npublic Api.h top\n')
        write(root, 'src/layers.txt', layers)
        write(root, 'include/plantarch/Types.h', '#pragma once\n')
        write(root, 'include/plantarch/Api.h', '#include "plantarch/Types.h"\n')
        write(root, 'builder/server/routes.cpp', '#include "routes.h"\n#include "gen.h"\n'
              '#include "builder/server/routes.h"\n#include "plantarch/Api.h"\n')
        write(root, 'builder/server/routes.h', '#pragma once\n#include <string>\n')
        write(root, 'apps/cli.h', '#pragma once\n')
        write(root, 'src/base/util.h', '#pragma once\n')
        write(root, 'src/middle/part.h', '#include "base/util.h"\n#include <vector>\n')
        write(root, 'src/middle/part.cpp', '#include "part.h"\n#include "plantarch/Types.h"\n')
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
            ('src/middle/part.cpp', '#include "part.h"\n#include "plantarch/Api.h"\n',
             'src/middle/part.cpp:2: #include "plantarch/Api.h": middle may not include '
             'plantarch/Api.h, which src/top/ implements above it'),
            ('include/plantarch/Types.h', '#pragma once\n#include "plantarch/Api.h"\n',
             'include/plantarch/Types.h:2: #include "plantarch/Api.h": Types.h (src/base/) may '
             'not include plantarch/Api.h'),
            ('include/plantarch/New.h', '#pragma once\n',
             'include/plantarch/New.h: not mapped to the folder that implements it'),
            ('builder/server/routes.cpp', '#include "routes.h"\n#include "cli.h"\n',
             'builder/server/routes.cpp:2: #include "cli.h": builder/ includes the public API '
             'and its own headers only, not apps/cli.h'),
            ('src/layers.txt', layers + 'public Gone.h base\n',
             'src/layers.txt:8: public header "Gone.h" does not exist'),
            ('src/layers.txt', layers + 'private top/gone.h\n',
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
                if not os.listdir(os.path.dirname(path)):
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
