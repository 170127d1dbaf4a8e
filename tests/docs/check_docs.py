#!/usr/bin/env python3
"""The docs as a manual: checks that fail when

- a page (docs/*.md, README.md) is over 40 000 bytes: a manual page a user reads, not a log;
- docs (docs/*.md, README.md) or code (src/, tests/, postproc/, inputs/, cmake/, .ci/,
  CMakeLists.txt) cite "issue N" (case-insensitive 'issue ?#?[0-9]+'): say what and why, cite SPEC §N
  or a paper; the history of a figure belongs in git;
- a relative link or image in docs/*.md or README.md points to a file that does not exist
  (links with a scheme, such as https:, and links to an anchor of the same page are not checked;
  text in code blocks and code spans is not a link).

    /usr/bin/python3 tests/docs/check_docs.py [REPOSITORY_ROOT]

Prints one line per finding and exits 1 if there is any, else prints one line and exits 0.
"""
import re
import sys
from pathlib import Path

MAX_BYTES = 40_000
ISSUE = re.compile(r"issue[ #-]?#?[0-9]+", re.IGNORECASE)
# [text](target "title") and ![alt](target); the target ends at whitespace or ')'
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+[\"'(][^)]*)?\)")
# [label]: target
REFERENCE_LINK = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
FENCE = re.compile(r"^\s{0,3}(`{3,}|~{3,})")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")


def pages(root):
    return sorted((root / "docs").glob("*.md")) + [root / "README.md"]


def prose_lines(text):
    """(line number, line) of the text outside fenced code blocks, code spans blanked."""
    fence = None
    for n, line in enumerate(text.splitlines(), 1):
        m = FENCE.match(line)
        if fence is None and m:
            fence = m.group(1)[0] * 3
            continue
        if fence is not None:
            if line.strip().startswith(fence):
                fence = None
            continue
        yield n, CODE_SPAN.sub(lambda s: " " * len(s.group(0)), line)


def links(text):
    for n, line in prose_lines(text):
        for m in INLINE_LINK.finditer(line):
            yield n, m.group(1)
        m = REFERENCE_LINK.match(line)
        if m:
            yield n, m.group(1)


def check(root):
    findings = []
    for page in pages(root):
        if not page.is_file():
            findings.append(f"{page.relative_to(root)}: missing")
            continue
        size = page.stat().st_size
        if size > MAX_BYTES:
            findings.append(f"{page.relative_to(root)}: {size} bytes, over {MAX_BYTES}")
        text = page.read_text(encoding="utf-8")
        for n, target in links(text):
            if SCHEME.match(target) or target.startswith("#"):
                continue
            path = target.split("#", 1)[0].split("?", 1)[0]
            if not path:
                continue
            resolved = (root / path.lstrip("/")) if path.startswith("/") else (page.parent / path)
            if not resolved.exists():
                findings.append(f"{page.relative_to(root)}:{n}: link to {target}: no such file")
    cited = [p for p in pages(root) if p.is_file()]
    for folder in ("src", "tests", "postproc", "inputs", "cmake", ".ci"):
        cited += sorted(p for p in (root / folder).rglob("*")
                        if p.is_file() and "__pycache__" not in p.parts)
    if (root / "CMakeLists.txt").is_file():
        cited.append(root / "CMakeLists.txt")
    for path in cited:
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            for m in ISSUE.finditer(line):
                findings.append(f"{path.relative_to(root)}:{n}: cites '{m.group(0)}'")
    return findings


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parents[2]).resolve()
    findings = check(root)
    for f in findings:
        print(f)
    if findings:
        print(f"check_docs: {len(findings)} finding(s)")
        return 1
    print(f"check_docs: {len(pages(root))} pages and the code clean")
    return 0


if __name__ == "__main__":
    sys.exit(main())
