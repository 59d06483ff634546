#!/usr/bin/env python3
"""Checks the documentation against itself and against the code (run by .ci/run).

    python3 scripts/check_docs.py [--book docs/book]

1. Nothing in the repository's text points outside it: no file under the checked roots
   names the project's private notes (the shared folder beside the checkout, its model
   page), and no Markdown link climbs out of the repository.
2. Every link of the built book (`mdbook build docs` first) resolves: the page exists and
   so does the anchor. Relative links in README.md, BENCHMARKS.md and the benchmark history resolve too.
3. The scenario reference lists exactly the keys the scenario parser accepts: every key
   in the first column of a table in docs/src/scenario.md is a key of the code in
   src/scenario/ (or of the serde structs it reads), and every key of the code is in the
   first column of a table somewhere in the book.
4. Every row of a Markdown table in README.md and the book has as many cells as its
   header.

Standard library only. Exits non-zero with one line per problem.
"""

import argparse
import re
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

ROOT = Path(__file__).resolve().parent.parent

# Where the repository's own text lives.
TEXT_ROOTS = [
    "README.md",
    "BENCHMARKS.md",
    "benchmarks",
    "Cargo.toml",
    ".ci",
    "docs/src",
    "docs/book.toml",
    "src",
    "shaders",
    "tests",
    "benches",
    "examples",
    "scripts",
    "python",
]
TEXT_SUFFIXES = {".md", ".rs", ".wgsl", ".toml", ".py", ".txt", ".csv", ""}

# Written in pieces so that this file does not match itself.
OUTSIDE = [
    re.compile(r"\.\./" + "shared"),
    re.compile("/work/" + "shared"),
    # the working machine's scratch folders (helpers' binaries, copies of models)
    re.compile("/work/" + "helpers"),
    re.compile("/work/" + "wt/"),
    re.compile(r"\bMODEL" + r"\.md\b"),
    re.compile("shared/" + "paper"),
]

MD_LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def text_files():
    for r in TEXT_ROOTS:
        p = ROOT / r
        if p.is_file():
            yield p
        elif p.is_dir():
            for f in sorted(p.rglob("*")):
                if f.is_file() and f.suffix in TEXT_SUFFIXES and "__pycache__" not in f.parts:
                    yield f


def strip_code(md):
    """Markdown without fenced code blocks and inline code (links there are not links)."""
    md = re.sub(r"^```.*?^```", "", md, flags=re.S | re.M)
    return re.sub(r"`[^`\n]*`", "", md)


def is_external(target):
    return bool(re.match(r"^[a-z][a-z0-9+.-]*:", target)) or target.startswith("//")


def check_outside(problems):
    for f in text_files():
        try:
            text = f.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        rel = f.relative_to(ROOT)
        for no, line in enumerate(text.splitlines(), 1):
            for pat in OUTSIDE:
                if pat.search(line):
                    problems.append(
                        f"{rel}:{no}: points outside the repository ({pat.pattern!r}); "
                        "state what is needed in the repository's own docs instead"
                    )
        if f.suffix == ".md":
            for m in MD_LINK.finditer(strip_code(text)):
                target = m.group(1)
                if is_external(target) or target.startswith("#"):
                    continue
                path = (f.parent / unquote(urlsplit(target).path)).resolve()
                if ROOT not in path.parents and path != ROOT:
                    problems.append(f"{rel}: link {target!r} leaves the repository")


def github_slug(heading):
    """The anchor GitHub gives a Markdown heading."""
    s = re.sub(r"[`*_]|<[^>]+>", "", heading.strip()).lower()
    s = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", s)
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def md_anchors(path):
    anchors, seen = set(), {}
    in_code = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            in_code = not in_code
        if in_code:
            continue
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            slug = github_slug(m.group(1))
            n = seen.get(slug, 0)
            seen[slug] = n + 1
            anchors.add(slug if n == 0 else f"{slug}-{n}")
    return anchors


def check_markdown_links(problems, files):
    """Relative links of Markdown files outside the book (README, BENCHMARKS)."""
    for rel in files:
        f = ROOT / rel
        if not f.exists():
            continue
        for m in MD_LINK.finditer(strip_code(f.read_text(encoding="utf-8"))):
            target = m.group(1)
            if is_external(target):
                continue
            parts = urlsplit(target)
            path = f if not parts.path else (f.parent / unquote(parts.path)).resolve()
            if ROOT not in path.parents and path != ROOT:
                continue  # reported by check_outside
            if not path.exists():
                problems.append(f"{rel}: link {target!r}: {path.relative_to(ROOT)} does not exist")
                continue
            if parts.fragment and path.suffix == ".md" and parts.fragment not in md_anchors(path):
                problems.append(f"{rel}: link {target!r}: no heading with that anchor")


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.links = set(), []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(a["id"])
        if a.get("name") and tag == "a":
            self.ids.add(a["name"])
        for key in ("href", "src"):
            if a.get(key):
                self.links.append(a[key])


def check_book(problems, book):
    if not (book / "index.html").exists():
        problems.append(f"{book}: no built book (run `mdbook build docs` first)")
        return
    pages = {}
    for f in book.rglob("*.html"):
        p = _Links()
        p.feed(f.read_text(encoding="utf-8"))
        pages[f.resolve()] = p
    for f, p in sorted(pages.items()):
        # The print page and the table of contents repeat the chapters' links.
        if f.name in ("print.html", "toc.html", "404.html"):
            continue
        rel = f.relative_to(book.resolve())
        for link in p.links:
            if is_external(link):
                continue
            parts = urlsplit(link)
            target = f if not parts.path else (f.parent / unquote(parts.path)).resolve()
            if not target.exists():
                problems.append(f"book {rel}: link {link!r}: no such file in the built book")
                continue
            if parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else set()
                if parts.fragment not in ids:
                    problems.append(f"book {rel}: link {link!r}: no element with id {parts.fragment!r}")


def check_tables(problems, files):
    """Every row of a Markdown table has as many cells as its header: an unescaped `|`
    inside a cell (`|v| v` in a formula) splits it and shifts the row."""
    for f in files:
        rel = f.relative_to(ROOT)
        in_code, width = False, None
        for no, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
            if line.startswith("```"):
                in_code = not in_code
            if in_code or not line.startswith("|"):
                width = None
                continue
            cells = len(line.replace("\\|", "").strip().strip("|").split("|"))
            if width is None:
                width = cells
            elif cells != width:
                problems.append(
                    f"{rel}:{no}: table row has {cells} cells, its header {width} "
                    "(escape a | inside a cell as \\|)"
                )


# --- scenario keys -------------------------------------------------------------------

# Files whose serde structs are read from scenario files.
SERDE_FILES = ["src/model/line_type.rs", "src/model/environment.rs"]
KEY = r"[a-z][a-z0-9_]*"


def serde_keys(text):
    """Field names of the structs deriving Deserialize in `text`."""
    keys = set()
    for m in re.finditer(r"#\[derive\([^)]*Deserialize[^)]*\)\][^{]*?struct\s+\w+\s*\{(.*?)\n\}", text, re.S):
        rename, skip = None, False
        for line in m.group(1).splitlines():
            r = re.search(r'#\[serde\([^]]*\brename\s*=\s*"(' + KEY + r')"', line)
            if r:
                rename = r.group(1)
            # A `#[serde(skip)]` field is no key.
            if re.search(r"#\[serde\(\s*skip\s*\)\]", line):
                skip = True
            f = re.match(r"\s*pub\s+(" + KEY + r")\s*:", line)
            if f:
                # A `#[serde(rename = "...")]` before the field names its key.
                if not skip:
                    keys.add(rename or f.group(1))
                rename, skip = None, False
    return keys


def table_keys(text):
    """Keys the hand-written TOML readers look up: `.get("k")`, `["k"]`, `contains_key("k")`,
    `push("k")`, helper calls `(p, field, t, "k", ...)`, and arrays of key names."""
    keys = set()
    pats = [
        r'\.get\("(' + KEY + r')"\)',
        r'\w\["(' + KEY + r')"\]',
        r'contains_key\("(' + KEY + r')"\)',
        r'\.push\("(' + KEY + r')"\)',
        r'\b(?:req|get)_\w+\(\s*\w+,\s*\w+,\s*\w+,\s*"(' + KEY + r')"',
        r'\breq\("(' + KEY + r')"\)',
    ]
    for pat in pats:
        keys.update(re.findall(pat, text))
    # Arrays of key names: `["a", "b"]`, `vec!["a", "b"]`, `extend(["a", "b"])`, consts;
    # not `&["t", "x"]`, the column headers of CSV files passed to their reader.
    for m in re.finditer(r'(?<!&)\[((?:\s*"' + KEY + r'"\s*,)+\s*"' + KEY + r'"\s*,?\s*)\]', text):
        keys.update(re.findall(r'"(' + KEY + r')"', m.group(1)))
    return keys


def code_keys():
    keys = set()
    for f in sorted((ROOT / "src/scenario").rglob("*.rs")):
        # Comments hold examples of values (`line_type = ["wire", "chain"]`), not keys.
        text = re.sub(r"//.*", "", f.read_text(encoding="utf-8"))
        keys |= serde_keys(text) | table_keys(text)
    for rel in SERDE_FILES:
        keys |= serde_keys((ROOT / rel).read_text(encoding="utf-8"))
    return keys


def documented_keys(path):
    """Backticked names in the first column of the Markdown tables of `path`."""
    keys = set()
    in_code = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            in_code = not in_code
        if in_code or not line.startswith("|") or re.match(r"^\|[\s:|-]+\|?$", line):
            continue
        first = line.split("|")[1]
        keys.update(k for k in re.findall(r"`([^`]+)`", first) if re.fullmatch(KEY, k))
    return keys


def check_keys(problems):
    reference = ROOT / "docs/src/scenario.md"
    code = code_keys()
    listed = documented_keys(reference)
    anywhere = set()
    for f in (ROOT / "docs/src").rglob("*.md"):
        anywhere |= documented_keys(f)
    for k in sorted(listed - code):
        problems.append(
            f"docs/src/scenario.md lists the key `{k}`, which src/scenario/ does not read"
        )
    for k in sorted(code - anywhere):
        problems.append(
            f"src/scenario/ reads the key `{k}`, which no table of the book lists "
            "(add it to docs/src/scenario.md with its unit and default)"
        )


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--book", default="docs/book", help="the built book (mdbook build docs)")
    args = ap.parse_args()
    problems = []
    check_outside(problems)
    check_markdown_links(
        problems, ["README.md", "BENCHMARKS.md", "benchmarks/history/BENCHMARKS-2026-12.md"]
    )
    check_book(problems, (ROOT / args.book))
    check_tables(problems, [ROOT / "README.md", *sorted((ROOT / "docs/src").rglob("*.md"))])
    check_keys(problems)
    for p in problems:
        print(p)
    if problems:
        print(f"check_docs: {len(problems)} problem(s)")
        return 1
    print("check_docs: ok (links resolve, nothing points outside, scenario keys match)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
