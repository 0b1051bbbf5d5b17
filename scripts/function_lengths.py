#!/usr/bin/env python3
"""Lists C++ functions longer than a limit (default 80 lines, signature to closing brace).

    python3 scripts/function_lengths.py [--limit N] [--check] DIR...

A function is a brace block opened after a parameter list ')' (with optional qualifiers)
outside any other function body; lambdas and nested blocks count towards their function.
Comments, string and character literals are blanked first. --check exits 1 when any
function is over the limit (the `functions_short` ctest runs it on apps/ and validation/).
"""
import argparse
import pathlib
import re
import sys

QUALIFIERS = re.compile(r"\)\s*(const|noexcept|override|final|mutable|&|&&|->\s*[\w:<>,\s*&]+|\s)*$")


def blank(text):
    """Comments and literals replaced by spaces; newlines kept."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k)
            j = n if j < 0 else j + len(delim)
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(re.sub(r"[^\n]", " ", text[i:j + 1])); i = j + 1
        else:
            out.append(c); i += 1
    return "".join(out)


def functions(path):
    """(name, first line, last line) of every function body in the file."""
    text = blank(path.read_text())
    found, stack, i = [], [], 0
    for i, c in enumerate(text):
        if c == "{":
            head = text[max(0, i - 400):i]
            in_function = any(kind == "f" for kind, _, _ in stack)
            is_function = not in_function and QUALIFIERS.search(head.rstrip() + " ") is not None \
                and re.search(r"\)\s*(const|noexcept|override|final|&|&&|->[^;{}]*|\s)*$", head)
            if is_function:
                # start: the line of the name before the parameter list
                depth, k = 0, len(head.rstrip()) - 1
                stripped = head.rstrip()
                while k >= 0:
                    if stripped[k] == ")": depth += 1
                    elif stripped[k] == "(":
                        depth -= 1
                        if depth == 0: break
                    k -= 1
                m = re.search(r"([\w:~<>]+)\s*$", stripped[:k]) if k > 0 else None
                name = m.group(1) if m else "?"
                start = text.count("\n", 0, i - len(head) + k) + 1 if k > 0 else text.count("\n", 0, i) + 1
                stack.append(("f", name, start))
            else:
                stack.append(("b", "", 0))
        elif c == "}" and stack:
            kind, name, start = stack.pop()
            if kind == "f":
                found.append((name, start, text.count("\n", 0, i) + 1))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dirs", nargs="+")
    parser.add_argument("--limit", type=int, default=80)
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    over = []
    for d in args.dirs:
        for path in sorted(pathlib.Path(d).rglob("*")):
            if path.suffix in (".cpp", ".hpp", ".h", ".cc"):
                for name, start, end in functions(path):
                    length = end - start + 1
                    if length > args.limit:
                        over.append((length, f"{path}:{start}", name))
    for length, where, name in sorted(over, reverse=True):
        print(f"{length:5d}  {where}  {name}")
    if args.check and over:
        print(f"{len(over)} function(s) longer than {args.limit} lines", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
