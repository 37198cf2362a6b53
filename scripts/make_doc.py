#!/usr/bin/env python3
"""The guide as HTML, and its checks (`make doc`; tests/test_doc.sh).

  /usr/bin/python3 scripts/make_doc.py [--check] [--out build/doc] [--root .]

Pages: README.md, CHANGELOG.md and every doc/**/*.md. Without --check, each page is rendered to
<out>/<same path>.html (Python-Markdown: tables, fenced code; headings get GitHub's anchors, so a
link that works on the repository's web view works here), links to a page become links to its
.html, the figures of doc/figures are copied beside their pages, and a link to another file of the
repository (a case, a script) points back into the source tree.

Checked, with --check or without (the exit status is 1 if any fails, one line per fault):
  - every relative link and image of every page names a file that exists;
  - every anchor (page.md#anchor, #anchor) names a heading of that page;
  - the rendered HTML again: every href and src resolves, every fragment is an id of its page;
  - every figure in doc/figures is shown by some page (an unused figure is a stale one);
  - a file of the repository that a guide page names in code (`cases/...`, `scripts/...`, `src/...`,
    `tests/...`, `include/...`) exists, unless the name is a pattern (`*`, `<t>`, NAME, N);
  - a page of the guide (doc/*.md, README.md) has at most MAX_LINES lines, no table cell longer
    than MAX_CELL characters (a link's target included), and no date but in a
    table row or a measurement's provenance line ("Measured ... on <date>: <machine>"): history
    belongs to CHANGELOG.md and doc/notes/;
  - every option the code registers is in doc/reference/options.md with a description
    (scripts/options_reference.py --check, skipped with --no-options, which needs bin/atrito).
"""
import argparse
import html
import os
import re
import shutil
import subprocess
import sys

LINK = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
EXTERNAL = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")
DATE = re.compile(r"\b20[0-9]{2}-[01][0-9]-[0-3][0-9]\b")
MAX_LINES = 300
REPO_PATH = re.compile(r"`((?:cases|scripts|src|tests|include)/[A-Za-z0-9_./-]+)`")
PATTERN = re.compile(r"[*<{\[]|(?<![A-Za-z])[A-Z]{1,5}(?![A-Za-z])")
MAX_CELL = 160  # characters of a table cell of the guide: a number or a few words, never a paragraph


def guide_page(p):
    """A page of the guide proper: not the history (CHANGELOG.md, doc/notes/) nor generated text."""
    return p == "README.md" or (p.startswith("doc" + os.sep) and os.sep not in p[4:])


def pages(root):
    out = [p for p in ("README.md", "CHANGELOG.md") if os.path.exists(os.path.join(root, p))]
    for d, _, files in os.walk(os.path.join(root, "doc")):
        for f in sorted(files):
            if f.endswith(".md"):
                out.append(os.path.relpath(os.path.join(d, f), root))
    return sorted(set(out))


def plain_heading(text):
    """The text GitHub slugs: inline markup removed (code spans keep their text, links their label)."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)
    out, pos = [], 0
    for m in CODE_SPAN.finditer(text):  # emphasis marks and tags outside code spans only
        out += [re.sub(r"<[^>]+>|\*\*|__|\*", "", text[pos:m.start()]), m.group(2)]
        pos = m.end()
    out.append(re.sub(r"<[^>]+>|\*\*|__|\*", "", text[pos:]))
    return html.unescape("".join(out)).strip()


def slug(text):
    """GitHub's heading anchor: lower case, punctuation but '-' and '_' dropped, spaces to '-'."""
    s = text.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s, flags=re.UNICODE)
    return s.replace(" ", "-")


def unique_slugs(texts):
    seen, out = {}, []
    for t in texts:
        s = slug(t)
        if s in seen:
            seen[s] += 1
            s = "%s-%d" % (s, seen[s])
        else:
            seen[s] = 0
        out.append(s)
    return out


def scan(path):
    """Headings (plain text) and links (line, is_image, target) of a markdown file, code excluded:
    fenced blocks, code spans, and indented blocks (four spaces after a blank line, outside a list)."""
    heads, links = [], []
    fenced = code = False
    prev_blank, in_list = True, False
    with open(path, encoding="utf-8") as fh:
        for n, line in enumerate(fh, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if fenced:
                continue
            blank = not line.strip()
            if line.startswith("    ") and not blank and (code or (prev_blank and not in_list)):
                code = True
                continue
            if not blank:
                code = False
                if re.match(r"^\s*([*+-]|\d+\.)\s", line):
                    in_list = True
                elif not line.startswith(" "):
                    in_list = False
            prev_blank = blank
            if blank:
                continue
            m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
            if m:
                heads.append(plain_heading(m.group(2)))
            bare = CODE_SPAN.sub("", line)
            for lm in LINK.finditer(bare):
                links.append((n, lm.group(1) == "!", lm.group(3)))
    return heads, links


def check_sources(root, names):
    errors = []
    scans = {p: scan(os.path.join(root, p)) for p in names}
    anchors = {p: set(unique_slugs(heads)) for p, (heads, _) in scans.items()}
    shown = set()
    for p in names:
        for line, image, target in scans[p][1]:
            if EXTERNAL.match(target):
                continue
            path, _, frag = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(p), path)) if path else p
            if path and not os.path.exists(os.path.join(root, dest)):
                errors.append("%s:%d: %s %s: no such file" % (p, line, "image" if image else "link", target))
                continue
            if image:
                shown.add(dest)
            if frag:
                if dest not in anchors:
                    if dest.endswith(".md"):
                        errors.append("%s:%d: link %s: page outside the guide" % (p, line, target))
                    continue
                if frag not in anchors[dest]:
                    errors.append("%s:%d: link %s: no heading with anchor #%s in %s" % (p, line, target, frag, dest))
    for p in names:
        if not guide_page(p):
            continue
        with open(os.path.join(root, p), encoding="utf-8") as fh:
            lines = fh.read().splitlines()
        if len(lines) > MAX_LINES:
            errors.append("%s: %d lines, more than %d for a page of the guide (move detail to doc/notes/)"
                          % (p, len(lines), MAX_LINES))
        for n, line in enumerate(lines, 1):
            for m in REPO_PATH.finditer(line):
                path = m.group(1).rstrip(".")
                if not PATTERN.search(path) and not os.path.exists(os.path.join(root, path)):
                    errors.append("%s:%d: %s: no such file in the repository" % (p, n, path))
            if line.lstrip().startswith("|"):
                cell = max(line.strip().strip("|").split("|"), key=len).strip()
                if len(cell) > MAX_CELL:
                    errors.append("%s:%d: a table cell of %d characters, more than %d (move the explanation below the table): %.50s..."
                                  % (p, n, len(cell), MAX_CELL, cell))
            if DATE.search(line) and not line.lstrip().startswith(("|", "Measured")):
                errors.append("%s:%d: a date outside a table (history goes to CHANGELOG.md or doc/notes/)" % (p, n))
    figdir = os.path.join(root, "doc", "figures")
    if os.path.isdir(figdir):
        for f in sorted(os.listdir(figdir)):
            if f.endswith((".png", ".svg", ".jpg")) and os.path.join("doc", "figures", f) not in shown:
                errors.append("doc/figures/%s: shown by no page" % f)
    return errors


# ------------------------------------------------------------------------------------ HTML build
STYLE = """body{max-width:60rem;margin:2rem auto;padding:0 1rem;font:16px/1.5 sans-serif;color:#222}
pre,code{font:14px monospace;background:#f4f4f4}pre{padding:.6rem;overflow-x:auto}
table{border-collapse:collapse;margin:1rem 0}td,th{border:1px solid #ccc;padding:.2rem .5rem}
th{background:#eee}img{max-width:100%}nav{font-size:14px;margin-bottom:1rem}"""


def build(root, names, out):
    import markdown
    from markdown.treeprocessors import Treeprocessor
    from markdown.extensions import Extension

    class Anchors(Treeprocessor):
        def run(self, doc):
            heads = [el for el in doc.iter() if el.tag in ("h1", "h2", "h3", "h4", "h5", "h6")]
            for el, s in zip(heads, unique_slugs(["".join(el.itertext()) for el in heads])):
                el.set("id", s)
            # a pipe escaped in a table's code span is a pipe (as on the repository's web view)
            for el in doc.iter("code"):
                if el.text and "\\|" in el.text:
                    el.text = type(el.text)(el.text.replace("\\|", "|"))

    class Links(Treeprocessor):
        page = ""

        def fix(self, target):
            if EXTERNAL.match(target) or target.startswith("#"):
                return target
            path, sep, frag = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(self.page), path))
            if dest in names:
                return os.path.relpath(dest[:-3] + ".html", os.path.dirname(self.page)) + sep + frag
            if dest.startswith(os.path.join("doc", "figures") + os.sep):
                return target  # copied beside the pages
            # another file of the repository: back into the source tree
            return os.path.relpath(os.path.join(root, dest), os.path.join(out, os.path.dirname(self.page))) + sep + frag

        def run(self, doc):
            for el in doc.iter():
                for attr in ("href", "src"):
                    if el.get(attr):
                        el.set(attr, self.fix(el.get(attr)))

    links = Links()

    class Guide(Extension):
        def extendMarkdown(self, md):
            md.treeprocessors.register(Anchors(md), "guide_anchors", 5)
            links.md = md
            md.treeprocessors.register(links, "guide_links", 4)

    md = markdown.Markdown(extensions=["tables", "fenced_code", Guide()])
    index = os.path.relpath("doc/README.md" if "doc/README.md" in names else "README.md")
    for p in names:
        links.page = p
        md.reset()
        with open(os.path.join(root, p), encoding="utf-8") as fh:
            body = md.convert(fh.read())
        heads, _ = scan(os.path.join(root, p))
        title = heads[0] if heads else p
        dest = os.path.join(out, p[:-3] + ".html")
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        home = os.path.relpath(index[:-3] + ".html", os.path.dirname(p))
        with open(dest, "w", encoding="utf-8") as fh:
            fh.write("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>%s</title>"
                     "<style>%s</style></head><body><nav><a href=\"%s\">the guide</a></nav>\n%s\n</body></html>\n"
                     % (html.escape(title), STYLE, home, body))
    fig = os.path.join(root, "doc", "figures")
    if os.path.isdir(fig):
        shutil.copytree(fig, os.path.join(out, "doc", "figures"), dirs_exist_ok=True)


def check_html(out):
    from html.parser import HTMLParser

    class P(HTMLParser):
        def __init__(self):
            super().__init__()
            self.ids, self.refs = set(), []

        def handle_starttag(self, tag, attrs):
            a = dict(attrs)
            if a.get("id"):
                self.ids.add(a["id"])
            for k in ("href", "src"):
                if a.get(k):
                    self.refs.append(a[k])

    parsed = {}
    for d, _, files in os.walk(out):
        for f in files:
            if f.endswith(".html"):
                p = os.path.join(d, f)
                h = P()
                with open(p, encoding="utf-8") as fh:
                    h.feed(fh.read())
                parsed[os.path.normpath(p)] = h
    errors = []
    for p, h in sorted(parsed.items()):
        for r in h.refs:
            if EXTERNAL.match(r):
                continue
            path, _, frag = r.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(p), path)) if path else p
            if not os.path.exists(dest):
                errors.append("%s: %s: no such file" % (os.path.relpath(p, out), r))
            elif frag and dest in parsed and frag not in parsed[dest].ids:
                errors.append("%s: %s: no element with id %s" % (os.path.relpath(p, out), r, frag))
    return errors


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--out", default=None, help="HTML folder (default <root>/build/doc)")
    ap.add_argument("--check", action="store_true", help="check the pages' links only, build nothing")
    ap.add_argument("--no-options", action="store_true", help="skip the options reference's check")
    a = ap.parse_args()
    root = os.path.abspath(a.root)
    os.chdir(root)
    names = pages(root)
    errors = check_sources(root, names)
    if not a.check:
        out = os.path.abspath(a.out or os.path.join(root, "build", "doc"))
        if os.path.isdir(out):
            shutil.rmtree(out)
        build(root, names, out)
        errors += check_html(out)
    if not a.no_options:
        r = subprocess.run([sys.executable, os.path.join(root, "scripts", "options_reference.py"), "--check"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            errors += ["doc/reference/options.md: " + l for l in (r.stdout + r.stderr).strip().splitlines()[-5:]]
    for e in errors:
        print("make_doc: " + e)
    n = len(names)
    if errors:
        print("make_doc: %d fault(s) in %d pages" % (len(errors), n))
        return 1
    print("make_doc: %d pages, links, anchors and figures checked%s" %
          (n, "" if a.check else ", HTML in " + os.path.relpath(out, root)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
