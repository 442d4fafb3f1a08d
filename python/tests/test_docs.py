"""Every ```python snippet of docs/python.md (and of docs/export.md), run as
written, with the outputs the page shows checked, so that the page cannot
drift from the package.

Each snippet runs on its own (a reader copies one at a time), from the
repository's root, so that its `examples/...` paths resolve as they do for
a reader there. Its top-level statements run one by one, and the comment
on a statement's lines says what it must do:

- `# -> VALUE ...`: the statement is an expression whose value equals VALUE,
  a Python literal (numbers, lists, tuples, dicts, strings, True, False,
  None), followed by any prose. Numbers are held to the digits shown: a
  number written with its last digit in the place 10^k matches within
  half of 10^k (so `0.569098` is 0.569098 +- 5e-7 and `2.466e-3` is
  2.466e-3 +- 5e-7). Arrays compare element by element; a dict has exactly
  the keys shown.
- `# warns NAME: TEXT`: the statement warns NAME (a flexure warning) and
  the message holds TEXT (up to an ellipsis `…`, when there is one).
- `# raises NAME: TEXT`: the statement raises NAME, whose message holds TEXT
  (up to `…`).

A statement with neither must not warn any flexure warning, so a warning the
page does not show fails too.
"""

import ast
import builtins
import io
import math
import re
import tokenize
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexure

ROOT = Path(__file__).resolve().parents[2]
# The pages whose snippets are run: python.md is the package's; export.md has one.
PAGES = ("python.md", "export.md")

_WARNINGS = (
    flexure.AccuracyWarning,
    flexure.StabilityWarning,
    flexure.YieldWarning,
    flexure.PreloadWarning,
    flexure.IntersectionWarning,
)


def snippets(page):
    """The ```python blocks of docs/`page`: (page, line of the fence, code)."""
    blocks = []
    lines = (ROOT / "docs" / page).read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```python":
            start = i + 1
            end = next(j for j in range(start, len(lines)) if lines[j].strip() == "```")
            blocks.append((page, start, "\n".join(lines[start:end]) + "\n"))
            i = end
        i += 1
    return blocks


def _comments(code):
    """{line number (1-based): [claim, ...]}: each line's comment, read by the tokenizer
    (so a `#` inside a string, such as a TOML comment, is not one), split at ` # `
    into one claim per part (`# -> 1.0  # warns AccuracyWarning` makes two)."""
    found = {}
    for tok in tokenize.generate_tokens(io.StringIO(code).readline):
        if tok.type == tokenize.COMMENT:
            found[tok.start[0]] = [part.strip() for part in tok.string[1:].split(" # ")]
    return found


def _literal(text):
    """The Python literal at the start of `text`, and its source: up to the bracket or quote
    that closes its first one, else up to the first space, comma, semicolon or colon."""
    text = text.strip()
    end = None
    if text[:1] in ("(", "[", "{"):
        depth, quote = 0, None
        for i, ch in enumerate(text):
            if quote:
                quote = None if ch == quote else quote
            elif ch in "'\"":
                quote = ch
            elif ch in "([{":
                depth += 1
            elif ch in ")]}":
                depth -= 1
                if depth == 0:
                    end = i + 1
                    break
    elif text[:1] in ("'", '"'):
        end = text.find(text[0], 1) + 1
    else:
        end = re.match(r"[^\s,;:]*", text).end()
    assert end, f"no Python literal at the start of {text!r}"
    source = text[:end]
    try:
        return ast.literal_eval(source), source
    except (ValueError, SyntaxError) as e:
        raise AssertionError(f"{source!r} is not a Python literal: {e}") from None


def _tolerances(source):
    """Half a unit in the last digit shown of each number of `source`, in order."""
    tolerances = []
    for m in re.finditer(r"(?<![\w.])[-+]?(\d+)(?:\.(\d*))?(?:[eE]([-+]?\d+))?", source):
        decimals = len(m.group(2) or "")
        exponent = int(m.group(3) or 0)
        tolerances.append(0.5 * 10.0 ** (exponent - decimals))
    return tolerances


def _matches(actual, expected, tolerances, where):
    """Whether `actual` equals `expected` to the digits shown; consumes `tolerances`."""
    if isinstance(expected, bool) or expected is None or isinstance(expected, str):
        assert actual == expected or (isinstance(actual, np.bool_) and bool(actual) == expected), (
            f"{where}: got {actual!r}, the page shows {expected!r}"
        )
        return
    if isinstance(expected, (int, float)):
        tol = tolerances.pop(0)
        value = float(actual)
        assert math.isfinite(value) and abs(value - expected) <= tol * (1 + 1e-9), (
            f"{where}: got {value!r}, the page shows {expected!r} (+- {tol:g})"
        )
        return
    if isinstance(expected, dict):
        assert isinstance(actual, dict), f"{where}: got {actual!r}, the page shows a dict"
        assert set(actual) == set(expected), f"{where}: keys {sorted(actual)}, the page shows {sorted(expected)}"
        for key, value in expected.items():
            _matches(actual[key], value, tolerances, f"{where}[{key!r}]")
        return
    if isinstance(expected, (list, tuple)):
        items = list(np.asarray(actual)) if isinstance(actual, np.ndarray) else list(actual)
        assert len(items) == len(expected), f"{where}: {len(items)} items, the page shows {len(expected)}"
        for k, (a, e) in enumerate(zip(items, expected)):
            _matches(a, e, tolerances, f"{where}[{k}]")
        return
    raise AssertionError(f"{where}: cannot compare with {expected!r}")


def _check_value(value, claim, where):
    expected, source = _literal(claim)
    # Numbers inside strings are not numbers: mask them before counting digits.
    masked = re.sub(r"'[^']*'|\"[^\"]*\"", "''", source)
    _matches(value, expected, _tolerances(masked), where)


def _expect(kind, claim):
    """(exception or warning class, the text its message must hold) of a `warns`/`raises` claim."""
    name, _, text = claim.partition(":")
    cls = getattr(flexure, name.strip(), None) or getattr(builtins, name.strip(), None)
    assert isinstance(cls, type) and issubclass(cls, BaseException), f"`{kind} {name}` names no class"
    return cls, text.split("…")[0].strip()


def run_snippet(code, first_line, page="python.md"):
    comments = _comments(code)
    tree = ast.parse(code)
    namespace = {"__name__": "__doc_snippet__"}
    for stmt in tree.body:
        where = f"docs/{page} line {first_line + stmt.lineno}"
        claims = [c for n in range(stmt.lineno, stmt.end_lineno + 1) for c in comments.get(n, [])]
        value_claim = next((c[2:].strip() for c in claims if c.startswith("->")), None)
        warns = next((c[5:].strip() for c in claims if c.startswith("warns ")), None)
        raises = next((c[6:].strip() for c in claims if c.startswith("raises ")), None)
        is_expr = isinstance(stmt, ast.Expr)
        if value_claim is not None:
            assert is_expr, f"{where}: `# ->` on a statement that is not an expression"
        module = ast.Module(body=[stmt], type_ignores=[])
        if raises is not None:
            cls, text = _expect("raises", raises)
            with pytest.raises(cls) as info:
                exec(compile(module, "<" + page + ">", "exec"), namespace)
            assert text in str(info.value), f"{where}: {cls.__name__} says {str(info.value)!r}, not {text!r}"
            continue
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            if is_expr:
                value = eval(compile(ast.Expression(stmt.value), "<" + page + ">", "eval"), namespace)
            else:
                exec(compile(module, "<" + page + ">", "exec"), namespace)
        ours = [w for w in caught if issubclass(w.category, _WARNINGS)]
        if warns is not None:
            cls, text = _expect("warns", warns)
            assert any(issubclass(w.category, cls) and text in str(w.message) for w in ours), (
                f"{where}: expected {cls.__name__} holding {text!r}, got {[str(w.message) for w in ours]}"
            )
        else:
            assert not ours, f"{where}: warns what the page does not show: {[str(w.message) for w in ours]}"
        if value_claim is not None:
            _check_value(value, value_claim, where)


SNIPPETS = [block for page in PAGES for block in snippets(page)]


def test_the_pages_have_their_snippets():
    # Eight blocks on python.md and one on export.md at the time of writing: fewer would
    # mean the extraction lost some.
    found = {page: sum(1 for p, _, _ in SNIPPETS if p == page) for page in PAGES}
    assert found["python.md"] >= 8 and found["export.md"] >= 1, found


@pytest.mark.parametrize(
    "page,first_line,code", SNIPPETS, ids=[f"{page}:{line}" for page, line, _ in SNIPPETS]
)
def test_snippet_runs_as_the_page_shows(page, first_line, code, monkeypatch):
    monkeypatch.chdir(ROOT)
    run_snippet(code, first_line, page)


def test_the_checker_holds_numbers_to_their_digits():
    # Reference: the convention above. 0.5691 is 0.569098 rounded to 4 places, 0.5692 is not.
    _check_value(0.569098, "0.5691 rest", "t")
    with pytest.raises(AssertionError):
        _check_value(0.569098, "0.5692", "t")
    _check_value(np.array([1.0, 2.466e-3]), "[1.0, 2.466e-3] kg", "t")
    with pytest.raises(AssertionError):
        _check_value(np.array([1.0, 2.467e-3]), "[1.0, 2.466e-3]", "t")
    with pytest.raises(AssertionError):
        _check_value({"factor": 2.0, "status": "lost"}, "{'factor': 2.0}", "t")
    _check_value({"factor": 2.4674011, "status": "lost"}, "{'factor': 2.4674011, 'status': 'lost'}: pi^2/4", "t")
    with pytest.raises(AssertionError):
        _check_value((True, 0.133), "(False, 0.133)", "t")


def test_the_checker_holds_warnings_and_errors_to_the_page():
    strip = "import flexure\nf = flexure.Flexure(length=0.05, modulus=200e9, width=0.01, thickness=2e-4, yield_strength=1e7)\n"
    # A warning the page does not show fails; one it shows passes, with its text.
    with pytest.raises(AssertionError, match="warns what the page does not show"):
        run_snippet(strip + "f.deflect(fy=0.5)\n", 0)
    run_snippet(strip + "f.deflect(fy=0.5)  # warns YieldWarning: exceeds the yield strength 1e7 Pa\n", 0)
    with pytest.raises(AssertionError, match="expected YieldWarning"):
        run_snippet(strip + "f.deflect(fy=0.5)  # warns YieldWarning: a text it does not say\n", 0)
    with pytest.raises(AssertionError, match="expected StabilityWarning"):
        run_snippet(strip + "f.deflect(fy=0.001)  # warns StabilityWarning\n", 0)
    # An error the page shows must come, with its text; one it does not show fails the test.
    run_snippet(strip + "flexure.Flexure(length=-1.0)  # raises ValueError: length\n", 0)
    with pytest.raises(pytest.fail.Exception):
        run_snippet(strip + "flexure.Flexure(length=1.0)  # raises ValueError: length\n", 0)
    with pytest.raises(ValueError):
        run_snippet(strip + "flexure.Flexure(length=-1.0)\n", 0)
