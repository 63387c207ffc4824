#!/usr/bin/env python3
"""Checks that the core's subsystems depend on each other one way only.

Each folder of native/core declares what it builds on in its CMakeLists.txt
(`radiosity_subsystem(NAME DEPENDS ...)`). Every `#include "folder/file.h"` in a subsystem's
sources and headers must name its own folder or one it builds on, directly or through others;
tests (NAME/tests) may include any subsystem. Exits 1 and names each offending line.

Usage: check_layering.py [native/core]
"""
import pathlib
import re
import sys

DECLARATION = re.compile(r'radiosity_subsystem\((\w+)(?:\s+DEPENDS\s+([\w\s]+))?\)')
INCLUDE = re.compile(r'^\s*#\s*include\s+"(\w+)/[^"]+"', re.MULTILINE)


def declared_dependencies(core):
    """Subsystem name -> the names it DEPENDS on, from each folder's CMakeLists.txt."""
    depends = {}
    for cmake in sorted(core.glob('*/CMakeLists.txt')):
        match = DECLARATION.search(cmake.read_text())
        if match:
            depends[match.group(1)] = (match.group(2) or '').split()
    return depends


def reachable(depends):
    """Subsystem name -> itself and every subsystem it builds on, directly or not."""
    closure = {}

    def visit(name, path):
        if name in path:
            sys.exit('check_layering: the subsystems depend on each other in a cycle: '
                     + ' -> '.join(path + (name,)))
        if name not in closure:
            below = {name}
            for dependency in depends.get(name, []):
                below |= visit(dependency, path + (name,))
            closure[name] = below
        return closure[name]

    for name in depends:
        visit(name, ())
    return closure


def main():
    core = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else 'native/core')
    allowed = reachable(declared_dependencies(core))
    problems = []
    for name, below in sorted(allowed.items()):
        for source in sorted((core / name).glob('*.[hc]*')):
            for line_number, line in enumerate(source.read_text().splitlines(), 1):
                match = INCLUDE.match(line)
                if match and match.group(1) in allowed and match.group(1) not in below:
                    problems.append(f'{source}:{line_number}: {name} includes {match.group(1)}, '
                                    f'which it does not build on ({", ".join(sorted(below))})')
    if not allowed:
        problems.append(f'no radiosity_subsystem() declarations under {core}')
    for problem in problems:
        print(problem)
    print(f'{len(allowed)} subsystems, {len(problems)} includes against their order')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
