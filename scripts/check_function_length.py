#!/usr/bin/env python3
"""Lists functions in src/ longer than a limit (default 200 lines); exit 1 if any.

  scripts/check_function_length.py [REPO_ROOT] [--max N] [--top K]

A function is a brace block opened at namespace or class scope after a ")"
(lambdas and nested blocks count toward their enclosing function). Comments,
string and raw-string literals are blanked first. Tests (*_test.cc) are not
checked. Run by ctest as style/no_function_over_200_lines (issue 25: a long
function is a stage that wants a name).
"""
import argparse
import re
from pathlib import Path


def blank_comments_and_strings(src):
    out, i, n = [], 0, len(src)
    while i < n:
        if src.startswith("//", i):
            j = src.find("\n", i)
            i = n if j < 0 else j
            continue
        if src.startswith("/*", i):
            j = src.find("*/", i + 2)
            j = n - 2 if j < 0 else j
            out.append("\n" * src.count("\n", i, j + 2))
            i = j + 2
            continue
        m = re.match(r'R"([^(\s]*)\(', src[i:i + 20]) if src.startswith('R"', i) else None
        if m:
            end = src.find(")" + m.group(1) + '"', i)
            end = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + "\n" * src.count("\n", i, end))
            i = end
            continue
        c = src[i]
        if c == '"' or (c == "'" and not (i > 0 and src[i - 1].isalnum())):
            j = i + 1
            while j < n and src[j] != c and src[j] != "\n":
                j += 2 if src[j] == "\\" else 1
            out.append('""')
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def functions(path):
    text = blank_comments_and_strings(path.read_text(errors="replace"))
    stack, line, head_start = [], 1, 0
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        elif c == "{":
            head = text[head_start:i].strip()
            if re.search(r"\bnamespace\b", head) or head.startswith('extern ""'):
                kind = "namespace"
            elif re.search(r"\b(struct|class|enum|union)\b[^()]*$", head):
                kind = "class"
            elif ")" in head and all(k in ("namespace", "class") for k, _, _ in stack):
                kind = "function"
            else:
                kind = "block"
            stack.append((kind, line, " ".join(head.split())[-70:]))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, first, head = stack.pop()
                if kind == "function":
                    yield line - first + 1, first, head
            head_start = i + 1
        elif c == ";":
            head_start = i + 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("root", nargs="?", default=Path(__file__).resolve().parent.parent, type=Path)
    ap.add_argument("--max", type=int, default=200)
    ap.add_argument("--top", type=int, default=0, help="also list the K longest functions")
    args = ap.parse_args()
    found = []
    for path in sorted((args.root / "src").rglob("*.cc")):
        if path.name.endswith("_test.cc"):
            continue
        for length, first, head in functions(path):
            found.append((length, f"{path.relative_to(args.root)}:{first}", head))
    found.sort(reverse=True)
    for length, where, head in found[:args.top]:
        print(f"{length:5d}  {where}  {head}")
    long = [f for f in found if f[0] > args.max]
    for length, where, head in long:
        print(f"{where}: function of {length} lines (limit {args.max}): {head}")
    if not long:
        print(f"functions: {len(found)} in src/, none over {args.max} lines")
    return 1 if long else 0


if __name__ == "__main__":
    raise SystemExit(main())
