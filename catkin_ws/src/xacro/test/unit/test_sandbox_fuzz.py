"""Property-based tests of the xacro drop-in's sandbox (issue #26): generated `${...}` and `$(eval ...)` expressions,
from xacro's documented language and from what would escape it (lambdas, comprehensions, dunder attributes, calls of
open/exec/__import__, huge powers and repetitions, deep nesting), each of which would write a marker file if it
ran. Whatever the expression: it is evaluated or refused with an error within 100 times the time of 100 evaluations
of a plain expression (measured in the same run); the marker is never written and nothing else appears in the
scratch folder; an expression the sandbox evaluates gives what PyPI's xacro gives.

CI runs a bounded number of examples with a fixed seed; scripts/fuzz_sim.sh runs many more
(TURTLE_SIM_FUZZ_EXAMPLES, TURTLE_SIM_FUZZ_SEED)."""
from __future__ import annotations

import math
import os
import sys
from pathlib import Path

import pytest
from hypothesis import event, given
from hypothesis import strategies as st
from workspace_testing.fuzz import fuzz
from workspace_testing.timing import assert_within, best_seconds, timed

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
if (PACKAGE_ROOT / "CATKIN_IGNORE").exists():  # scripts/lib/dropins.py: the system's xacro is used here
    pytest.skip("the drop-in is ignored", allow_module_level=True)
sys.path.insert(0, str(PACKAGE_ROOT / "src"))

import xacro_dropin  # noqa: E402
from xacro_dropin import sandbox  # noqa: E402

ANSWER_WITHIN_REFERENCES = 100  # an answer may take this many times 100 evaluations of a plain expression
MARK = "MARK"  # the file a hostile piece writes in the working directory if it runs

numbers = st.one_of(
    st.integers(min_value=-100, max_value=100).map(str),
    st.floats(min_value=-1e3, max_value=1e3).map(lambda v: repr(0.0 if abs(v) < sys.float_info.min else v)),
    st.sampled_from(["1e308", "1e-320", "10**6", "2**64", "0", "-0.0", "float('nan')", "float('inf')"]),
)
atoms = st.one_of(
    numbers,
    st.sampled_from(["pi", "wheel", "name", "True", "False", "None", "'link'", "'a_b'", "[1, 2]", "(1,)", "{'k': 2}"]),
    st.sampled_from(["radians(90)", "sin(0.5)", "sqrt(2)", "math.floor(2.5)", "python.len('ab')", "len([1])"]),
    st.sampled_from(["xacro.arg('width')", "'x'.upper()", "str(1)", "int('3')", "max(1, 2)", "abs(-2)"]),
)
hostile = st.sampled_from(
    [
        "(lambda: open('MARK', 'w'))()",
        "[open('MARK', 'w') for _ in [1]]",
        "{open('MARK', 'w') for _ in [1]}",
        "list(open('MARK', 'w') for _ in [1])",
        "open('MARK', 'w')",
        'exec(\'open("MARK", "w")\')',
        'list(map(exec, [\'open("MARK", "w")\']))',
        "__import__('os').system('touch MARK')",
        "().__class__.__base__.__subclasses__()",
        "getattr(1, 'real')",
        "python.vars(xacro)",
        "python.type(1).mro()",
        "'{0.__class__}'.format(1)",
        "10**10**10",
        "'a' * 10**12",
        "[1] * 10**9",
        "1 << 10**9",
        "range(10**12)",
        "'%0999999999d' % 1",
        "'x'.zfill(10**9)",
        "('x' * 10**6).replace('', 'y' * 10**6)",
        "sum(range(10**11))",
        "(x := 1)",
        "f'{1}'",
        "b'x'",
        "*[1]",
        "(" * 60 + "1" + ")" * 60,
        "-" * 500 + "1",
    ]
)
operators = st.sampled_from(["+", "-", "*", "/", "//", "%", "**", "<", "==", "!=", " and ", " or ", " in "])


def combine(children: st.SearchStrategy) -> st.SearchStrategy:
    return st.one_of(
        st.tuples(children, operators, children).map(lambda t: "(%s%s%s)" % t),
        children.map(lambda c: "(not %s)" % c),
        children.map(lambda c: "-(%s)" % c),
        st.tuples(children, children, children).map(lambda t: "(%s if %s else %s)" % t),
        st.tuples(children, children).map(lambda t: "[%s, %s][0]" % t),
        st.tuples(
            st.sampled_from(["max", "min", "abs", "str", "float", "round", "len", "sorted", "python.sum"]), children
        ).map(lambda t: "%s(%s)" % t),
    )


expressions = st.recursive(st.one_of(atoms, atoms, atoms, hostile), combine, max_leaves=8)


@pytest.fixture(scope="module")
def pypi():
    """PyPI's xacro, its upstream safe_eval kept for comparison, then sandboxed as the drop-in's command runs it."""
    xacro = xacro_dropin.import_pypi_xacro()
    from xacro import substitution_args

    upstream = xacro.safe_eval
    sandbox.sandbox_xacro(xacro, substitution_args)
    yield xacro, substitution_args, upstream


def symbols(xacro):
    table = xacro.Table(xacro._global_symbols)
    for name, value in (("wheel", "0.033"), ("name", "'base'")):
        table[name] = value
    xacro.substitution_args_context["arg"] = {"width": "0.2"}
    return table


def answer(call):
    try:
        value = call()
        return ("value", repr(value) if not (isinstance(value, float) and math.isnan(value)) else "nan")
    except Exception as error:  # refused or failed: either is an answer
        return ("error", type(error).__name__)


@pytest.fixture(scope="module")
def reference_seconds(pypi):
    """A plain expression evaluated through the sandbox, 100 times: the machine's speed, measured in this run."""
    xacro = pypi[0]
    return best_seconds(lambda: [xacro.eval_text("${radians(90) * wheel + 1}", symbols(xacro)) for _ in range(100)])


def outcome(call, reference_seconds):
    result, seconds = timed(lambda: answer(call))
    assert_within(seconds, reference_seconds, ANSWER_WITHIN_REFERENCES, "an answer")
    return result


@fuzz(150)
@given(expression=expressions)
def test_generated_expressions_are_evaluated_as_upstream_or_refused_and_never_run_code(
    pypi, expression: str, tmp_path_factory, reference_seconds
) -> None:
    xacro, substitution_args, upstream = pypi
    scratch = tmp_path_factory.mktemp("xacro_fuzz")
    here = os.getcwd()
    os.chdir(str(scratch))
    xacro.filestack = [str(scratch / "fuzz.xacro")]
    try:
        sandboxed = outcome(lambda: xacro.eval_text("${%s}" % expression, symbols(xacro)), reference_seconds)
        evaluated = outcome(
            lambda: substitution_args.resolve_args("$(eval %s)" % expression, {"arg": {"wheel": "1"}}),
            reference_seconds,
        )
        assert os.listdir(str(scratch)) == [], os.listdir(str(scratch))
        event("${} %s, $(eval) %s" % (sandboxed[0], evaluated[0]))
        if sandboxed[0] == "value" and sandbox.refusal(expression) is None:
            # Allowed and bounded: upstream's eval (not sandboxed) gives the same.
            same = outcome(lambda: upstream(expression, symbols(xacro)), reference_seconds)
            assert same == sandboxed, (expression, same, sandboxed)
    finally:
        os.chdir(here)
