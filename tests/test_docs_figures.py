"""Every time or speed in README.md and docs/*.md names the run that measured it.

CONTRIBUTING's rule: figures are measured, not remembered; each names its run (the issue
"every figure in README and docs names its run").  A figure here is a duration (ms, s,
minutes, hours, CPU-s, core-seconds), a rate (faces/s, ...), a speed ratio ("~60x faster",
"4.5 times faster") or a cell of a table with a time column.  Its paragraph or its section
(the text under its heading, with the introductions of the headings above it) must hold a
commit that git resolves (7 to 40 hex digits) and a run name: a command (backquoted or in a
code block), the word "benchmark", or the generated stamp "*Measured ...*".

Not figures, and not scanned: code blocks and inline code (commands with their settings,
README's illustrative output), settings and targets (timeouts, budgets, limits, defaults,
"every 10 s", "< 10 s" goals, hangs reported as "> 60 s") and docs/errata.md (by the
issue's scope).  performance.md's Targets table is scanned like the rest: each of its rows
names the commit and date of the run that measured it (`benchmarks/report.py`).
"""

from __future__ import annotations

import itertools
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXCLUDED_FILES = {"errata.md"}
# (file, heading): sections not scanned (none today; the Targets table names its runs)
EXCLUDED_SECTIONS: set[tuple[str, str]] = set()

_NUM = r"\d[\d,]*(?:\.\d+)?"
_RANGE = rf"{_NUM}(?:\s?(?:-|to|and)\s?{_NUM})?"
FIGURE = re.compile(
    rf"(?<![\w.^/*+-])~?(?:{_RANGE}\s?(?:ms|µs|s|secs?|seconds?|min|minutes?|hours?|"
    rf"CPU-s|CPU seconds|core-seconds)\b(?![-/]\w)"
    rf"|{_NUM}\s?(?:faces|flips|examples|checks)/s\b"
    rf"|{_RANGE}\s?(?:x|×|times)\s(?:faster|slower|the speed|the time)\b)"
    r"|\b(?:under|over|about|in|takes?|took|is)\s(?:a|an|half an?)\s(?:second|minute|hour)\b")
# settings and goals, not measurements: a figure right after one of these words ...
SETTING_RIGHT_BEFORE = re.compile(
    r"(?:\bat most|\bat least|[<>]=?|[≤≥]|\bno task over|\btarget|\bevery|\bdefault|"
    r"\blimit|\bbudget|\bload average)\W{0,3}$", re.I)
# ... or within 40 characters after one of these (in its sentence) ...
SETTING_NEAR_BEFORE = re.compile(r"\b(?:timeouts?|budget|limit|killed|stopped after)\b", re.I)
# ... or followed closely by one of these
SETTING_AFTER = re.compile(r"^[^.;]{0,12}?\b(?:timeout|budget|limit|shrinking|of wall clock|"
                           r"after the run ended)\b", re.I)
# a table whose header names a time column: each of its rows holds figures
TIME_COLUMN = re.compile(r"\bseconds?\b|\bs\b|/s\b|\bwall\b", re.I)
COMMIT = re.compile(r"(?<![\w/.-])[0-9a-f]{7,40}(?![\w-])")
_COMMAND = r"(?:[A-Z_]+=\S+ )*(?:python3?|ddg-oracle|pytest|bash|nice|\.ci/run)(?=[ `])"
# a command in backquotes or on a line of a code block, or the benchmarks' own words
RUN_NAME = re.compile(rf"`{_COMMAND}[^`]*`|^\s*{_COMMAND}|\bbenchmarks?\b|\*Measured\b", re.M)


def _documents() -> list[Path]:
    return [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").glob("*.md")
                                         if p.name not in EXCLUDED_FILES)


def _paragraphs(lines: list[str]):
    """(first line index, last line index) of each paragraph outside code blocks: its
    durations are commands' settings and illustrative output, not measurements."""
    block, fenced = [], False
    for i, line in enumerate(lines + [""]):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        elif not fenced and line.strip() and not line.startswith("    "):
            block.append(i)
            continue
        if block:
            yield block[0], block[-1]
        block = []


def _is_setting(text: str, start: int, end: int) -> bool:
    before = text[max(0, start - 40):start].rsplit(". ", 1)[-1]
    return bool(SETTING_RIGHT_BEFORE.search(before) or SETTING_NEAR_BEFORE.search(before)
                or SETTING_AFTER.search(text[end:end + 40]))


def _figures(path: Path):
    """(line number, figure, context) for every figure of a document; the context is the
    figure's paragraph, its section and the introductions of the headings above it."""
    raw = path.read_text(encoding="utf-8").splitlines()
    fenced, headings = False, []          # (line index, level), outside code blocks
    for i, line in enumerate(raw):
        fenced ^= line.lstrip().startswith("```")
        if not fenced and (m := re.match(r"(#+) ", line)):
            headings.append((i, len(m[1])))
    for first, last in _paragraphs(raw):
        above = [(j, lvl) for j, lvl in headings if j <= first]
        if above and (path.name, raw[above[-1][0]].strip()) in EXCLUDED_SECTIONS:
            continue
        text = "\n".join(raw[first:last + 1])
        # inline code is a command or a name: blanked, keeping offsets, to find figures
        blank = re.sub(r"`[^`]*`", lambda m: re.sub(r"[^\n]", " ", m[0]), text)
        found = [(first + text.count("\n", 0, m.start()), m[0].strip())
                 for m in FIGURE.finditer(blank) if not _is_setting(text, m.start(), m.end())]
        if raw[first].startswith("|") and TIME_COLUMN.search(raw[first]):
            found += [(i, raw[i][:50]) for i in range(first + 2, last + 1)
                      if raw[i].startswith("|")]
        if not found:
            continue
        context = [text]
        level = 99          # its section, then each enclosing heading's text up to the next
        for j, lvl in reversed(above):
            if lvl < level:
                after = first if level == 99 else j
                context.append("\n".join(raw[j:next((k for k, _ in headings if k > after),
                                                      len(raw))]))
                level = lvl
        if not above or above[0][1] > 1:     # the text before the first heading
            context.append("\n".join(raw[:headings[0][0] if headings else len(raw)]))
        for line, figure in found:
            yield line + 1, figure, "\n".join(context)


def _commits(tokens: set[str]) -> set[str]:
    """The tokens git resolves to a commit (all of them without a .git directory)."""
    if not (ROOT / ".git").exists() or not tokens:
        return tokens
    names = sorted(tokens)
    out = subprocess.run(["git", "cat-file", "--batch-check"], cwd=ROOT, capture_output=True,
                         text=True, input="".join(f"{t}^{{commit}}\n" for t in names),
                         check=True).stdout.splitlines()
    return {t for t, line in zip(names, out) if line.split()[1:2] == ["commit"]}


def test_the_scan_finds_figures_and_skips_settings():
    # figures the docs hold, and settings beside them the scan must not take for figures
    assert FIGURE.search("checks in 42.1 s on 2 cores")
    assert FIGURE.search("took 386 s / 592 CPU-s")
    assert FIGURE.search("241,819 faces/s")
    assert FIGURE.search("(~15x and ~150x faster;")
    assert FIGURE.search("in 15 to 24 s over five runs")
    for setting in ("with a 3 s timeout", "the default limit (120 s)", "< 10 s",
                    "a progress line every 10 s", "hangs (> 60 s)", "budget: 18 s, 10 s shrinking"):
        assert all(_is_setting(setting, m.start(), m.end()) for m in FIGURE.finditer(setting))
    measured = "at a923bdf: 136 meshes of at most 20,000 faces in 863 s"
    assert [m[0] for m in FIGURE.finditer(measured)
            if not _is_setting(measured, m.start(), m.end())] == ["863 s"]


def test_every_figure_names_its_run():
    figures = [(p, *f) for p in _documents() for f in _figures(p)]
    assert len(figures) > 100         # the scan still sees the docs' figures
    # the figures of one paragraph share its context: judge each context once
    contexts = {context: set(COMMIT.findall(context)) for *_, context in figures}
    commits = _commits(set().union(*contexts.values()))
    lacks = {context: [what for what, ok in (
        ("a commit git resolves", tokens & commits),
        ("a run name (a command, 'benchmark' or '*Measured')",
         RUN_NAME.search(context))) if not ok] for context, tokens in contexts.items()}
    missing = [f"{path.relative_to(ROOT)}:{line}: {figure!r} names no run: lacks "
               + " and ".join(lacks[context])
               for path, line, figure, context in sorted(figures, key=lambda f: f[:2])
               if lacks[context]]
    assert not missing, "\n".join(missing)


def test_each_row_of_a_table_with_a_run_column_names_its_commit():
    """performance.md's Targets table gathers figures of many runs: each row names its own
    (a table is one paragraph for the scan above, which one commit anywhere satisfies)."""
    tables = 0
    for path in _documents():
        raw = path.read_text(encoding="utf-8").splitlines()
        for i, line in enumerate(raw):
            if not (line.startswith("|") and re.search(r"\|\s*run\s*\|\s*$", line)):
                continue
            tables += 1
            rows = list(itertools.takewhile(lambda r: r.startswith("|"), raw[i + 2:]))
            assert rows, f"{path.name}:{i + 1}: a table without rows"
            for r in rows:
                run = r.rstrip(" |").rsplit("|", 1)[-1]
                assert _commits(set(COMMIT.findall(run))), \
                    f"{path.name}: a row names no commit that git resolves: {r[:80]}"
    assert tables, "no table with a run column: performance.md's Targets table has one"
