"""The message file: rqt_console's format (ConsoleWidget._handle_save_clicked / _handle_load_clicked): the header
`message;severity;node;stamp;topics;location`, values in double quotes joined by `;`, `"` written as `\\"`,
stamps secs.nsecs with 9 digits; a row the real one wrote loads; what we write reads back the same."""
import io

from hypothesis import given, settings
from hypothesis import strategies as st

from rqt_console.log_file import read_records, write_records
from rqt_console.log_record import SEVERITY_LABELS, LogRecord

# a file as rqt_console writes it: a quote in a message, a two-line message, two topics
REAL_FILE = (
    "message;severity;node;stamp;topics;location\n"
    '"Oh no! I hit the wall! (Clamping from [x=11.088889, y=5.544445])";"4";"/turtlesim";"1700000000.012345678";'
    '"/rosout,/turtle1/color_sensor,/turtle1/pose";"/tmp/turtlesim.cpp:Turtle::update:187"\n'
    '"said \\"hi\\"";"2";"/talker";"1700000001.000000001";"/chatter";"talker.py:talk:20"\n'
    '"first line\n'
    'second line";"8";"/n";"5.000000000";"";"x:y:1"\n'
)


def test_a_file_rqt_console_wrote_loads():
    records, skipped = read_records(io.StringIO(REAL_FILE))
    assert skipped == []
    assert records[0] == LogRecord(
        "Oh no! I hit the wall! (Clamping from [x=11.088889, y=5.544445])",
        4,
        "/turtlesim",
        (1700000000, 12345678),
        ("/rosout", "/turtle1/color_sensor", "/turtle1/pose"),
        "/tmp/turtlesim.cpp:Turtle::update:187",
    )
    assert records[1].message == 'said "hi"' and records[1].stamp == (1700000001, 1)
    assert records[2].message == "first line\nsecond line" and records[2].topics == ()


def test_what_we_write_is_that_format():
    out = io.StringIO()
    records, _ = read_records(io.StringIO(REAL_FILE))
    write_records(records, out)
    assert out.getvalue() == REAL_FILE


def test_bad_rows_are_skipped_with_a_reason_and_a_wrong_header_refused():
    text = "message;severity;node;stamp;topics;location\n" '"m";"3";"/n";"1.0";"";"l"\n' '"m";"2";"/n";"1";"";"l"\n'
    records, skipped = read_records(io.StringIO(text))
    assert records == [] and len(skipped) == 2
    try:
        read_records(io.StringIO("a,b,c\n"))
    except ValueError as error:
        assert "not an rqt_console message file" in str(error)
    else:
        raise AssertionError("a file without the header was read")


text = st.text(st.characters(blacklist_categories=("Cs", "Cc"), blacklist_characters=";"), max_size=30)
records = st.builds(
    LogRecord,
    st.lists(text, min_size=1, max_size=3).map("\n".join),
    st.sampled_from(sorted(SEVERITY_LABELS)),
    text.map(lambda s: s.replace('"', "")),
    st.tuples(st.integers(0, 2**32 - 1), st.integers(0, 999999999)),
    st.lists(st.from_regex(r"\A/[a-z_]{1,8}\Z"), max_size=3).map(tuple),
    st.from_regex(r"\A[a-z_./]{1,10}:[a-z_]{1,8}:[0-9]{1,4}\Z"),
)


@settings(max_examples=200, deadline=None)
@given(st.lists(records, max_size=5))
def test_save_load_round_trip(saved):
    # ';' in a value and a message line ending in a backslash are ambiguous in this format (as in rqt_console's)
    saved = [r for r in saved if not any(line.endswith("\\") for line in r.message.split("\n"))]
    out = io.StringIO()
    assert write_records(saved, out) == len(saved)
    loaded, skipped = read_records(io.StringIO(out.getvalue()))
    assert skipped == [] and loaded == saved
