"""The workspace's Markdown stays readable: no table row over MAX_ROW characters (a row that long cannot be read,
reviewed or diffed; the reference it held belongs in a section of its own, as turtle_sim_ode's doc/ pages)."""
import os
import subprocess

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MAX_ROW = 400


def markdown_files():
    listing = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "*.md"],
        cwd=REPO,
        stdout=subprocess.PIPE,
        universal_newlines=True,
        check=True,
    ).stdout.split()
    return [name for name in listing if os.path.isfile(os.path.join(REPO, name))]


def long_rows(text, limit=MAX_ROW):
    """(line number, length) of each table row (a line starting with '|') longer than ``limit`` characters."""
    return [
        (number, len(line.strip()))
        for number, line in enumerate(text.splitlines(), 1)
        if line.lstrip().startswith("|") and len(line.strip()) > limit
    ]


def test_long_rows_are_found():
    table = "| a | b |\n|---|---|\n| " + "x" * 401 + " |\nprose " + "y" * 500 + "\n"
    assert long_rows(table) == [(3, 405)]


def test_no_markdown_table_row_over_the_limit():
    files = markdown_files()
    assert any(name.endswith("README.md") for name in files)
    found = []
    for name in files:
        with open(os.path.join(REPO, name), encoding="utf-8") as handle:
            found += ["%s:%d (%d characters)" % (name, line, length) for line, length in long_rows(handle.read())]
    assert not found, "table rows over %d characters: %s" % (MAX_ROW, ", ".join(found))
