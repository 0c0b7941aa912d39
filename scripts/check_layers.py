#!/usr/bin/env python3
"""Checks that the README's "Layers, bottom → top" table is the code's layering.

  scripts/check_layers.py [REPO_ROOT]

The table (README.md) gives each module under src/asbuilt/ a layer number. The
check fails, naming the file and line, when
  - a module folder is missing from the table, or the table names a folder that
    does not exist;
  - a file of module M includes "asbuilt/N/…" where N's layer is not below M's
    (a module's own headers are fine);
  - a module's CMakeLists.txt links asbuilt::N (DEPS or PRIVATE_DEPS of its
    library) where N's layer is not below M's;
  - the top-level CMakeLists.txt's ASBUILT_MODULES is not ordered by layer
    (CMake adds the modules in that order, bottom → top).
Run by ctest as layers/readme_table_is_the_code.
"""
import re
import sys
from pathlib import Path

root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
problems = []

readme = (root / "README.md").read_text()
section = readme.split("## Layers, bottom → top", 1)
if len(section) < 2:
    sys.exit("README.md: no \"## Layers, bottom → top\" section")
layer = {}
for line in section[1].split("\n## ", 1)[0].splitlines():
    m = re.match(r"\|\s*(\d+)\s*\|\s*`(\w+)`\s*\|", line)
    if m:
        layer[m.group(2)] = int(m.group(1))

src = root / "src" / "asbuilt"
folders = {p.name for p in src.iterdir() if p.is_dir()}
for name in sorted(folders - layer.keys()):
    problems.append(f"README.md: module src/asbuilt/{name} is not in the layers table")
for name in sorted(layer.keys() - folders):
    problems.append(f"README.md: layers table names `{name}`, which is not a folder of src/asbuilt")

include = re.compile(r'^\s*#\s*include\s+"asbuilt/(\w+)/')
for module in sorted(folders & layer.keys()):
    for path in sorted((src / module).rglob("*")):
        if path.suffix not in (".h", ".cc"):
            continue
        for number, text in enumerate(path.read_text(errors="replace").splitlines(), 1):
            m = include.match(text)
            if not m or m.group(1) == module or m.group(1) not in layer:
                continue
            if layer[m.group(1)] >= layer[module]:
                problems.append(f"{path.relative_to(root)}:{number}: `{module}` (layer {layer[module]}) includes "
                                f"`{m.group(1)}` (layer {layer[m.group(1)]}), which is not below it")
    cmake = src / module / "CMakeLists.txt"
    if cmake.exists():
        text = cmake.read_text()
        block = re.search(r"asbuilt_library\((.*?)\)\s*$", text, re.S | re.M)
        for dep in sorted(set(re.findall(r"asbuilt::(\w+)", block.group(1) if block else ""))):
            if dep in layer and dep != module and layer[dep] >= layer[module]:
                problems.append(f"{cmake.relative_to(root)}: `{module}` (layer {layer[module]}) links "
                                f"`{dep}` (layer {layer[dep]}), which is not below it")

top = (root / "CMakeLists.txt").read_text()
m = re.search(r"set\(ASBUILT_MODULES ([^)]*)\)", top)
if not m:
    problems.append("CMakeLists.txt: no set(ASBUILT_MODULES …)")
else:
    order = m.group(1).split()
    for name in order:
        if name not in layer:
            problems.append(f"CMakeLists.txt: ASBUILT_MODULES lists `{name}`, which is not in README's layers table")
    known = [n for n in order if n in layer]
    for a, b in zip(known, known[1:]):
        if layer[a] > layer[b]:
            problems.append(f"CMakeLists.txt: ASBUILT_MODULES lists `{a}` (layer {layer[a]}) before `{b}` "
                            f"(layer {layer[b]}); order them bottom → top as README's table")
    for name in sorted(layer.keys() - set(order)):
        problems.append(f"CMakeLists.txt: ASBUILT_MODULES does not list `{name}`")

for p in problems:
    print(p)
if problems:
    sys.exit(1)
print(f"layers: {len(layer)} modules, includes, links and CMake order agree with README.md")
