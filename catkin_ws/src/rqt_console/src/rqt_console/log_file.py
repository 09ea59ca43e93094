"""rqt_console's message file (.csv), without Qt: a header line `message;severity;node;stamp;topics;location`,
then one row a message, each value in double quotes, values separated by `;`; a `"` inside a message is written
`\\"`, the stamp as secs.nsecs (9 digits), topics comma-separated, severity as the Log level number. A message with
line breaks spans several lines. Format as rqt_console's ConsoleWidget._handle_save_clicked writes and
_handle_load_clicked reads it."""
from __future__ import annotations

from typing import Iterable, List, TextIO, Tuple

from .log_record import SEVERITY_LABELS, LogRecord

FILE_COLUMNS = ("message", "severity", "node", "stamp", "topics", "location")


def write_records(records: Iterable[LogRecord], stream: TextIO) -> int:
    """Writes the records; returns how many."""
    stream.write(";".join(FILE_COLUMNS) + "\n")
    count = 0
    for record in records:
        values = (
            record.message.replace('"', '\\"'),
            str(record.severity),
            record.node,
            "%d.%09d" % record.stamp,
            ",".join(record.topics),
            record.location,
        )
        stream.write(";".join('"%s"' % value for value in values) + "\n")
        count += 1
    return count


def _joined_rows(lines: List[str]) -> List[str]:
    """The rows with their quotes stripped, a message's wrapped lines joined again with line breaks."""
    rows: List[str] = []
    open_row = False
    for line in lines:
        if not open_row:
            if not line.startswith('"'):
                continue  # not a row of this format
            line = line[1:]
            rows.append("")
        else:
            rows[-1] += "\n"
        closes = line.endswith('"') and not line.endswith('\\"')
        rows[-1] += line[:-1] if closes else line
        open_row = not closes
    return rows


def read_records(stream: TextIO) -> Tuple[List[LogRecord], List[str]]:
    """The records of a file and the reasons rows were skipped. Raises ValueError if the header is missing."""
    lines = stream.read().splitlines()
    if not lines or any(column not in FILE_COLUMNS for column in lines[0].split(";")):
        raise ValueError("not an rqt_console message file: the first line must be %s" % ";".join(FILE_COLUMNS))
    columns = lines[0].split(";")
    records, skipped = [], []
    for row in _joined_rows(lines[1:]):
        values = dict(zip(columns, row.split('";"')))
        if len(values) != len(columns):
            skipped.append("%d values where %d columns are: %s" % (len(row.split('";"')), len(columns), row))
            continue
        try:
            severity = int(values.get("severity", "2"))
            secs, nsecs = values.get("stamp", "0.0").split(".")
            stamp = (int(secs), int(nsecs))
        except ValueError:
            skipped.append("unreadable severity or stamp: %s" % row)
            continue
        if severity not in SEVERITY_LABELS:
            skipped.append("unknown severity value: %d" % severity)
            continue
        topics = values.get("topics", "")
        records.append(
            LogRecord(
                values.get("message", "").replace('\\"', '"'),
                severity,
                values.get("node", ""),
                stamp,
                tuple(topics.split(",")) if topics else (),
                values.get("location", ""),
            )
        )
    return records, skipped
