#!/usr/bin/env python3
"""Every relative link and image in README.md and docs/*.md names a file of the repository (and a heading
of it, for #anchors), and every page under docs/ is reached from the README. usage: links.py [REPO_ROOT]"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2]).resolve()
pages = [root / "README.md"] + sorted((root / "docs").glob("*.md"))

INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFDEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)")
HTML = re.compile(r"<(?:img|a)\b[^>]*?\b(?:src|href)\s*=\s*\"([^\"]+)\"", re.I)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`|\*\*|__", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def prose(path):
    """(line number, text) of each line outside fenced code, with inline code spans blanked."""
    fence = None
    for n, line in enumerate(path.read_text(encoding="utf-8").split("\n"), 1):
        stripped = line.lstrip()
        if fence is None and (stripped.startswith("```") or stripped.startswith("~~~")):
            fence = stripped[:3]
            continue
        if fence is not None:
            if stripped.startswith(fence):
                fence = None
            continue
        yield n, re.sub(r"`[^`]*`", "``", line)


def anchors(path):
    seen, out = {}, set()
    for _, line in prose(path):
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            s = slug(m.group(1))
            k = seen.get(s, 0)
            seen[s] = k + 1
            out.add(s if k == 0 else f"{s}-{k}")
    return out


errors, links, reached = [], 0, set()
for page in pages:
    for n, line in prose(page):
        targets = INLINE.findall(line) + HTML.findall(line)
        m = REFDEF.match(line)
        if m:
            targets.append(m.group(1))
        for target in targets:
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):   # http:, https:, mailto: are not checked here
                continue
            links += 1
            where = f"{page.relative_to(root)}:{n}"
            file_part, _, anchor = target.partition("#")
            dest = (page.parent / file_part).resolve() if file_part else page
            if root not in dest.parents and dest != root:
                errors.append(f"{where}: '{target}' leaves the repository")
                continue
            if not dest.exists():
                errors.append(f"{where}: '{target}' names no file ({dest.relative_to(root)})")
                continue
            reached.add(dest)
            if anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                errors.append(f"{where}: '{target}': {dest.relative_to(root)} has no heading '#{anchor}'")

# Every page under docs/ is reachable from the README through the pages' links.
graph_ok, todo, seen_pages = set(), [root / "README.md"], set()
while todo:
    page = todo.pop()
    if page in seen_pages:
        continue
    seen_pages.add(page)
    for _, line in prose(page):
        for target in INLINE.findall(line):
            file_part = target.partition("#")[0]
            if file_part and not re.match(r"^[a-z][a-z0-9+.-]*:", file_part, re.I):
                dest = (page.parent / file_part).resolve()
                if dest.suffix == ".md" and dest.exists():
                    todo.append(dest)
for page in pages[1:]:
    if page.resolve() not in seen_pages:
        errors.append(f"{page.relative_to(root)}: no link from the README reaches it")

for e in errors:
    print(e)
print(f"links: {links} relative links and images in {len(pages)} pages, {len(errors)} broken")
sys.exit(1 if errors else 0)
