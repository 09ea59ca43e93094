"""read_md5sums reads the upstream md5sum tables the message packages' tests compare with."""
from pathlib import Path

import pytest

from workspace_testing.msg_md5 import read_md5sums


def test_lines_comments_and_blanks(tmp_path: Path) -> None:
    table = tmp_path / "upstream_md5sums.txt"
    table.write_text("# where they come from\n\nmsg/A 0123  # trailing note\nsrv/B 4567\n")
    assert read_md5sums(table) == {"msg/A": "0123", "srv/B": "4567"}


def test_a_line_of_three_words_is_an_error(tmp_path: Path) -> None:
    table = tmp_path / "upstream_md5sums.txt"
    table.write_text("msg/A 0123 extra\n")
    with pytest.raises(ValueError):
        read_md5sums(table)
