#!/usr/bin/python3
"""Checks that every link in the repository's Markdown files resolves inside
the repository. Usage:
    check_links.py [REPO_ROOT] [FILE.md ...]
Without files it checks README.md and every .md file under docs/, data/,
examples/, fuzz/ and tests/. A link (inline `[text](target)`, image
`![alt](target)`, reference definition `[ref]: target`, or HTML `src=`/`href=`)
fails when its target file does not exist, lies outside the repository, or
names a `#section` that is not a heading of the target Markdown file (GitHub's
anchor rules). Web links (http, https, mailto) are not followed. Code blocks
and code spans are skipped. Sections of docs/method.md cited by name in
source files and docs (`docs/method.md, "Solver"`) must be headings of it.
Exits 1 listing every broken link as FILE:LINE: target: why."""
import os
import re
import sys

INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HTML = re.compile(r"\b(?:src|href)\s*=\s*\"([^\"]+)\"")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
WEB = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def strip_code(lines):
    """The lines with fenced code blocks blanked and code spans removed."""
    out, fence = [], None
    for line in lines:
        m = re.match(r"^\s{0,3}(`{3,}|~{3,})", line)
        if fence:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence):
                fence = None
            out.append("")
            continue
        if m:
            fence = m.group(1)
            out.append("")
            continue
        if line.startswith("    ") and (not out or out[-1].strip() == ""):
            out.append("")  # indented code block (after a blank line)
            continue
        out.append(re.sub(r"(`+)(?:(?!\1).)+?\1", "", line))
    return out


def slug(text):
    """GitHub's anchor for a heading."""
    text = re.sub(r"`|\*\*|__", "", text)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading keeps its text
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        found, seen = set(), {}
        with open(path, encoding="utf-8") as f:
            for line in strip_code(f.read().splitlines()):
                m = HEADING.match(line)
                if not m:
                    continue
                s = slug(m.group(2))
                n = seen.get(s, 0)
                seen[s] = n + 1
                found.add(s if n == 0 else f"{s}-{n}")
        cache[path] = found
    return cache[path]


def check_file(root, path):
    errors = []
    with open(path, encoding="utf-8") as f:
        lines = strip_code(f.read().splitlines())
    here = os.path.dirname(path)
    for number, line in enumerate(lines, 1):
        targets = [m.group(1) for m in INLINE.finditer(line)]
        targets += [m.group(1) for m in REFERENCE.finditer(line)]
        targets += [m.group(1) for m in HTML.finditer(line)]
        for target in targets:
            target = target.strip("<>")
            if WEB.match(target):
                continue
            file_part, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(here, file_part)) if file_part else path
            where = f"{os.path.relpath(path, root)}:{number}: {target}"
            if os.path.isabs(file_part):
                errors.append(f"{where}: an absolute path")
                continue
            if os.path.relpath(resolved, root).startswith(".."):
                errors.append(f"{where}: outside the repository")
                continue
            if not os.path.exists(resolved):
                errors.append(f"{where}: no such file")
                continue
            if anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
                errors.append(f"{where}: no heading with anchor #{anchor}")
    return errors


SECTION_CITATION = re.compile(r"(?:docs/)?method\.md\W{0,4}\"([^\"]+)\"")
CITING_EXTENSIONS = (".h", ".cpp", ".py", ".sh", ".txt", ".cmake", ".in", ".geo", ".md")


def check_section_citations(root):
    """Every `docs/method.md "Section"` in the tree names a heading of docs/method.md."""
    method = os.path.join(root, "docs", "method.md")
    if not os.path.exists(method):
        return [f"docs/method.md: no such file"]
    headings = set()
    with open(method, encoding="utf-8") as f:
        for line in strip_code(f.read().splitlines()):
            m = HEADING.match(line)
            if m:
                headings.add(m.group(2).strip())
    errors = []
    for top in ("include", "src", "tests", "examples", "bench", "fuzz", "scripts", "data", "docs", "cmake"):
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith(CITING_EXTENSIONS):
                    continue
                path = os.path.join(dirpath, name)
                if os.path.samefile(path, __file__):
                    continue  # its own messages
                with open(path, encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        for m in SECTION_CITATION.finditer(line):
                            if m.group(1) not in headings:
                                errors.append(f"{os.path.relpath(path, root)}:{number}: docs/method.md "
                                              f"\"{m.group(1)}\": no such section")
    return errors


def default_files(root):
    files = [os.path.join(root, "README.md")]
    for top in ("docs", "data", "examples", "fuzz", "tests"):
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames.sort()
            files += [os.path.join(dirpath, n) for n in sorted(filenames) if n.endswith(".md")]
    return files


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    files = [os.path.abspath(p) for p in argv[2:]] or default_files(root)
    errors = []
    for path in files:
        errors += check_file(root, path)
    if len(argv) <= 2:
        errors += check_section_citations(root)
    for e in errors:
        print(e)
    print(f"{len(files)} Markdown file(s), {len(errors)} broken link(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
