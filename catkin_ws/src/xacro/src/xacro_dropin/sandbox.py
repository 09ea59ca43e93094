"""A sandbox for xacro's expressions: `${...}` (and so `xacro:property` values and macro params, which xacro evaluates
the same way), `$(eval ...)` and yaml unit tags.

PyPI's xacro evaluates them with Python's eval() and refuses only names that begin with `__` among the expression's
own top-level names; a lambda, a comprehension or a string handed to a builtin hides anything from that check, and
`$(eval)` runs with every builtin. Here an expression is parsed first and allowed only if every piece of it is in
xacro's documented language (wiki.ros.org/xacro, "Math expressions"): literals (numbers, strings, True/False/None,
lists, tuples, dicts, sets), names of properties and args, arithmetic, comparisons, `and`/`or`/`not`,
`a if c else b`, indexing and slicing, attribute access to names not beginning with `_` (namespaces such as `math.pi`,
`xacro.arg`, yaml dictionaries), and calls of the functions xacro exposes (math's, the few builtins it lists,
`xacro.*`) and of the pure methods of strings, lists and dictionaries. Everything else (lambda, comprehensions,
generator expressions, `:=`, f-strings, starred arguments, names and attributes beginning with `_`, calls of
anything else) is refused with a SandboxError naming the file, the expression and the construct. An allowed
expression is then evaluated with no builtins but those listed, and with `**`, `*`, `<<` and `range` bounded so that
no expression can take the machine's memory or minutes of its time (`10**10**10`, `'a' * 10**12`, `'%0999999999d' % 1`).
"""
from __future__ import annotations

import ast
import math
import re
from typing import Callable, Dict, Optional

# The builtins xacro 2.x exposes (globally or under `python.`), less those that reach beyond values: `type`, `vars`,
# `hash` and `isinstance`/`issubclass` hand out classes and object internals.
ALLOWED_BUILTINS = {
    name: getattr(__import__("builtins"), name)
    for name in (
        "list", "dict", "map", "len", "str", "float", "int", "bool", "min", "max", "round", "abs", "all", "any",
        "complex", "divmod", "enumerate", "filter", "frozenset", "ord", "repr", "reversed", "slice", "set", "sum",
        "tuple", "zip", "sorted", "chr",
    )
}  # fmt: skip
ALLOWED_FUNCTIONS = set(ALLOWED_BUILTINS) | {"range"} | {name for name in dir(math) if not name.startswith("_")}
# Methods of str, list, tuple and dict whose results are no larger than what they are called on (no format/format_map:
# they reach attributes by text; no join, replace, center, ljust, rjust or zfill: they multiply sizes).
ALLOWED_METHODS = {
    "capitalize", "casefold", "count", "endswith", "find", "index", "isalnum", "isalpha", "isdigit", "islower",
    "isnumeric", "isspace", "isupper", "lower", "lstrip", "partition", "rfind", "rindex", "rpartition", "rsplit",
    "rstrip", "split", "splitlines", "startswith", "strip", "swapcase", "title", "upper", "get", "keys", "values",
    "items", "copy",
}  # fmt: skip
# Namespaces whose every public member may be called: xacro's own (xacro.arg, xacro.load_yaml, ...) and math; of
# `python.` only the builtins above.
CALLABLE_NAMESPACES = {"xacro", "math"}
# Attributes that lead from a value to running code or to the interpreter's state, though they begin with no '_'.
REFUSED_ATTRIBUTES = {
    "gi_frame", "gi_code", "cr_frame", "cr_code", "ag_frame", "ag_code", "f_globals", "f_locals", "f_builtins",
    "f_back", "f_code", "tb_frame", "tb_next", "func_globals", "mro", "format", "format_map",
}  # fmt: skip
MAX_EXPRESSION_CHARS = 10000

_NODES = (
    ast.Expression, ast.Constant, ast.Name, ast.Load, ast.Tuple, ast.List, ast.Dict, ast.Set, ast.BinOp,
    ast.UnaryOp, ast.BoolOp, ast.Compare, ast.IfExp, ast.Subscript, ast.Slice, ast.Attribute, ast.Call,
    ast.keyword, ast.operator, ast.unaryop, ast.boolop, ast.cmpop,
)  # fmt: skip
# Python 3.8 spells these in the tree as well (ast.Index and friends, ast.Num/Str/NameConstant are Constant there).
_NODES += tuple(getattr(ast, name) for name in ("Index", "ExtSlice") if hasattr(ast, name))
_NAMED = {
    ast.Lambda: "a lambda",
    ast.ListComp: "a list comprehension",
    ast.SetComp: "a set comprehension",
    ast.DictComp: "a dict comprehension",
    ast.GeneratorExp: "a generator expression",
    ast.JoinedStr: "an f-string",
    ast.Starred: "a starred argument",
    ast.Await: "await",
}
if hasattr(ast, "NamedExpr"):
    _NAMED[ast.NamedExpr] = "an assignment expression (:=)"


# The largest results the bounded operations make: far beyond any robot description's numbers and strings.
MAX_POWER_BITS = 65536
MAX_SEQUENCE_ITEMS = 1_000_000
# A %-format's width or precision beyond this many digits would make a huge string ('%0999999999d' % 1).
MAX_FORMAT_WIDTH_DIGITS = 6
MAX_RANGE = 1_000_000
_GUARD = "_xacro_sandbox_operation"  # its name begins with '_': no checked expression can name it


class SandboxError(Exception):
    """An expression the sandbox does not evaluate; the message names the file, the expression and why."""


def _called_name(function: ast.expr) -> Optional[str]:
    """Why a call of ``function`` is refused, or None if it is allowed."""
    if isinstance(function, ast.Name):
        return None if function.id in ALLOWED_FUNCTIONS else "a call of '%s'" % function.id
    if isinstance(function, ast.Attribute):
        owner = function.value
        if isinstance(owner, ast.Name) and owner.id in CALLABLE_NAMESPACES:
            return None
        if isinstance(owner, ast.Name) and owner.id == "python" and function.attr in ALLOWED_FUNCTIONS:
            return None
        if function.attr in ALLOWED_METHODS:
            return None
        return "a call of method '%s'" % function.attr
    return "a call of a computed function"


def refusal(expression: str) -> Optional[str]:
    """Why ``expression`` is not evaluated (a construct named in words), or None if the sandbox allows it."""
    if len(expression) > MAX_EXPRESSION_CHARS:
        return "longer than %d characters" % MAX_EXPRESSION_CHARS
    try:
        tree = ast.parse(expression.strip(), mode="eval")
    except SyntaxError as error:
        return "not a Python expression (%s)" % error.msg
    except (ValueError, MemoryError, RecursionError) as error:  # NUL bytes, absurd nesting
        return "not a Python expression (%s)" % type(error).__name__
    nodes = list(ast.walk(tree))
    for node in nodes:  # the constructs first, then names, then calls: the message names the outermost fault
        if isinstance(node, tuple(_NAMED)):
            return next(words for kind, words in _NAMED.items() if isinstance(node, kind))
        if not isinstance(node, _NODES):
            return "a %s" % type(node).__name__
        if isinstance(node, ast.Constant) and isinstance(node.value, bytes):
            return "a bytes literal"
    for node in nodes:
        if isinstance(node, ast.Name) and node.id.startswith("_"):
            return "the name '%s' (names beginning with '_' are refused)" % node.id
        if isinstance(node, ast.Attribute) and (node.attr.startswith("_") or node.attr in REFUSED_ATTRIBUTES):
            return "the attribute '%s'" % node.attr
    for node in nodes:
        if isinstance(node, ast.Call):
            why = _called_name(node.func)
            if why is not None:
                return why
    return None


def check(expression: str, filename: str) -> None:
    """SandboxError naming ``filename`` and ``expression`` if the sandbox refuses it."""
    why = refusal(expression)
    if why is not None:
        shown = expression if len(expression) <= 200 else expression[:200] + "..."
        raise SandboxError(
            "in file %s: expression '%s' refused: %s is outside xacro's expression language (the xacro drop-in "
            "evaluates literals, properties, arithmetic, comparisons and xacro's functions only)"
            % (filename, shown, why)
        )


def _bounded(operation: str, left: object, right: object) -> object:
    """``left ** right``, ``left * right``, ``left % right`` or ``left << right``, refused (SandboxError) where the result would be
    huge; otherwise exactly what Python gives."""
    if operation == "pow":
        if isinstance(left, int) and isinstance(right, int) and abs(left) > 1 and right > 0:
            if right * max(abs(left).bit_length() - 1, 1) > MAX_POWER_BITS:
                raise SandboxError("%d ** %d is too large to evaluate" % (left, right))
        return left**right  # type: ignore[operator]
    if operation == "mod":
        if isinstance(left, str) and re.search(r"\d{%d,}" % (MAX_FORMAT_WIDTH_DIGITS + 1), left):
            raise SandboxError("a %%-format with a width of more than %d digits is too large" % MAX_FORMAT_WIDTH_DIGITS)
        return left % right  # type: ignore[operator]
    if operation == "lshift":
        if isinstance(right, int) and right > MAX_POWER_BITS:
            raise SandboxError("a shift by %d bits is too large to evaluate" % right)
        return left << right  # type: ignore[operator]
    for sequence, count in ((left, right), (right, left)):
        if isinstance(sequence, (str, list, tuple)) and isinstance(count, int):
            if len(sequence) * count > MAX_SEQUENCE_ITEMS:
                raise SandboxError("a sequence repeated %d times is too large to evaluate" % count)
    return left * right  # type: ignore[operator]


def bounded_range(original: Callable = range) -> Callable:
    """``original`` (range, or xacro's wrapper of it), refused beyond MAX_RANGE items."""

    def bounded(*arguments: int) -> range:
        if len(range(*arguments)) > MAX_RANGE:
            raise SandboxError("range%r has more than %d items" % (arguments, MAX_RANGE))
        return original(*arguments)

    return bounded


class _Bounded(ast.NodeTransformer):
    """`a ** b`, `a * b`, `a % b`, `a << b` as calls of _bounded."""

    OPERATIONS = {ast.Pow: "pow", ast.Mult: "mult", ast.Mod: "mod", ast.LShift: "lshift"}

    def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
        self.generic_visit(node)
        operation = self.OPERATIONS.get(type(node.op))
        if operation is None:
            return node
        call = ast.Call(ast.Name(_GUARD, ast.Load()), [ast.Constant(operation), node.left, node.right], [])
        return ast.copy_location(call, node)


def sandboxed_eval(
    expression: str,
    symbols: Dict,
    local_symbols: Optional[object] = None,
    filename: str = "?",
    builtins: Optional[Dict] = None,
) -> object:
    """``expression`` evaluated with ``symbols`` (and ``local_symbols``) after ``check``, with ``builtins`` only."""
    check(expression, filename)
    tree = ast.fix_missing_locations(_Bounded().visit(ast.parse(expression.strip(), mode="eval")))
    code = compile(tree, "<expression>", "eval")
    # As upstream, not through a symbol table's own __setitem__ (which would warn of a redefined symbol).
    dict.update(symbols, {"__builtins__": builtins or {}, _GUARD: _bounded})
    return eval(code, symbols, local_symbols)  # noqa: S307 - the tree was checked above


def sandbox_xacro(xacro, substitution_args) -> None:
    """Make PyPI's xacro evaluate every `${...}` and `$(eval ...)` in the sandbox (``xacro``: the library's top
    module, whose safe_eval the expressions go through; ``substitution_args``: its module of `$(...)`)."""
    sa = substitution_args
    needed = ("_DictWrapper", "_eval_arg", "_eval_dirname", "_eval_dict", "convert_value")
    if not callable(getattr(xacro, "safe_eval", None)) or not all(hasattr(sa, name) for name in needed):
        raise RuntimeError(
            "%s has no safe_eval/_eval to replace: not the PyPI xacro this drop-in was written for" % xacro
        )

    def current_file() -> str:
        stack = getattr(xacro, "filestack", None) or ["?"]
        return str(stack[-1])

    def safe_eval(expr: str, globals: Dict, locals: Optional[Dict] = None) -> object:
        """`${...}`: upstream gives it no builtins at all (its names come from the symbol table); nor does this."""
        return sandboxed_eval(expr, globals, locals, current_file())

    def eval_substitution(text: str, context: Dict) -> str:
        """`$(eval ...)` as upstream's _eval evaluates it (args, `arg()`, `dirname()`, `find()`, `env()`, math),
        but with ALLOWED_BUILTINS for builtins instead of all of Python's."""
        context.setdefault("arg", {})
        functions = {
            "arg": lambda name: sa.convert_value(sa._eval_arg(name, args=context["arg"]), "auto"),
            "dirname": lambda: sa._eval_dirname(context["filename"]),
        }
        functions.update(sa._eval_dict)
        names = sa._DictWrapper(context["arg"], functions)
        builtins = dict(ALLOWED_BUILTINS, range=bounded_range())
        return str(sandboxed_eval(text, {}, names, context.get("filename") or current_file(), builtins))

    xacro.safe_eval = safe_eval
    sa._eval = eval_substitution
    symbols = xacro._global_symbols  # range as xacro exposes it (directly and as python.range), bounded
    for table in (symbols, symbols.get("python", {})):
        if "range" in table:
            dict.__setitem__(table, "range", bounded_range(dict.__getitem__(table, "range")))
