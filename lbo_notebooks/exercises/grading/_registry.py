"""What every graded test shares: the registry of graders, their points, and the library made
unavailable to the answer of a *build it yourself* exercise.

A grader is a function of the student's answers (by the names the exercise's prompt defines) that
returns a :class:`Verdict`: the fraction of the exercise's points earned and a message. It runs in
a fresh Python process (``python -m lbo_notebooks.exercises.grading``), so nothing an answer cell
did to the kernel (patched checks, a patched NumPy, changed notebook variables) reaches it; it
rebuilds whatever the exercise is about from the prompt's definitions, and judges functions on
inputs the notebook never shows.

Examples
--------
>>> @grader("99-demo", kind="compute")
... def _demo(x):
...     return Verdict(1.0 if x == 2 else 0.0, "2 is the answer." if x == 2 else "Not 2.")
>>> GRADERS["99-demo"].points, GRADERS["99-demo"].names
(2, ('x',))
>>> del GRADERS["99-demo"]
"""

from __future__ import annotations

import functools
import importlib
import inspect
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

# Points by kind of exercise (docs/exercises.md, "Points"): what it takes, not how long the cell is.
# A build is the core of a lesson; a compute or explore needs the idea applied correctly; a
# prediction or a choice between explanations is formative (its visible check confirms a guess by
# design); a recap asks three questions, a point each (partial credit); a written explanation is
# graded by a person with the rubric in the instructor's cell.
POINTS = {"build": 5, "compute": 2, "explore": 2, "predict": 1, "choice": 1, "recap": 3, "written": 2}


@dataclass(frozen=True)
class Verdict:
    """A grader's judgement: ``fraction`` of the points in [0, 1], and why."""

    fraction: float
    message: str

    def __post_init__(self) -> None:
        if not 0.0 <= self.fraction <= 1.0:
            raise ValueError(f"fraction must lie in [0, 1], got {self.fraction}.")


@dataclass(frozen=True)
class Grader:
    exercise: str
    kind: str
    points: int
    names: tuple[str, ...]
    judge: Callable[..., Verdict]
    replaces: tuple[str, ...] = field(default=())


GRADERS: dict[str, Grader] = {}


def grader(exercise: str, *, kind: str, replaces: tuple[str, ...] = ()) -> Callable[[Callable[..., Verdict]], Callable[..., Verdict]]:
    """Register ``judge`` as the graded test of ``exercise``.

    Parameters
    ----------
    exercise : str
        The exercise id, ``"NN-name"``.
    kind : str
        One of :data:`POINTS`; it sets the exercise's points.
    replaces : tuple of str
        For a *build it yourself* exercise: the library's functions (``"module:attr"`` or
        ``"module:Class.method"``, also third-party ones such as ``"igl:cotmatrix"``) that the answer
        must not call. While the answer runs (:func:`student_call`), each raises :class:`LibraryUsed`.
    """
    if kind not in POINTS:
        raise ValueError(f"kind must be one of {tuple(POINTS)}, got {kind!r}.")

    def register(judge: Callable[..., Verdict]) -> Callable[..., Verdict]:
        if exercise in GRADERS:
            raise ValueError(f"exercise {exercise!r} has two graders.")
        names = tuple(inspect.signature(judge).parameters)
        GRADERS[exercise] = Grader(exercise, kind, POINTS[kind], names, judge, tuple(replaces))
        return judge
    return register


# --- the library made unavailable while the answer runs -------------------------------------------

class LibraryUsed(Exception):
    """An answer to a *build it yourself* exercise called the library function it replaces."""


_running_student = False
_used: list[str] = []


def _resolve(target: str) -> tuple[Any, str, Any] | None:
    """``"module:attr"`` or ``"module:Class.method"`` -> (owner, attribute name, original), or None
    when the module is not installed."""
    module_name, _, path = target.partition(":")
    try:
        owner: Any = importlib.import_module(module_name)
    except ImportError:
        return None
    *parents, attr = path.split(".")
    for part in parents:
        owner = getattr(owner, part)
    return owner, attr, owner.__dict__[attr] if isinstance(owner, type) else getattr(owner, attr)


def block(targets: tuple[str, ...]) -> None:
    """Make each target raise :class:`LibraryUsed` when called from :func:`student_call`.

    The original is replaced wherever it is bound: its own module, every loaded module of the
    package that imported it by name, and classes for methods. Call this before the answers are
    unpickled, so that a function pickled by reference resolves to the blocked one.
    """
    for target in targets:
        found = _resolve(target)
        if found is None:
            continue
        owner, attr, original = found
        if getattr(original, "__lbo_guard__", False):
            continue  # blocked already (an earlier grader in this process)
        is_static = isinstance(original, staticmethod)
        function = original.__func__ if isinstance(original, (staticmethod, classmethod)) else original
        label = target.replace(":", ".")

        @functools.wraps(function)
        def guard(*args: Any, __function: Any = function, __label: str = label, **kwargs: Any) -> Any:
            if _running_student:
                _used.append(__label)
                raise LibraryUsed(__label)
            return __function(*args, **kwargs)

        guard.__lbo_guard__ = True  # type: ignore[attr-defined]
        del guard.__wrapped__  # functools.wraps' way back to the original: not for the answer
        try:  # but the original's signature stays, for help() and inspect in the same process
            guard.__signature__ = inspect.signature(function)  # type: ignore[attr-defined]
        except (TypeError, ValueError):  # a C function without one
            pass
        replacement: Any = staticmethod(guard) if is_static else guard
        setattr(owner, attr, replacement)
        if isinstance(owner, type):
            continue
        # Rebind it wherever it is re-exported: in this package and in the target's own package
        # (pyFM.signatures re-exports pyFM.spectral's functions, say), so that every route to it,
        # and every function pickled by reference, finds the guard.
        packages = {"lbo_notebooks", target.partition(":")[0].partition(".")[0]}
        for name, module in list(sys.modules.items()):
            if module is None or name.partition(".")[0] not in packages:
                continue
            for key, value in list(vars(module).items()):
                if value is function:
                    setattr(module, key, guard)


@contextmanager
def _student() -> Iterator[None]:
    global _running_student
    _running_student, before = True, _running_student
    try:
        yield
    finally:
        _running_student = before


def student_call(function: Any, *args: Any) -> Any:
    """Call the student's function with the replaced library blocked.

    Returns what it returns; raises :class:`LibraryUsed` if it called a blocked function (even if
    it caught the exception), and ``feedback.Stop`` for a stub, a placeholder or an error of its own
    (as the visible checks' ``call_attempt``).
    """
    from ..feedback import Stop, call_attempt

    start = len(_used)
    stopped: Stop | None = None
    with _student():
        try:
            value = call_attempt(function, *args)
        except Stop as stop:
            stopped = stop
    used = _used[start:]
    if used:
        raise LibraryUsed(used[0])
    if stopped is not None:
        raise stopped
    return value


def from_feedback(feedback: Any) -> Verdict:
    """A visible check's :class:`~lbo_notebooks.exercises.Feedback`, run by a grader on inputs it
    rebuilt, as a verdict: full points when correct, else the check's status and hint."""
    from ..feedback import Stop

    if feedback.correct:
        return Verdict(1.0, feedback.message)
    raise Stop(feedback.status, feedback.message)


def recap_verdict(answers: list[Any] | tuple[Any, ...], judges: list[Any] | tuple[Any, ...]) -> Verdict:
    """A recap's partial credit: the fraction of its questions answered right, with the hints of the
    wrong ones only (never the right answers). ``judges`` return None for a right answer, else a
    hint (``feedback.pick`` and ``feedback.number_judge`` make them). Raises ``Stop`` when nothing is
    answered (not attempted) or nothing is right.

    Examples
    --------
    >>> from lbo_notebooks.exercises.feedback import pick
    >>> judges = [pick({"a": None, "b": "not b"})] * 3
    >>> verdict = recap_verdict(["a", "A ", "b"], judges)
    >>> round(verdict.fraction, 3), verdict.message
    (0.667, '2 of 3 right. Question 3: not b')
    """
    from ..feedback import NOT_ATTEMPTED, WRONG, Stop, is_placeholder, unanswered

    if unanswered(list(answers)) is not None or all(is_placeholder(a) for a in answers):
        raise Stop(NOT_ATTEMPTED, "Replace the `...` placeholders with your answers and run the cell again.")
    wrong = []
    for k, (answer, judge) in enumerate(zip(answers, judges), 1):
        if is_placeholder(answer) or unanswered(answer) is not None:
            hint: str | None = "not answered yet (still `...`)."
        else:
            try:
                hint = judge(answer)
            except Exception:  # noqa: BLE001 - an answer object the judge cannot even read
                hint = f"could not read your answer (a {type(answer).__name__})."
        if hint is not None:
            wrong.append(f"Question {k}: {hint}")
    right = len(answers) - len(wrong)
    if not wrong:
        return Verdict(1.0, f"Right, all {len(answers)}.")
    message = f"{right} of {len(answers)} right. " + " ".join(wrong)
    if right == 0:
        raise Stop(WRONG, message)
    return Verdict(right / len(answers), message)
