#!/usr/bin/python3
"""Every relative link of README.md, docs/ and studies/README.md resolves: its file exists in the
checkout, and its #anchor, when it has one into a Markdown page, is a heading of that page (as
GitHub makes anchors of headings). Prints each broken link as FILE:LINE: target (problem) and
exits 1; 0 when every link resolves.

    /usr/bin/python3 tests/docs/check_links.py [CHECKOUT]
"""
import re
import sys
from pathlib import Path

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


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parents[2])
    problems = list(broken_links(root))
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
