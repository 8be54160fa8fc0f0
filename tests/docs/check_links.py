#!/usr/bin/python3
"""Every relative link of README.md, docs/ and studies/README.md resolves: its file exists in the
checkout, and its #anchor, when it has one into a Markdown page, is a heading of that page (as
GitHub makes anchors of headings). Every source path the pages cite (a header, a source file, a
script: `src/post/include/pcrf/post/cube_reports.hpp`, `study/plan.hpp`, `fuzz.py`) names a file
of the checkout: a path from one of its top-level folders exactly, a shorter one as the end of
a file's path. Prints each broken link or citation as FILE:LINE: target (problem) and exits 1;
0 when every one resolves.

    /usr/bin/python3 tests/docs/check_links.py [CHECKOUT]
"""
import re
import sys
from pathlib import Path

# A cited source path: folders, then a file with a source's extension, not part of a longer word
# or path. One after "owner/repo@commit:" is another repository's; one with a placeholder in
# capitals (NAME_plan.cpp) names no file.
CITED = re.compile(r"(?<![\w./:@-])((?:[\w.-]+/)*[\w.-]+\.(?:hpp|cpp|h|py|sh|cmake))(?![\w/])")
PLACEHOLDER = re.compile(r"(?<![A-Za-z])[A-Z]{3,}(?![a-z])")
URL = re.compile(r"[a-z][a-z0-9+.-]*://\S+")
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^()\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^\s*```")


def pages(root):
    yield root / "README.md"
    yield from sorted((root / "docs").rglob("*.md"))
    yield root / "studies" / "README.md"


def anchors(page):
    """GitHub's anchors of a page's headings: lower case, punctuation dropped, spaces as dashes,
    repeats numbered."""
    seen, found = {}, set()
    for line in outside_code(page):
        heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line[1])
        if not heading:
            continue
        slug = re.sub(r"[^\w\- ]", "", heading.group(1).lower()).replace(" ", "-")
        count = seen.get(slug, 0)
        seen[slug] = count + 1
        found.add(slug if count == 0 else f"{slug}-{count}")
    return found


def outside_code(page):
    """(line number, text) of the lines outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
        elif not fenced:
            yield number, line


def broken_links(root):
    for page in pages(root):
        if not page.is_file():
            yield f"{page.relative_to(root)}: missing page"
            continue
        for number, line in outside_code(page):
            for target in LINK.findall(re.sub(r"`[^`]*`", "", line)):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto:: not ours to check
                    continue
                path, _, anchor = target.partition("#")
                file = (page.parent / path).resolve() if path else page
                where = f"{page.relative_to(root)}:{number}: {target}"
                if not file.exists():
                    yield f"{where} (no such file)"
                elif anchor and file.suffix == ".md" and anchor not in anchors(file):
                    yield f"{where} (no heading #{anchor} in {file.relative_to(root)})"


def checkout_files(root):
    """Every file of the checkout, as a path from its root (build trees and hidden folders left out)."""
    files = []
    for path in root.rglob("*"):
        parts = path.relative_to(root).parts
        if path.is_file() and not any(p.startswith(".") or p.startswith("build") for p in parts[:-1]):
            files.append("/".join(parts))
    return files


def cited_paths(root):
    """Each source path a page cites that names no file of the checkout."""
    files = checkout_files(root)
    tops = {f.split("/")[0] for f in files if "/" in f}
    for page in pages(root):
        if not page.is_file():
            continue
        for number, line in outside_code(page):
            for cited in CITED.findall(URL.sub("", line)):
                if PLACEHOLDER.search(cited):
                    continue
                if cited.split("/")[0] in tops:
                    known = (root / cited).is_file()
                else:
                    known = any(f == cited or f.endswith("/" + cited) for f in files)
                if not known:
                    yield f"{page.relative_to(root)}:{number}: {cited} (no such file in the checkout)"


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parents[2])
    problems = list(broken_links(root)) + list(cited_paths(root))
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
