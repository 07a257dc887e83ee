#!/usr/bin/env python3
"""Every path and section the docs and the code's comments cite exists (J7).

Checked in every tracked text file (docs, README, sources, scripts, CMake):
- a path that starts with one of the repository's top-level folders (`rt_core/src/servo.cpp`,
  `tests/client/`): it exists from the root or from the citing file's folder, or as an include
  path (`shm/events.hpp` is shm/include/hapticctrl/shm/events.hpp), or with an extension added (a
  test binary named after its source), or it ends in `_` or `-` and begins existing names (a
  family: `tests/e2e/run_`). Patterns (`*`, `<...>`, `{...}`, `$VAR`), placeholders (`NAME`),
  build outputs and system includes are not paths of the repository; nor are two words with a
  slash and no extension ("client/raw").
- a Markdown link `[text](target#anchor)`: the target exists and has a heading with that anchor.
- a section cited after a document (`docs/control.md, *Joint space*`, `docs/x.md "Timing"`,
  `README.md's *The first run*`): the document has a heading that contains it.

usage: check_links.py SOURCE_DIR            exit 1 naming each citation that does not resolve
       check_links.py --self-test           plants one broken citation of each kind in a scratch
                                            tree and fails unless each is found
"""
import os
import re
import subprocess
import sys
import tempfile

TEXT_FILES = ('.md', '.cpp', '.hpp', '.h', '.c', '.py', '.sh', '.mjs', '.js', '.x', '.idl',
              '.cmake', '.txt', '.arm', '.xml', '.service')
# The checker's own examples and self-test cite what does not exist, on purpose.
SKIPPED = ('lcmtypes/generated/', 'bridges/web/package-lock.json', 'scripts/check_links.py')
MADE_BY_THE_BUILD = ('build', 'lcmtypes/generated')
CHECKED = {'paths': 0, 'sections': 0, 'links': 0}
SECTION = re.compile(r"((?:docs/[\w-]+|README)\.md)(?:'s)?,?\s(?:section\s)?[*\"“]"
                     r"([^*\"”\n]{3,80}?)[*\"”]")
LINK = re.compile(r'\]\(([^)\s#]*)(#[\w-]+)?\)')


def tracked(root):
    if os.path.exists(os.path.join(root, '.git')):  # a folder, or a worktree's file
        out = subprocess.run(['git', 'ls-files'], cwd=root, capture_output=True, text=True,
                             check=True).stdout
        return [f for f in out.split('\n') if f]
    found = []
    for folder, _, names in os.walk(root):
        found += [os.path.relpath(os.path.join(folder, n), root) for n in names]
    return found


class Tree:
    """The repository's files and folders, and the include paths its headers have."""

    def __init__(self, root, files):
        self.root = root
        self.files = set(files)
        self.folders = {os.path.dirname(f) for f in files}
        for f in list(self.folders):
            while f:
                f = os.path.dirname(f)
                self.folders.add(f)
        self.includes = {f.split('/include/hapticctrl/', 1)[1] for f in files
                         if '/include/hapticctrl/' in f}
        self.tops = sorted({f.split('/')[0] for f in files if '/' in f})

    def exists(self, path):
        return path in self.files or path.rstrip('/') in self.folders

    def resolves(self, path, citing):
        here = os.path.normpath(os.path.join(os.path.dirname(citing), path))
        if self.exists(path) or self.exists(here) or path in self.includes:
            return True
        if any(f.startswith(path + '.') for f in self.files):
            return True  # a target or binary named after its source
        return path[-1] in '_-' and any(f.startswith(path) for f in self.files)

    def headings(self, doc):
        with open(os.path.join(self.root, doc), encoding='utf-8') as f:
            return [re.sub(r'^#+\s*', '', line).strip() for line in f if line.startswith('#')]


def slug(heading):
    """GitHub's anchor of a heading."""
    text = re.sub(r'[^\w\- ]', '', heading.strip().lower())
    return text.replace(' ', '-')


def paths_in(tree, line):
    pattern = re.compile(r'(?<![\w./-])((?:' + '|'.join(map(re.escape, tree.tops)) +
                         r')/[\w./+-]*[\w/])')
    for m in pattern.finditer(line):
        path = m.group(1).rstrip('.')
        rest = line[m.end():m.end() + 1]
        if rest in '*<{$' and rest or any(c in path for c in '*<>{}$'):
            continue  # a pattern
        parts = path.rstrip('/').split('/')
        if any(re.fullmatch(r'[A-Z][A-Z_]+(\.\w+)?', p) for p in parts):
            continue  # a placeholder: mujoco/scenes/NAME.xml
        if len(parts) == 2 and '.' not in parts[1] and not path.endswith('/'):
            continue  # two words with a slash ("client/raw"), not a path
        yield path


def check_file(tree, name):
    problems = []
    with open(os.path.join(tree.root, name), encoding='utf-8', errors='replace') as f:
        lines = f.read().split('\n')
    for number, line in enumerate(lines, 1):
        where = f'{name}:{number}'
        if re.match(r'\s*#\s*include\s*<', line):
            continue  # a system header
        for path in paths_in(tree, line):
            CHECKED['paths'] += 1
            if not path.startswith(MADE_BY_THE_BUILD) and not tree.resolves(path, name):
                problems.append(f'{where}: cites {path}, which does not exist')
        for m in SECTION.finditer(line):
            CHECKED['sections'] += 1
            doc, section = m.group(1), m.group(2).strip().rstrip('.,')
            if not tree.exists(doc):
                problems.append(f'{where}: cites {doc}, which does not exist')
            elif not any(section.lower() in h.lower() for h in tree.headings(doc)):
                problems.append(f'{where}: cites the section "{section}" of {doc}, which has none')
        if not name.endswith('.md'):
            continue
        for m in LINK.finditer(line):
            target, anchor = m.group(1), m.group(2)
            if re.match(r'[a-z]+:', target):
                continue  # a URL
            CHECKED['links'] += 1
            doc = os.path.normpath(os.path.join(os.path.dirname(name), target)) if target else name
            if not tree.exists(doc):
                problems.append(f'{where}: links {target}, which does not exist')
            elif anchor and doc.endswith('.md') and anchor[1:] not in map(slug,
                                                                            tree.headings(doc)):
                problems.append(f'{where}: links {target}{anchor}, which has no such heading')
    return problems


def check(root):
    files = tracked(root)
    tree = Tree(root, files)
    problems = []
    for name in sorted(files):
        if name.endswith(TEXT_FILES) and not name.startswith(SKIPPED):
            problems += check_file(tree, name)
    return problems, len(files)


def self_test():
    """One broken citation of each kind must be found, and nothing in a clean tree."""
    with tempfile.TemporaryDirectory() as root:
        def write(path, text):
            os.makedirs(os.path.join(root, os.path.dirname(path)), exist_ok=True)
            with open(os.path.join(root, path), 'w', encoding='utf-8') as f:
                f.write(text)
        write('docs/a.md', '# A\n\n## Joint space\n\nSee `src/x.cpp` and [b](b.md#b).\n')
        write('docs/b.md', '# B\n')
        write('src/x.cpp', '// docs/a.md, *Joint space*\n')
        clean, _ = check(root)
        write('src/y.cpp', '// src/gone.cpp; docs/a.md, *No such section*\n')
        write('docs/c.md', '# C\n\n[a](a.md#nowhere) [d](d.md)\n')
        planted, _ = check(root)
    wanted = ['src/gone.cpp', 'No such section', 'a.md#nowhere', 'd.md']
    missed = [w for w in wanted if not any(w in p for p in planted)]
    if clean or missed or len(planted) != len(wanted):
        print(f'check_links: self-test failed: clean tree {clean}, planted found {planted}, '
              f'missed {missed}', file=sys.stderr)
        return 1
    print(f'check_links: self-test: the {len(wanted)} planted citations found, a clean tree clean')
    return 0


def main(argv):
    if argv[1:] == ['--self-test']:
        return self_test()
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 64
    problems, count = check(os.path.abspath(argv[1]))
    for p in problems:
        print(f'check_links: {p}', file=sys.stderr)
    if not problems:
        print(f'check_links: every cited path and section exists ({count} files read: '
              f"{CHECKED['paths']} paths, {CHECKED['sections']} sections, "
              f"{CHECKED['links']} links)")
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
