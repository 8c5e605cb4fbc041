"""The feedback of the exercises' self-checks, and revealing a solution on purpose.

A check (in the sibling modules, one per part of the series) runs the student's attempt inside
:func:`run_check`: it returns a :class:`Feedback` that says *correct*, *wrong* (with a hint) or
*not attempted*, displays it, and never raises. The helpers here turn an attempt into a number,
an array or a call result, or stop the check with :class:`Stop` and a message.

Examples
--------
>>> run_check("00-demo", False, lambda: "Right.").status
'correct'
>>> run_check("00-demo", False, lambda: require_attempt(...)).status
'not attempted'
"""

from __future__ import annotations

import html
import json
import os
import re
import signal
import threading
from contextlib import contextmanager
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "Feedback", "CORRECT", "WRONG", "NOT_ATTEMPTED", "MIME_TYPE", "solution", "Stop", "run_check",
    "require_attempt", "as_number", "call_attempt", "close_to", "same_values", "choose",
    "unanswered", "is_placeholder", "result", "pick", "number_judge", "recap", "solutions_available",
    "SELF_STUDY_MARKER", "ratio_one", "as_array", "named_option", "plain", "right", "CHECK_SECONDS",
]

CORRECT, WRONG, NOT_ATTEMPTED = "correct", "wrong", "not attempted"
MIME_TYPE = "application/vnd.lbo-notebooks.feedback+json"
"""Extra MIME type of the displayed feedback: ``{"exercise", "status"}``, for scripts that read outputs."""

_STYLE = {CORRECT: ("#1a7f37", "✔"), WRONG: ("#b42318", "✘"), NOT_ATTEMPTED: ("#8a6d00", "…")}


class Feedback:
    """The result of a check: exercise id, status and a message (which never gives the answer away).

    Attributes
    ----------
    exercise : str
        The exercise's id, e.g. ``"03-stiffness"`` (its cells in the notebook carry the grade ids
        ``"03-stiffness-answer"`` and ``"03-stiffness-check"``).
    status : {"correct", "wrong", "not attempted"}
    message : str
        One or two sentences, with inline code in backticks.

    Examples
    --------
    >>> fb = Feedback("01-edges", "wrong", "Off by a factor of two.")
    >>> fb.correct, fb.attempted
    (False, True)
    >>> print(fb)
    01-edges · wrong: Off by a factor of two.
    """

    __slots__ = ("exercise", "status", "message", "_shown_at")

    def __init__(self, exercise: str, status: str, message: str) -> None:
        if status not in _STYLE:
            raise ValueError(f"status must be one of {tuple(_STYLE)}, got {status!r}.")
        self.exercise, self.status, self.message = exercise, status, message
        self._shown_at: int | None = None

    @property
    def correct(self) -> bool:
        return self.status == CORRECT

    @property
    def attempted(self) -> bool:
        return self.status != NOT_ATTEMPTED

    def __str__(self) -> str:
        return f"{self.exercise} · {self.status}: {self.message}"

    def __repr__(self) -> str:
        return f"Feedback({self.exercise!r}, {self.status!r}, {self.message!r})"

    def _repr_html_(self) -> str:
        colour, mark = _STYLE[self.status]
        text = _inline_markdown(self.message)
        reveal = ("" if self.correct or not solutions_available() else
                  f' <span style="opacity: 0.6">(to see a solution: <code>exercises.solution("{html.escape(self.exercise)}")</code>)</span>')
        return (f'<div class="lbo-feedback" data-exercise="{html.escape(self.exercise)}" data-status="{self.status}" '
                f'style="border-left: 4px solid {colour}; padding: 2px 8px; margin: 2px 0">'
                f'<b style="color: {colour}">{mark} {self.status}</b> · exercise {html.escape(self.exercise)}: {text}{reveal}</div>')

    def _bundle(self) -> dict[str, Any]:
        return {"text/plain": str(self), "text/html": self._repr_html_(),
                MIME_TYPE: {"exercise": self.exercise, "status": self.status}}

    def _ipython_display_(self) -> None:
        # A check shows its feedback itself; returned as a cell's last value, it is not shown twice.
        shell = _shell()
        if shell is not None and self._shown_at == shell.execution_count:
            return
        _show(self)


_SUB = re.compile(r"(?<![\w\\])([A-Za-zα-ωΑ-Ω])_(\{[^{}]+\}|\([^()]+\)|[0-9A-Za-z]+)")
_SUP = re.compile(r"(?<=[\w)])\^(\{[^{}]+\}|\([^()]*(?:\([^()]*\)[^()]*)*\)|[0-9A-Za-z−-]+)")


def _inline_markdown(message: str) -> str:
    """A message's inline Markdown as HTML: `code`, **strong**, *emphasis*, and the subscripts and
    superscripts of formulas (λ_0, φ_{n−1}, s^(2(1−α))), never inside code.

    >>> _inline_markdown("Not *two*: `Phi.T @ A` gives λ_0 and Φ_{n-1}, e^(−λt).")
    'Not <em>two</em>: <code>Phi.T @ A</code> gives λ<sub>0</sub> and Φ<sub>n-1</sub>, e<sup>−λt</sup>.'
    """
    pieces = re.split(r"(`[^`]+`)", message)
    out = []
    for k, piece in enumerate(pieces):
        if k % 2:
            out.append(f"<code>{html.escape(piece[1:-1], quote=False)}</code>")
            continue
        text = html.escape(piece, quote=False)
        text = re.sub(r"\*\*([^*]+)\*\*", r"<b>\1</b>", text)
        text = re.sub(r"(?<![\w*])\*([^*\s](?:[^*]*[^*\s])?)\*(?![\w*])", r"<em>\1</em>", text)
        text = _SUB.sub(lambda m: f"{m.group(1)}<sub>{_unwrap(m.group(2))}</sub>", text)
        text = _SUP.sub(lambda m: f"<sup>{_unwrap(m.group(1))}</sup>", text)
        out.append(text)
    return "".join(out)


def _unwrap(group: str) -> str:
    return group[1:-1] if group[:1] in "{(" else group


def _shell() -> Any:
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover - IPython is a dependency of JupyterLab
        return None
    return get_ipython()


def _show(feedback: Feedback) -> None:
    shell = _shell()
    if shell is None:
        print(feedback)
        return
    from IPython.display import display

    display(feedback._bundle(), raw=True)
    feedback._shown_at = shell.execution_count


def result(exercise: str, status: str, message: str, show: bool) -> Feedback:
    feedback = Feedback(exercise, status, message)
    if show:
        _show(feedback)
    return feedback


# --- the answer as given -------------------------------------------------------------------------

_PLAIN_ITEMS = 10_000_000


def plain(x: Any) -> Any:
    """The answer as plain built-in data, read without running any method its own class defines.

    A subclass of ``str``, ``int``, ``float``, ``list``, ``tuple``, ``dict`` or of NumPy's array
    comes back as the base type with the same content, so that no override (a ``lower()`` that
    looks around, a ``__float__`` that never returns) runs while a check reads it; containers are
    read item by item (up to ten million items); anything else (a function, a mesh, a sparse
    matrix) is returned as it is.

    Examples
    --------
    >>> class Sly(str):
    ...     def lower(self): return "whatever the check wants"
    >>> type(plain(Sly("Double"))), plain([Sly("a"), (1, 2.5)])
    (<class 'str'>, ['a', (1, 2.5)])
    """
    budget = [_PLAIN_ITEMS]

    def read(x: Any, depth: int) -> Any:
        budget[0] -= 1
        if budget[0] < 0 or depth > 50:
            raise Stop(WRONG, "Your answer is nested too deeply or is too large to be an answer here.")
        if x is None or x is Ellipsis or x is NotImplemented or type(x) in (bool, int, float, complex, str):
            return x
        if isinstance(x, bool):
            return bool(x)
        if isinstance(x, int):
            return int.__int__(x)
        if isinstance(x, float):
            return float.__float__(x)
        if isinstance(x, complex):
            return complex(complex.real.__get__(x), complex.imag.__get__(x))
        if isinstance(x, str):
            return str.__str__(x)
        if isinstance(x, np.generic) and type(x).__module__ == "numpy":
            return x
        if isinstance(x, np.ndarray):
            array = np.ndarray.view(x, np.ndarray)
            if array.dtype != object:
                return array
            budget[0] -= array.size
            if budget[0] < 0:
                raise Stop(WRONG, "Your answer is too large to be an answer here.")
            items = [read(item, depth + 1) for item in array.reshape(-1).tolist()]
            out = np.empty(len(items), dtype=object)
            out[:] = items
            return out.reshape(array.shape)
        if isinstance(x, (list, tuple)):
            items = [read(item, depth + 1) for item in (list.__iter__(x) if isinstance(x, list) else tuple.__iter__(x))]
            return items if isinstance(x, list) else tuple(items)
        if isinstance(x, dict):
            return {read(key, depth + 1): read(value, depth + 1) for key, value in dict.items(x)}
        return x

    return read(x, 0)


def is_placeholder(x: Any) -> bool:
    return (x is None or x is Ellipsis or x is NotImplemented
            or (isinstance(x, str) and str.strip(str.__str__(x)) in ("", "...")))


def unanswered(x: Any) -> str | None:
    """Why ``x`` counts as not attempted (a message), or None if it is an attempt."""
    if is_placeholder(x):
        return "Replace the `...` placeholder with your answer and run the cell again."
    x = plain(x)
    parts = list(x.values()) if isinstance(x, dict) else list(x) if isinstance(x, (list, tuple)) else []
    if parts and all(is_placeholder(p) for p in parts):
        return "Replace the `...` placeholders with your answers and run the cell again."
    return None


class Stop(Exception):
    """Raised inside a check to finish it early with this feedback status and message."""

    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status, self.message = status, message


CHECK_SECONDS = 120.0
"""How long a check may run (``LBO_CHECK_SECONDS`` overrides it): an answer that never finishes (a
student function that loops, an object whose conversion to a number never returns) is reported
as wrong after that long instead of hanging the cell."""


class _Overtime(BaseException):
    """Raised into a check that ran past its time (a BaseException: the student's ``except
    Exception`` cannot swallow it)."""


@contextmanager
def _time_limit(seconds: float) -> Any:
    """Raise :class:`_Overtime` into the block after ``seconds`` of wall time, with a real-time
    interval timer; only where signals can be used (the main thread of a POSIX process, no timer
    of someone else's running), else the block runs unbounded."""
    usable = (hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
              and signal.getitimer(signal.ITIMER_REAL)[0] == 0)
    if not usable:
        yield
        return

    def overtime(signum: int, frame: Any) -> None:
        raise _Overtime

    previous = signal.signal(signal.SIGALRM, overtime)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _check_seconds() -> float:
    try:
        seconds = float(os.environ.get("LBO_CHECK_SECONDS", CHECK_SECONDS))
    except ValueError:
        return CHECK_SECONDS
    return seconds if np.isfinite(seconds) and seconds > 0 else CHECK_SECONDS


def run_check(exercise: str, show: bool, body: Callable[[], str]) -> Feedback:
    """Run a check's body: it returns the message of a correct answer or raises Stop. A body that
    runs past :data:`CHECK_SECONDS` ends as *wrong*: the answer did not finish."""
    seconds = _check_seconds()
    try:
        with _time_limit(seconds):
            message = body()
    except Stop as stop:
        return result(exercise, stop.status, stop.message, show)
    except _Overtime:
        return result(exercise, WRONG, f"The check stopped after {seconds:g} s: your answer (or a function it calls) "
                      "did not finish. Look for a loop that never ends, then run the cell again.", show)
    return result(exercise, CORRECT, message, show)


def require_attempt(x: Any) -> None:
    why = unanswered(x)
    if why is not None:
        raise Stop(NOT_ATTEMPTED, why)
    if isinstance(x, (Mapping, list, tuple)):
        parts = list(x.values()) if isinstance(x, Mapping) else list(x)
        if any(is_placeholder(p) for p in parts):
            raise Stop(WRONG, "Some parts are still `...`: fill in every part.")


def as_number(x: Any, what: str = "a number") -> float:
    x = plain(x)
    # Only types whose conversion runs no code of the answer's own (a Fraction or a Decimal is fine).
    if not (isinstance(x, (bool, int, float, complex, str, list, tuple, np.ndarray, np.generic))
            or type(x).__module__ in ("fractions", "decimal")):
        raise Stop(WRONG, f"Expected {what} (a finite float), got {_shown_type(x)}.")
    try:
        value = float(np.asarray(x, dtype=np.float64).reshape(()))
    except (TypeError, ValueError, OverflowError, ArithmeticError):
        raise Stop(WRONG, f"Expected {what} (a finite float), got {_shown_type(x)}.") from None
    except Exception as err:  # noqa: BLE001 - an object whose __float__ / __array__ raises
        raise Stop(WRONG, f"Expected {what}; turning your {_shown_type(x)} into a number raised {type(err).__name__}.") from None
    if not np.isfinite(value):
        raise Stop(WRONG, f"Expected {what}, got {value}.")
    return value


def _shown_type(x: Any) -> str:
    if isinstance(x, int) and not isinstance(x, bool) and abs(x) > 1e300:
        return "an integer too large for a float"
    return type(x).__name__


def as_array(value: Any, what: str, *, finite: bool = True) -> np.ndarray:
    """The student's answer as a float array (sparse matrices densified), or a 'wrong' stop."""
    import scipy.sparse as sp

    if sp.issparse(value):
        value = value.toarray()
    value = plain(value)
    if not isinstance(value, (bool, int, float, list, tuple, np.ndarray, np.generic)):
        raise Stop(WRONG, f"Expected {what}, got {type(value).__name__}.")
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        raise Stop(WRONG, f"Expected {what}, got {type(value).__name__}.") from None
    if finite and not np.all(np.isfinite(arr)):
        raise Stop(WRONG, "Your answer has NaN or infinite entries.")
    return arr


def named_option(value: Any, options: tuple[str, ...]) -> str | None:
    """The option ``value`` names, compared without case and spaces ("PCA+smooth" is "pca + smooth"), or None."""
    if not isinstance(value, str):
        return None
    key = "".join(str.split(str.__str__(value))).lower().replace("→", "->")
    return next((o for o in options if "".join(o.split()) == key), None)


def call_attempt(function: Any, *args: Any) -> Any:
    """Call the student's function; placeholders and stubs count as not attempted."""
    if is_placeholder(function):
        raise Stop(NOT_ATTEMPTED, "Write the function, then run the cell again.")
    if not callable(function):
        raise Stop(WRONG, f"Pass the function itself (without calling it); got {type(function).__name__}.")
    try:
        value = function(*args)
    except NotImplementedError:
        raise Stop(NOT_ATTEMPTED, "The function body is still the stub: write it, then run the cell again.") from None
    except (Exception, SystemExit) as err:  # the student's bug (even a sys.exit), reported, not raised
        raise Stop(WRONG, f"Your function raised {type(err).__name__}: {err}") from None
    if is_placeholder(value):
        raise Stop(NOT_ATTEMPTED, "Your function returns nothing: is its body still `...`, or is a `return` missing?")
    return value


def close_to(x: float, target: float, rtol: float = 1e-2) -> bool:
    return abs(x - target) <= rtol * abs(target)


class right(str):  # noqa: N801 - used like a marker: options = {"double": right("because ..."), ...}
    """The reason of the right choice, in a choice's ``options`` (where a wrong one has its hint).

    >>> choose("00-demo", "b", {"a": "not a", "b": right("b, because ...")}, show=False).message
    'Right: b, because ...'
    """


def _is_right(hint: Any) -> bool:
    return hint is None or isinstance(hint, right)


def _right_message(hint: Any) -> str:
    return f"Right: {hint}" if isinstance(hint, right) else "Right."


def choose(exercise: str, answer: Any, options: Mapping[str, str | None], show: bool) -> Feedback:
    """A multiple-choice answer: ``options`` maps each choice to its hint, the right one to its
    reason (:class:`right`; None: no reason). The answer is read as plain text, case and outer
    spaces ignored."""
    def body() -> str:
        require_attempt(answer)
        text = plain(answer)
        key = text.strip().lower() if isinstance(text, str) else None
        if key not in options:
            raise Stop(WRONG, "Answer with one of: " + ", ".join(f'"{o}"' for o in options) + ".")
        hint = options[key]
        if not _is_right(hint):
            raise Stop(WRONG, hint)
        return _right_message(hint)
    return run_check(exercise, show, body)

def same_values(m: np.ndarray, ref: np.ndarray, rtol: float = 1e-8) -> bool:
    return bool(np.abs(m - ref).max() <= rtol * max(np.abs(ref).max(), 1e-300))


def ratio_one(exercise: str, value: Any, below: str, above: str, show: bool, rtol: float = 1e-6) -> Feedback:
    """A check of a normalised constant that must come out as exactly 1 (to ``rtol``), as an
    eigenbasis's worst-case ratio for its own pair (W, A) does: hints for below and above."""
    def body() -> str:
        require_attempt(value)
        got = as_number(value)
        if abs(got - 1) <= rtol:
            return "Right: exactly 1, to round-off: each eigenbasis is optimal for its own pair (W, A)."
        if 0 < got < 0.1:
            raise Stop(WRONG, "Normalise: multiply by λ_n (`values[n]`, n the number of basis functions or constraints), so that the optimum reads 1.")
        raise Stop(WRONG, below if got < 1 else above)
    return run_check(exercise, show, body)


# --- several questions in one check --------------------------------------------------------------

def pick(options: Mapping[str, str | None]) -> Callable[[Any], str | None]:
    """A judge for one choice question, ``{choice: hint, or None for the right one}``: it returns the
    hint of a wrong choice, ``None`` for the right one (choices compared lower-case, trimmed)."""
    def judge(answer: Any) -> str | None:
        answer = plain(answer)
        key = str(answer).strip().lower() if isinstance(answer, (str, int, float)) else None
        if key not in options:
            return "answer with one of: " + ", ".join(f'"{o}"' for o in options) + "."
        hint = options[key]
        return None if _is_right(hint) else hint
    judge.reasons = {key: str(hint) for key, hint in options.items() if isinstance(hint, right)}  # type: ignore[attr-defined]
    return judge


def number_judge(target: float, near: list[tuple[float, str]], otherwise: str, rtol: float = 1e-3) -> Callable[[Any], str | None]:
    """A judge for one number question: ``None`` at ``target`` (relative ``rtol``), else the hint of the
    slip it matches, else ``otherwise``."""
    def judge(answer: Any) -> str | None:
        try:
            value = as_number(answer)
        except Stop as stop:
            return stop.message
        if close_to(value, target, rtol):
            return None
        return next((hint for slip, hint in near if close_to(value, slip, rtol)), otherwise)
    return judge


def recap(exercise: str, answers: list[Any], judges: list[Callable[[Any], str | None]], show: bool) -> Feedback:
    """Several questions in one check (a notebook's recap): correct when all are, else the hints of
    the wrong ones, never the right answers.

    Examples
    --------
    >>> judges = [pick({"a": None, "b": "not b"}), number_judge(2.0, [(4.0, "twice too large")], "no")]
    >>> recap("00-demo", ["a", 4.0], judges, show=False).message
    '1 of 2 right. Question 2: twice too large'
    """
    def body() -> str:
        require_attempt(answers)
        wrong = [f"Question {k}: {hint}" for k, (answer, judge) in enumerate(zip(answers, judges), 1)
                 if (hint := judge(answer)) is not None]
        if wrong:
            raise Stop(WRONG, f"{len(answers) - len(wrong)} of {len(answers)} right. " + " ".join(wrong))
        reasons = [f"({k}) {why}" for k, (answer, judge) in enumerate(zip(answers, judges), 1)
                   if (why := getattr(judge, "reasons", {}).get(str(plain(answer)).strip().lower()))]
        return f"Right, all {len(answers)}" + (": " + " ".join(reasons) if reasons else ".")
    return run_check(exercise, show, body)


# --- revealing a solution on purpose -------------------------------------------------------------

_REGION = re.compile(r"^[ \t]*(?:#+|<!--)\s*BEGIN SOLUTION.*?$\n(.*?)^[ \t]*(?:#+|<!--)\s*END SOLUTION.*?$",
                     re.MULTILINE | re.DOTALL)


def _instructor_notebooks() -> Path | None:
    here = Path(__file__).resolve().parents[2] / "notebooks"
    return here if here.is_dir() else None


SELF_STUDY_MARKER = ".edition.json"
"""The file ``./make.sh student`` writes into the self-study edition's folder (the edition's manifest):
where it sits, :func:`solution` reveals solutions on request."""


def solutions_available() -> bool:
    """Whether :func:`solution` reveals anything here: in the instructor edition (the kernel runs in
    the checkout's ``notebooks/``) and in the self-study edition (its folder holds
    :data:`SELF_STUDY_MARKER`), never in a graded course's release, nor without the checkout.
    ``LBO_NOTEBOOKS_SOLUTIONS=1`` or ``0`` decides instead (a lecturer's own notebooks).

    Examples
    --------
    >>> import os; os.environ["LBO_NOTEBOOKS_SOLUTIONS"] = "0"
    >>> solutions_available()
    False
    >>> del os.environ["LBO_NOTEBOOKS_SOLUTIONS"]
    """
    folder = _instructor_notebooks()
    if folder is None:
        return False
    decided = os.environ.get("LBO_NOTEBOOKS_SOLUTIONS")
    if decided in ("0", "1"):
        return decided == "1"
    here = Path.cwd().resolve()
    return here == folder.resolve() or (here / SELF_STUDY_MARKER).is_file()


def solution(exercise: str, *, show: bool = True) -> str | None:
    """The instructor's solution of one exercise, on purpose: try first, then look.

    Only where :func:`solutions_available` (the instructor and self-study editions). Reads the solution regions (``### BEGIN SOLUTION`` ... ``### END SOLUTION``) of the cells with
    the grade id ``<exercise>-answer`` (and ``<exercise>-explain``) in the instructor edition,
    ``notebooks/`` of the checkout the package is installed from. The student edition has no
    solutions in it; where no checkout is at hand (a handed-out edition), this says so.

    Parameters
    ----------
    exercise : str
        The exercise id shown by its check, e.g. ``"03-mass"``.
    show : bool
        Display the solution (as Markdown in Jupyter, as text elsewhere).

    Returns
    -------
    str or None
        The solution's text with ``show=False``; ``None`` once it has been displayed (so that
        Jupyter does not show it a second time as the cell's value).

    Examples
    --------
    >>> import os; os.environ["LBO_NOTEBOOKS_SOLUTIONS"] = "1"
    >>> "BEGIN SOLUTION" not in solution("03-scaling", show=False)
    True
    >>> os.environ["LBO_NOTEBOOKS_SOLUTIONS"] = "0"
    >>> solution("03-scaling", show=False).startswith("Solutions are not shown in a graded course")
    True
    >>> del os.environ["LBO_NOTEBOOKS_SOLUTIONS"]
    """
    if not isinstance(exercise, str) or not re.fullmatch(r"\d\d-[a-z0-9]+(?:-[a-z0-9]+)*", exercise):
        raise ValueError(f"exercise must be an exercise id as its check shows it, such as \"03-mass\"; got {exercise!r}.")
    folder = _instructor_notebooks()
    if folder is None:
        text = "The solutions are not part of this edition (no instructor notebooks found next to the package)."
    elif not solutions_available():
        text = ("Solutions are not shown in a graded course: your lecturer hands them out after the deadline. "
                "Studying on your own? Open the self-study edition, `./make.sh student lab` (docs/exercises.md).")
    else:
        number = exercise.split("-", 1)[0]
        pieces = []
        for path in sorted(folder.glob(f"{number}_*.ipynb")):
            for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
                grade_id = cell.get("metadata", {}).get("nbgrader", {}).get("grade_id", "")
                if grade_id in (f"{exercise}-answer", f"{exercise}-explain"):
                    source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
                    if cell["cell_type"] == "markdown" and not _REGION.search(source):
                        pieces.append(source.strip())  # a written answer: the whole cell is the model answer
                        continue
                    for match in _REGION.finditer(source):
                        region = match.group(1)
                        if cell["cell_type"] != "code":
                            pieces.append(region.strip())
                            continue
                        if region[:1] in (" ", "\t"):  # a function body: show it under its def line
                            region = source[: match.start()] + region
                        pieces.append(f"```python\n{region.rstrip()}\n```")
        text = "\n\n".join(pieces) if pieces else f"No solution found for exercise {exercise!r}."
    if show:
        shell = _shell()
        if shell is None:
            print(text)
        else:
            from IPython.display import Markdown, display

            display(Markdown(f"**Solution of exercise {exercise}**\n\n{text}"))
        return None
    return text


