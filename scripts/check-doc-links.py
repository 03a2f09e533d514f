#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Checks the links between the project's Markdown pages.

Every relative link or image in a tracked *.md file, `[text](path#anchor)` or a reference
definition `[label]: path#anchor`, must name a file or folder that exists, and its anchor (or a
bare `#anchor` within the page) must be a heading of the target page, spelled as GitHub spells
it (lower case, punctuation dropped, spaces as hyphens, `-1`, `-2` for repeated headings).
Links inside code (fenced blocks, `inline code`) and to other sites are not checked.

Usage: check-doc-links.py [REPO_ROOT]   (default: the folder above this script)
       check-doc-links.py --self-test    (checks that the checker catches broken links)
Exit status 0 when every link resolves, 1 otherwise (one line per broken link: file, line, link).
Needs any python3 (and git, to list the tracked pages of a checkout).
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFDEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?([^\s>]+)>?")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")


def slug(text):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading: its text
    # Inline HTML tags go (their text stays); inside `code`, <T> is text.
    parts = text.split("`")
    text = "".join(p if i % 2 else re.sub(r"<[^>]+>", "", p) for i, p in enumerate(parts))
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def prose_lines(path):
    """(line number, line) of the lines outside fenced code blocks."""
    fence = None
    with open(path, encoding="utf-8") as fh:
        for no, line in enumerate(fh, 1):
            m = FENCE.match(line)
            if m:
                if fence is None:
                    fence = m.group(1)
                elif m.group(1) == fence:
                    fence = None
                continue
            if fence is None:
                yield no, line.rstrip("\n")


_anchor_cache = {}


def anchors(path):
    """The anchors of a page's headings (inline code keeps its text in them)."""
    if path not in _anchor_cache:
        found, seen = set(), {}
        for _, line in prose_lines(path):
            h = HEADING.match(line)
            if h:
                s = slug(h.group(2))
                n = seen.get(s, 0)
                seen[s] = n + 1
                found.add(s if n == 0 else "%s-%d" % (s, n))
        _anchor_cache[path] = found
    return _anchor_cache[path]


def md_files(root):
    """The tracked *.md files; outside a git checkout (a source archive), every *.md file but
    those in hidden folders and build folders."""
    try:
        out = subprocess.run(["git", "-C", root, "rev-parse", "--show-toplevel"],
                             capture_output=True, text=True)
        in_git = out.returncode == 0 and os.path.samefile(out.stdout.strip(), root)
    except OSError:  # no git
        in_git = False
    if in_git:
        out = subprocess.run(["git", "-C", root, "ls-files", "*.md"], capture_output=True,
                             text=True, check=True)
        return [os.path.join(root, f) for f in out.stdout.split("\n") if f]
    found = []
    for d, dirs, files in os.walk(root):
        dirs[:] = sorted(x for x in dirs if not x.startswith(".") and not x.startswith("build"))
        found += [os.path.join(d, f) for f in sorted(files) if f.endswith(".md")]
    return found


def check(root):
    bad = []
    for f in md_files(root):
        rel = os.path.relpath(f, root)
        for no, line in prose_lines(f):
            line = re.sub(r"`[^`]*`", "", line)  # links inside inline code are not links
            targets = [m.group(1) for m in LINK.finditer(line)]
            m = REFDEF.match(line)
            if m:
                targets.append(m.group(1))
            for t in targets:
                if re.match(r"[A-Za-z][A-Za-z0-9+.-]*:", t):  # https:, mailto:, ...
                    continue
                path, _, frag = t.partition("#")
                target = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
                if not os.path.exists(target):
                    bad.append("%s:%d: %s: no such file" % (rel, no, t))
                elif frag and target.endswith(".md") and frag not in anchors(target):
                    bad.append("%s:%d: %s: no heading with that anchor in %s" %
                               (rel, no, t, os.path.relpath(target, root)))
    return bad


def self_test():
    """A small tree of pages (no git checkout: every *.md file) with one broken link of each kind
    must report exactly those."""
    d = tempfile.mkdtemp(prefix="ebgeom-doclinks-")
    try:
        files = {
            "README.md": "# Top\n[guide](docs/guide.md#the-apit-v2) [gone](docs/missing.md)\n"
                         "[bad anchor](docs/guide.md#nowhere) `[code](not/checked.md)`\n"
                         "[web](https://example.org/x) [self](#top) [self bad](#bottom)\n",
            "docs/guide.md": "# Guide\n\n## The `api<T>` (v2)\n\n```sh\n# not a heading\n```\n"
                             "## Again\n## Again\n[up](../README.md#top) [second](#again-1)\n"
                             "[ref]: ../README.md#nope\n",
        }
        for rel, text in files.items():
            p = os.path.join(d, rel)
            os.makedirs(os.path.dirname(p), exist_ok=True)
            with open(p, "w", encoding="utf-8") as fh:
                fh.write(text)
        got = sorted(b.split(": ")[0] + ": " + b.split(": ")[1] for b in check(d))
        want = sorted([
            "README.md:2: docs/missing.md",
            "README.md:3: docs/guide.md#nowhere",
            "README.md:4: #bottom",
            "docs/guide.md:11: ../README.md#nope",
        ])
        if got != want:
            print("check-doc-links self-test: expected %s, got %s" % (want, got))
            return 1
        print("check-doc-links self-test: ok (%d broken links found, none missed)" % len(want))
        return 0
    finally:
        shutil.rmtree(d)


def main(argv):
    if len(argv) > 1 and argv[1] == "--self-test":
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                      "..")
    bad = check(os.path.abspath(root))
    for b in bad:
        print(b)
    if bad:
        print("check-doc-links: %d broken link(s)" % len(bad))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
