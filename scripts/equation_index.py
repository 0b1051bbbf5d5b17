#!/usr/bin/env python3
"""Writes docs/equations.md: every thesis equation the code cites, where, and in what.

    python3 scripts/equation_index.py            # regenerate docs/equations.md
    python3 scripts/equation_index.py --check    # exit 1 when docs/equations.md is stale

The index is built from the code's own citations: "(3.42)" in lib/, solvers/, validation/ and
apps/ (comments and string literals of C++ sources and headers), ranges "(2.48)-(2.53)" expanded to every equation between.
For each citation: the file and line, and the function, class or declaration it belongs to
(the enclosing function body; else, for a comment, the declaration that follows it; else the
enclosing class). The thesis' section of each equation comes from its \\tag{} in
../shared/reference/thesis-soft-robots-cosserat.md, when that file is there.

--check compares equations, files and functions, not line numbers, so the ctest
docs_equation_index fails when a citation is added, removed or moves to another function, not
when unrelated lines shift (regenerate anyway when you touch the code: the lines are printed).
"""
import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "equations.md"
THESIS = ROOT.parent / "shared" / "reference" / "thesis-soft-robots-cosserat.md"
DIRS = ("lib", "solvers", "validation", "apps")

CITATION = re.compile(r"\((\d)\.(\d+)\)(?:\s*-\s*\((\d)\.(\d+)\))?")
KEYWORDS = {"if", "for", "while", "switch", "return", "catch", "sizeof", "static_cast",
            "const_cast", "reinterpret_cast", "dynamic_cast", "decltype", "alignof", "assert",
            "defined", "noexcept", "requires", "operator", "template", "throw", "new", "delete"}


def blank_code(text):
    """(code with comments and literals blanked, per-line comment flags)."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text[i] in "\"'":
            q, j = text[i], i + 1
            while j < n and text[j] != q and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(re.sub(r"[^\n]", " ", text[i:j + 1]))
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def scopes(code):
    """Per line: the innermost enclosing function name, or class name, or None."""
    lines = code.split("\n")
    per_line, stack, pending = [], [], None
    for line in lines:
        head = line.strip()
        m = re.search(r"\b(class|struct)\s+(\w+)[^;]*$", head)
        if m:
            pending = ("class", m.group(2))
        else:
            f = re.search(r"([~\w:]+)\s*\([^;]*$", head)
            if f and f.group(1).split("::")[-1] not in KEYWORDS and not head.startswith("#"):
                pending = ("function", f.group(1))
        current = next((name for kind, name in reversed(stack) if kind == "function"), None) \
            or next((name for kind, name in reversed(stack) if kind == "class"), None)
        per_line.append(current)
        for ch in line:
            if ch == "{":
                in_function = any(k == "function" for k, _ in stack)
                if pending and not in_function:
                    stack.append(pending)
                else:
                    stack.append(("block", None))
                pending = None
            elif ch == "}" and stack:
                stack.pop()
            elif ch == ";" and not any(k == "function" for k, _ in stack):
                pending = None
    return per_line


def next_declaration(code_lines, start):
    """The name declared by the first code line at or after `start`."""
    for line in code_lines[start:start + 12]:
        head = line.strip()
        if not head or head.startswith("#"):
            continue
        m = re.search(r"\b(?:class|struct|enum class|enum|using|namespace)\s+(\w+)", head)
        if m:
            return m.group(1)
        f = re.search(r"([~\w:]+)\s*\(", head)
        if f and f.group(1).split("::")[-1] not in KEYWORDS:
            return f.group(1)
        m = re.search(r"(\w+)\s*(?:=|\{|;)", head)
        if m:
            return m.group(1)
    return None


def thesis_sections():
    """equation -> the thesis section it is tagged under, if the thesis is here."""
    if not THESIS.exists():
        return None
    sections, current = {}, ""
    for line in THESIS.read_text(encoding="utf-8").split("\n"):
        if line.startswith("### "):
            current = line[4:].strip()
        for tag in re.findall(r"\\tag\{(\d\.\d+)\}", line):
            sections.setdefault(tag, current)
    return sections


def citations():
    """(equation, file, line, owner) for every citation, sorted."""
    found = []
    for d in DIRS:
        for path in sorted((ROOT / d).rglob("*")):
            if path.suffix not in (".cpp", ".hpp"):
                continue
            text = path.read_text(encoding="utf-8")
            code = blank_code(text)
            owners = scopes(code)
            code_lines = code.split("\n")
            rel = path.relative_to(ROOT).as_posix()
            for number, line in enumerate(text.split("\n")):
                blanked = code_lines[number] if number < len(code_lines) else ""
                for m in CITATION.finditer(line):
                    if m.start() < len(blanked) and blanked[m.start()] != " ":
                        continue  # code such as f(1.0), not a citation in a comment or text
                    chapter, first = int(m.group(1)), int(m.group(2))
                    last = first
                    if m.group(3) and int(m.group(3)) == chapter and int(m.group(4)) >= first:
                        last = int(m.group(4))
                    if chapter not in (1, 2, 3, 4) or last - first > 40:
                        continue
                    owner = owners[number] if number < len(owners) else None
                    is_comment = code_lines[number].strip() == "" or "//" in line
                    if owner is None or (is_comment and code_lines[number].strip() == ""):
                        owner = owner or next_declaration(code_lines, number + 1)
                    for k in range(first, last + 1):
                        found.append((chapter, k, rel, number + 1, owner or "(file)"))
    return sorted(set(found))


def render(rows, sections):
    out = ["# Equation index", "",
           "Every equation of the thesis (`../shared/reference/thesis-soft-robots-cosserat.md`) that",
           "the code cites, where and in what: generated by `python3 scripts/equation_index.py`",
           "from the citations in lib/, solvers/, validation/ and apps/ (ranges such as",
           "(2.48)-(2.53) are expanded). Do not edit by hand; the ctest `docs_equation_index`",
           "fails when a citation is added, removed or moves to another function.", ""]
    equations = sorted({(c, k) for c, k, *_ in rows})
    out.append(f"{len(equations)} equations, {len(rows)} citations.")
    out.append("")
    out.append("| equation | thesis section | file:line | in |")
    out.append("|---|---|---|---|")
    for c, k in equations:
        eq = f"{c}.{k}"
        section = (sections or {}).get(eq, "") if sections is not None else ""
        first = True
        for rc, rk, path, line, owner in rows:
            if (rc, rk) != (c, k):
                continue
            label = f"({eq})" if first else ""
            sec = section if first else ""
            out.append(f"| {label} | {sec} | [{path}:{line}](../{path}#L{line}) | `{owner}` |")
            first = False
    return "\n".join(out) + "\n"


def comparable(text, with_sections):
    """The index without line numbers (and without sections when the thesis is absent)."""
    keep = []
    current = ""
    for line in text.split("\n"):
        if not line.startswith("| (") and not line.startswith("|  |"):
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) != 4:
            continue
        if cells[0]:
            current = cells[0]
        path = re.sub(r"\[([^:\]]+):\d+\].*", r"\1", cells[2])
        keep.append((current, cells[1] if with_sections else "", path, cells[3]))
    return sorted(keep)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="exit 1 if docs/equations.md is stale")
    args = parser.parse_args()
    sections = thesis_sections()
    text = render(citations(), sections)
    if not args.check:
        OUT.write_text(text, encoding="utf-8")
        print(f"wrote {OUT.relative_to(ROOT)}")
        return 0
    if not OUT.exists():
        print("docs/equations.md is missing: run python3 scripts/equation_index.py")
        return 1
    with_sections = sections is not None
    old = comparable(OUT.read_text(encoding="utf-8"), with_sections)
    new = comparable(text, with_sections)
    if old == new:
        return 0
    gone = sorted(set(old) - set(new))
    added = sorted(set(new) - set(old))
    for row in gone[:20]:
        print("stale in docs/equations.md:", row)
    for row in added[:20]:
        print("missing from docs/equations.md:", row)
    print("docs/equations.md is out of date: run python3 scripts/equation_index.py")
    return 1


if __name__ == "__main__":
    sys.exit(main())
